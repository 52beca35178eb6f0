// QuadRefiner: the front door of the quad-splitting schemes, Catmull-Clark
// (with OpenSubdiv's crease semantics) and bilinear, on polygons of any size.
//
//   auto refiner = QuadRefiner::create(topology, QuadScheme::kCatmullClark, options, {.levels = 3});
//   std::vector<Vec3> fine = refiner->refinePoints(basePoints);
//   auto limit = refiner->limitSurface(fine);
//
// Topology of every level is built once by create(); refinePoints() only
// applies weights, so moved control points are cheap to re-evaluate (the
// OpenSubdiv TopologyRefiner / PrimvarRefiner split, as LoopRefiner does).
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/mesh/surface_mesh.h"
#include "core/topology/level.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera::schemes {

enum class QuadScheme {
  kCatmullClark,
  kBilinear,  // face centroids, edge midpoints, vertices kept: no smoothing, no creases
};

class QuadRefiner {
 public:
  struct Uniform {
    int levels = 1;
    // Without it the finest level holds faces, sharpness and rules only:
    // enough for refinePoints() and controlSurface(), not for limits.
    bool fullTopologyInLastLevel = true;
    // Refuses refinements beyond this many quads at the finest level.
    long long maxFaces = 16LL * 1024 * 1024;
    std::function<void(int level, int levels)> onLevel = nullptr;
  };

  static Expected<QuadRefiner> create(const PolyTopology& topology, QuadScheme scheme,
                                      const CreaseOptions& options, const Uniform& uniform);

  QuadScheme scheme() const { return scheme_; }
  int maxLevel() const { return static_cast<int>(levels_.size()) - 1; }
  const Level& level(int l) const { return levels_[l]; }
  const Level& finestLevel() const { return levels_.back(); }

  // Points of the finest level from base points (one per base vertex).
  std::vector<Vec3> refinePoints(std::span<const Vec3> basePoints) const;
  // Points of every level, [0] being the base points.
  std::vector<std::vector<Vec3>> refinePointsPerLevel(std::span<const Vec3> basePoints) const;

  // The finest level's faces as triangles: each quad split along its first
  // diagonal, a larger polygon (level 0 only) fanned from its first corner.
  SurfaceMesh controlSurface(std::span<const Vec3> finestPoints) const;
  // Catmull-Clark only, on an all-quad finest level with full topology.
  Expected<SurfaceMesh> limitSurface(std::span<const Vec3> finestPoints) const;

 private:
  QuadRefiner() = default;
  void interpolate(int level, std::span<const Vec3> parent, std::span<Vec3> child) const;

  QuadScheme scheme_ = QuadScheme::kCatmullClark;
  CreaseOptions options_;
  std::vector<Level> levels_;
};

// Bilinear refinement of vertex data (quad_split.h numbering).
void interpolateBilinear(const Level& parent, std::span<const Vec3> parentPoints,
                         std::span<Vec3> childPoints);

}  // namespace tessera::schemes
