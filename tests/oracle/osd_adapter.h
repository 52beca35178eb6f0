// The OpenSubdiv side shared by the oracle tests and the benchmarks: a point
// type for PrimvarRefiner, Tessera's base topology and options turned into
// Far's descriptor and Sdc options, and uniform interpolation. OpenSubdiv is a
// test and benchmark dependency only; nothing under core/ includes this.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "core/loop/level_builder.h"
#include "core/loop/loop_options.h"
#include "core/util/vec3.h"

namespace tessera::oracle {

// Double-precision point; PrimvarRefiner's weights are float.
struct OsdPoint {
  double x = 0, y = 0, z = 0;
  void Clear(void* = nullptr) { x = y = z = 0; }
  void AddWithWeight(const OsdPoint& src, float w) {
    x += w * src.x;
    y += w * src.y;
    z += w * src.z;
  }
  Vec3 toVec3() const { return Vec3(x, y, z); }
  static OsdPoint from(const Vec3& p) { return {p[0], p[1], p[2]}; }
};

// Far's descriptor points into arrays owned here, built once per topology so
// that benchmarks time only OpenSubdiv's own work.
class OsdInput {
 public:
  explicit OsdInput(const BaseTopology& topology);
  const OpenSubdiv::Far::TopologyDescriptor& descriptor() const { return descriptor_; }

 private:
  std::vector<int> vertsPerFace_, indices_, creasePairs_, cornerIndices_;
  std::vector<float> creaseWeights_, cornerWeights_;
  OpenSubdiv::Far::TopologyDescriptor descriptor_;
};

// Throws std::runtime_error on any OpenSubdiv error (it would otherwise print
// to stdout and carry on).
std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> createOsdRefiner(const OsdInput& input,
                                                                   const LoopOptions& options, int levels,
                                                                   bool fullTopologyInLastLevel);

// Points of `level` from base points, through every level in between.
std::vector<OsdPoint> interpolateOsd(const OpenSubdiv::Far::TopologyRefiner& refiner,
                                     std::span<const OsdPoint> basePoints, int level);

}  // namespace tessera::oracle
