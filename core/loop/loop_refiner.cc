#include "core/loop/loop_refiner.h"

#include <string>

#include "core/loop/interpolate.h"
#include "core/loop/limit.h"
#include "core/loop/refinement.h"
#include "core/mesh/vertex_normals.h"

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
    interpolateLevel(levels_[l], levels_[l + 1], current, next);
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
    interpolateLevel(levels_[l], levels_[l + 1], points.back(), next);
    points.push_back(std::move(next));
  }
  return points;
}

std::vector<std::array<int, 3>> LoopRefiner::finestTriangles() const {
  const Level& fine = finestLevel();
  return {fine.faceVertices.begin(), fine.faceVertices.end()};
}

SurfaceMesh LoopRefiner::controlSurface(std::span<const Vec3> finestPoints) const {
  SurfaceMesh surface;
  surface.positions.assign(finestPoints.begin(), finestPoints.end());
  surface.triangles = finestTriangles();
  surface.normals = areaWeightedVertexNormals(surface.positions, surface.triangles);
  return surface;
}

Expected<SurfaceMesh> LoopRefiner::limitSurface(std::span<const Vec3> finestPoints) const {
  if (!finestLevel().fullTopology) {
    return invalidArgument("limit evaluation needs the finest level's full topology");
  }
  SurfaceMesh surface;
  surface.positions.resize(finestPoints.size());
  surface.normals.resize(finestPoints.size());
  surface.triangles = finestTriangles();
  const Level& fine = finestLevel();
  computeLimit(fine, finestPoints, surface.positions, surface.normals);
  // Split vertices along creases and at corners: each further side gets a
  // copy of the vertex with its own limit normal, appended after the level's
  // vertices so that vertex numbering is unchanged.
  for (Index v = 0; v < fine.numVertices; ++v) {
    if (isSmoothLike(fine.vertexRules[v])) continue;
    auto ringF = fine.ringFacesOf(v);
    const int n = fine.valence(v);
    for (const LimitSector& sector : otherLimitSectors(fine, v, finestPoints)) {
      const int copy = static_cast<int>(surface.positions.size());
      surface.positions.push_back(surface.positions[v]);
      surface.normals.push_back(sector.normal);
      for (int k = sector.firstFace; k < sector.firstFace + sector.faceCount; ++k) {
        const int ring = k % n;
        surface.triangles[ringF[ring]][fine.ringFaceLocal[fine.ringOffsets[v] + ring]] = copy;
      }
    }
  }
  return surface;
}

}  // namespace tessera
