// OpenSubdiv 3.5 as the oracle of Catmull-Clark and bilinear on polygons:
// Far::TopologyRefiner with SCHEME_CATMARK (or SCHEME_BILINEAR) refines the
// same faces and tags, PrimvarRefinerReal<double> interpolates and takes
// Limit() in double precision, and results are reported in Tessera's vertex
// numbering, found by following OpenSubdiv's parent-to-child relations level
// by level (never by assuming both number vertices alike).
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefiner.h>

#include "core/catmark/polygon_level.h"
#include "core/hierarchy/edit.h"
#include "core/schemes/quad_refiner.h"
#include "core/util/vec3.h"

namespace tessera::oracle {

struct OsdQuadLevel {
  std::vector<Vec3> points;          // refined control points, Tessera numbering
  std::vector<Vec3> limitPositions;  // PrimvarRefiner::Limit at this level
  std::vector<Vec3> limitTangent1;
  std::vector<Vec3> limitTangent2;
};

// Far's descriptor points into arrays owned here, built once per topology so
// that benchmarks time only OpenSubdiv's own work.
class OsdPolyInput {
 public:
  explicit OsdPolyInput(const PolyTopology& topology);
  const OpenSubdiv::Far::TopologyDescriptor& descriptor() const { return descriptor_; }

 private:
  std::vector<int> vertsPerFace_, indices_, creasePairs_, cornerIndices_;
  std::vector<float> creaseWeights_, cornerWeights_;
  OpenSubdiv::Far::TopologyDescriptor descriptor_;
};

// Throws std::runtime_error on any OpenSubdiv error.
std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> createOsdQuadRefiner(const OsdPolyInput& input,
                                                                       schemes::QuadScheme scheme,
                                                                       const CreaseOptions& options,
                                                                       int levels,
                                                                       bool fullTopologyInLastLevel);

// Points of the finest level, double weights throughout.
struct OsdDoublePoint {
  double x = 0, y = 0, z = 0;
  void Clear(void* = nullptr) { x = y = z = 0; }
  void AddWithWeight(const OsdDoublePoint& src, double w) {
    x += w * src.x;
    y += w * src.y;
    z += w * src.z;
  }
};
std::vector<OsdDoublePoint> interpolateOsdDouble(const OpenSubdiv::Far::TopologyRefiner& refiner,
                                                 std::span<const OsdDoublePoint> basePoints, int level);

// Changes the points of one level, in Tessera's numbering, before the next
// level is interpolated from them (an edit's offsets at that level).
using OsdLevelEdit = std::function<void(int level, std::vector<Vec3>& points)>;

// Results for levels 0..ours.maxLevel(); limit data for every level from
// `firstLimitLevel` on when withLimit (a level must be all quads for
// Limit()). With `edit`, each level's points are Far's interpolation of the
// edited level above, and `points` holds them after the level's own edit.
std::vector<OsdQuadLevel> refineQuadsWithOpenSubdiv(const PolyTopology& topology,
                                                    std::span<const Vec3> basePoints,
                                                    const CreaseOptions& options,
                                                    const schemes::QuadRefiner& ours, bool withLimit,
                                                    int firstLimitLevel, const OsdLevelEdit& edit = {});

// The base topology with the active base-level sharpness edits as its tags
// (each edge and vertex tagged once); `base` is its level 0. Throws
// std::invalid_argument as below.
PolyTopology taggedTopology(const PolyTopology& baseTopology, const Level& base, std::span<const Edit> edits);

// Far's levels for a document's base mesh with its `edits` (the active
// ones, Pulli & Lounsbery's semantics): base-level sharpness edits become
// tags of the base mesh (each edge and vertex tagged once), moves are added
// at their level in the local frame (core/loop/local_frame.h) of the
// level's interpolated points, before the next level is interpolated.
// Throws std::invalid_argument for what Far's tags cannot state: a
// sharpness edit below the base level, or a second tag of one element.
std::vector<OsdQuadLevel> refineEditedQuadsWithOpenSubdiv(const PolyTopology& topology,
                                                          std::span<const Vec3> basePoints,
                                                          const CreaseOptions& options,
                                                          const schemes::QuadRefiner& ours,
                                                          std::span<const Edit> edits);

}  // namespace tessera::oracle
