#include "core/schemes/quad_refiner.h"

#include "core/mesh/sharpness.h"

#include <string>

#include "core/catmark/interpolate.h"
#include "core/catmark/quad_split.h"
#include "core/catmark/surfaces.h"
#include "core/schemes/bilinear_masks.h"

namespace tessera::schemes {

Expected<QuadRefiner> QuadRefiner::create(const PolyTopology& topology, QuadScheme scheme,
                                          const CreaseOptions& options, const Uniform& uniform) {
  if (uniform.levels < 0)
    return invalidArgument("level must be 0 or more, got " + std::to_string(uniform.levels));
  QuadRefiner refiner;
  refiner.scheme_ = scheme;
  refiner.options_ = options;
  // Bilinear has no creases: its base level ignores them (and boundary rules).
  TESSERA_ASSIGN_OR_RETURN(Level base, buildPolyLevel(topology, options));
  long long faces = static_cast<long long>(base.faceVertices.size());
  for (int l = 1; l < uniform.levels; ++l) {
    faces *= 4;
    if (faces > uniform.maxFaces) break;
  }
  if (uniform.levels > 0 && faces > uniform.maxFaces) {
    return invalidArgument("level " + std::to_string(uniform.levels) + " would make more than " +
                           std::to_string(uniform.maxFaces) + " quads (" + std::to_string(base.numFaces()) +
                           " base faces); choose a lower level");
  }
  refiner.levels_.reserve(uniform.levels + 1);
  refiner.levels_.push_back(std::move(base));
  for (int l = 1; l <= uniform.levels; ++l) {
    const SplitDetail detail = (l < uniform.levels || uniform.fullTopologyInLastLevel)
                                   ? SplitDetail::kFull
                                   : SplitDetail::kFacesOnly;
    refiner.levels_.push_back(splitToQuads(refiner.levels_.back(), options, detail));
    if (uniform.onLevel) uniform.onLevel(l, uniform.levels);
  }
  return refiner;
}

void QuadRefiner::interpolate(int level, std::span<const Vec3> parent, std::span<Vec3> child) const {
  if (scheme_ == QuadScheme::kBilinear) {
    interpolateBilinear(levels_[level], parent, child);
  } else {
    interpolateCatmark(levels_[level], levels_[level + 1], parent, child);
  }
}

std::vector<Vec3> QuadRefiner::refinePoints(std::span<const Vec3> basePoints) const {
  std::vector<Vec3> current(basePoints.begin(), basePoints.end()), next;
  for (int l = 0; l < maxLevel(); ++l) {
    next.resize(levels_[l + 1].numVertices);
    interpolate(l, current, next);
    current.swap(next);
  }
  return current;
}

std::vector<std::vector<Vec3>> QuadRefiner::refinePointsPerLevel(std::span<const Vec3> basePoints) const {
  std::vector<std::vector<Vec3>> points;
  points.emplace_back(basePoints.begin(), basePoints.end());
  for (int l = 0; l < maxLevel(); ++l) {
    std::vector<Vec3> next(levels_[l + 1].numVertices);
    interpolate(l, points.back(), next);
    points.push_back(std::move(next));
  }
  return points;
}

SurfaceMesh QuadRefiner::controlSurface(std::span<const Vec3> finestPoints) const {
  const Level& level = finestLevel();
  SurfaceMesh surface = polygonSurfaceOf(level, finestPoints);
  if (scheme_ != QuadScheme::kCatmullClark) return surface;  // bilinear has no sharp features
  // The cage's tags at this level (decayed from the base's): refined again
  // with them, by OpenSubdiv or by Tessera, it gives the same surface.
  for (Index e = 0; e < static_cast<Index>(level.edgeVertices.size()); ++e) {
    if (!isSmooth(level.edgeSharpness[e]))
      surface.creases.push_back({level.edgeVertices[e][0], level.edgeVertices[e][1], level.edgeSharpness[e]});
  }
  for (Index v = 0; v < level.numVertices; ++v) {
    if (!isSmooth(level.vertexSharpness[v])) surface.corners.push_back({v, level.vertexSharpness[v]});
  }
  surface.boundary =
      options_.boundary == BoundaryInterpolation::kEdgeAndCorner ? "edge-and-corner" : "edge-only";
  surface.creaseMethod = options_.creaseMethod == CreaseMethod::kChaikin ? "chaikin" : "uniform";
  return surface;
}

Expected<SurfaceMesh> QuadRefiner::limitSurface(std::span<const Vec3> finestPoints) const {
  if (scheme_ != QuadScheme::kCatmullClark) {
    return unsupported("bilinear subdivision has no limit to evaluate: its limit is its own control mesh");
  }
  return catmarkLimitSurfaceOf(finestLevel(), options_, finestPoints);
}

void interpolateBilinear(const Level& parent, std::span<const Vec3> p, std::span<Vec3> c) {
  const Index nV = parent.numVertices;
  const Index nF = parent.numFaces();
  for (Index v = 0; v < nV; ++v) c[v] = p[v];
  for (Index f = 0; f < nF; ++f) {
    auto fv = parent.faceVerticesOf(f);
    Vec3 sum(0, 0, 0);
    for (Index v : fv) sum += p[v];
    c[nV + f] = bilinear::facePointWeight(static_cast<int>(fv.size())) * sum;
  }
  for (Index e = 0; e < static_cast<Index>(parent.edgeVertices.size()); ++e) {
    const auto& ev = parent.edgeVertices[e];
    c[nV + nF + e] = bilinear::kEdgeEndWeight * (p[ev[0]] + p[ev[1]]);
  }
}

}  // namespace tessera::schemes
