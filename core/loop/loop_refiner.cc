#include "core/loop/loop_refiner.h"

#include <string>

#include "core/loop/interpolate.h"
#include "core/loop/refinement.h"
#include "core/loop/surfaces.h"

namespace tessera {

Expected<LoopRefiner> LoopRefiner::create(const BaseMesh& mesh, const LoopOptions& options,
                                          const Uniform& uniform) {
  return create(BaseTopology::fromBaseMesh(mesh), options, uniform);
}

Expected<LoopRefiner> LoopRefiner::create(const BaseTopology& topology, const LoopOptions& options,
                                          const Uniform& uniform) {
  const int levels = uniform.levels;
  const long long maxFaces = uniform.maxFaces;
  if (levels < 0) return invalidArgument("refinement level must be >= 0, got " + std::to_string(levels));
  long long faces = static_cast<long long>(topology.triangles.size());
  for (int l = 0; l < levels; ++l) {
    // Compare before multiplying, so that no budget can overflow the count.
    if (faces > maxFaces / 4) {
      return invalidArgument("level " + std::to_string(levels) + " would exceed the limit of " +
                             std::to_string(maxFaces) + " triangles (" +
                             std::to_string(topology.triangles.size()) + " base triangles)");
    }
    faces *= 4;
  }
  TESSERA_ASSIGN_OR_RETURN(Level base, buildBaseLevel(topology, options));
  LoopRefiner refiner;
  refiner.options_ = options;
  refiner.levels_.reserve(levels + 1);
  refiner.levels_.push_back(std::move(base));
  for (int l = 0; l < levels; ++l) {
    const bool last = (l + 1 == levels);
    const RefineDetail detail =
        (last && !uniform.fullTopologyInLastLevel) ? RefineDetail::kFacesOnly : RefineDetail::kFull;
    refiner.levels_.push_back(refineLevel(refiner.levels_.back(), options, detail));
    if (uniform.onLevel) uniform.onLevel(l + 1, levels);
  }
  return refiner;
}

std::vector<Vec3> LoopRefiner::refinePoints(std::span<const Vec3> basePoints) const {
  std::vector<Vec3> current(basePoints.begin(), basePoints.end());
  std::vector<Vec3> next;
  for (int l = 0; l < maxLevel(); ++l) {
    next.resize(levels_[l + 1].numVertices);
    interpolateLevel(levels_[l], options_, current, next);
    current.swap(next);
  }
  return current;
}

std::vector<std::vector<Vec3>> LoopRefiner::refinePointsPerLevel(std::span<const Vec3> basePoints) const {
  std::vector<std::vector<Vec3>> points;
  points.reserve(levels_.size());
  points.emplace_back(basePoints.begin(), basePoints.end());
  for (int l = 0; l < maxLevel(); ++l) {
    std::vector<Vec3> next(levels_[l + 1].numVertices);
    interpolateLevel(levels_[l], options_, points.back(), next);
    points.push_back(std::move(next));
  }
  return points;
}

SurfaceMesh LoopRefiner::controlSurface(std::span<const Vec3> finestPoints) const {
  return controlSurfaceOf(finestLevel(), finestPoints);
}

Expected<SurfaceMesh> LoopRefiner::limitSurface(std::span<const Vec3> finestPoints) const {
  return limitSurfaceOf(finestLevel(), finestPoints, options_.creaseMethod);
}

}  // namespace tessera
