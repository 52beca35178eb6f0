// LoopRefiner: the front door of uniform Loop refinement with sharp features.
//
//   auto refiner = LoopRefiner::create(baseMesh, options, {.levels = 3});
//   std::vector<Vec3> fine = refiner->refinePoints(baseMesh.positions());
//   SurfaceMesh limit = refiner->limitSurface(fine);
//
// Topology of every level is built once by create(); refinePoints() and the
// limit functions only apply weights, so moved control points are cheap to
// re-evaluate (the OpenSubdiv TopologyRefiner / PrimvarRefiner split).
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "core/loop/level_builder.h"
#include "core/loop/loop_options.h"
#include "core/mesh/base_mesh.h"
#include "core/mesh/surface_mesh.h"
#include "core/topology/level.h"
#include "core/util/status.h"

namespace tessera {

class LoopRefiner {
 public:
  struct Uniform {
    int levels = 1;
    // Without it the finest level holds faces, sharpness and rules only:
    // enough for refinePoints() and controlSurface(), not for limits.
    bool fullTopologyInLastLevel = true;
    // Refuses refinements beyond this many triangles at the finest level.
    long long maxFaces = 16LL * 1024 * 1024;
    // Called after each level is built, for progress reports.
    std::function<void(int level, int levels)> onLevel = nullptr;
  };

  static Expected<LoopRefiner> create(const BaseMesh& mesh, const LoopOptions& options,
                                      const Uniform& uniform);
  static Expected<LoopRefiner> create(const BaseTopology& topology, const LoopOptions& options,
                                      const Uniform& uniform);

  int maxLevel() const { return static_cast<int>(levels_.size()) - 1; }
  const Level& level(int l) const { return levels_[l]; }
  const Level& finestLevel() const { return levels_.back(); }
  const LoopOptions& options() const { return options_; }

  // Points of the finest level from base points (one per base vertex).
  std::vector<Vec3> refinePoints(std::span<const Vec3> basePoints) const;
  // Points of every level, [0] being the base points.
  std::vector<std::vector<Vec3>> refinePointsPerLevel(std::span<const Vec3> basePoints) const;

  // Surfaces of the finest level (see surfaces.h); the limit surface needs
  // fullTopologyInLastLevel.
  SurfaceMesh controlSurface(std::span<const Vec3> finestPoints) const;
  Expected<SurfaceMesh> limitSurface(std::span<const Vec3> finestPoints) const;

 private:
  LoopRefiner() = default;

  LoopOptions options_;
  std::vector<Level> levels_;
};

}  // namespace tessera
