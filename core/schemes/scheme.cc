#include "core/schemes/scheme.h"

#include "core/schemes/butterfly.h"
#include "core/schemes/doo_sabin.h"
#include "core/schemes/quad_refiner.h"
#include "core/schemes/sqrt3.h"

namespace tessera::schemes {

const std::vector<std::string>& schemeNames() {
  static const std::vector<std::string> names = {"loop",      "catmull-clark", "bilinear",
                                                 "butterfly", "sqrt3",         "doo-sabin"};
  return names;
}

const char* schemeName(Scheme scheme) {
  return schemeNames()[static_cast<int>(scheme)].c_str();
}

Expected<Scheme> parseScheme(const std::string& name) {
  const auto& names = schemeNames();
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<Scheme>(i);
  }
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return invalidArgument("unknown scheme '" + name + "' (one of " + list + ")");
}

bool schemeTakesPolygons(Scheme scheme) {
  return scheme == Scheme::kCatmullClark || scheme == Scheme::kBilinear || scheme == Scheme::kDooSabin;
}

bool schemeHasCreases(Scheme scheme) {
  return scheme == Scheme::kLoop || scheme == Scheme::kCatmullClark;
}

std::string limitUnavailableReason(Scheme scheme) {
  switch (scheme) {
    case Scheme::kBilinear:
      return "bilinear subdivision's limit is its own control mesh: drop --limit";
    case Scheme::kButterfly:
      return "the Butterfly scheme interpolates: its vertices already lie on the limit surface, drop --limit";
    case Scheme::kDooSabin:
      return "Doo-Sabin's limit points belong to faces (their centroids), not to vertices: drop --limit";
    default:
      return "";
  }
}

namespace {

SurfaceMesh polygonSurface(const PolyTopology& t, std::vector<Vec3> points) {
  SurfaceMesh s;
  s.positions = std::move(points);
  for (int f = 0; f < t.numFaces(); ++f) {
    const int from = t.faceOffsets[f], to = t.faceOffsets[f + 1];
    s.addPolygon(std::span<const int>(t.indices.data() + from, static_cast<size_t>(to - from)));
  }
  return s;
}

}  // namespace

Expected<SurfaceMesh> refinePolygons(const PolygonMesh& mesh, const SchemeRequest& request) {
  if (const std::string why = limitUnavailableReason(request.scheme); request.limit && !why.empty()) {
    return unsupported(why);
  }
  switch (request.scheme) {
    case Scheme::kCatmullClark:
    case Scheme::kBilinear: {
      const QuadScheme quad =
          request.scheme == Scheme::kBilinear ? QuadScheme::kBilinear : QuadScheme::kCatmullClark;
      QuadRefiner::Uniform uniform;
      uniform.levels = request.levels;
      // Limits need the last level's rings; a Catmull-Clark cage's written
      // tags need its edges (QuadRefiner::controlSurface).
      uniform.fullTopologyInLastLevel = request.limit || quad == QuadScheme::kCatmullClark;
      uniform.maxFaces = request.maxFaces;
      TESSERA_ASSIGN_OR_RETURN(QuadRefiner refiner,
                               QuadRefiner::create(mesh.topology, quad, request.crease, uniform));
      const std::vector<Vec3> points = refiner.refinePoints(mesh.points);
      if (request.limit) return refiner.limitSurface(points);
      return refiner.controlSurface(points);
    }
    case Scheme::kDooSabin: {
      TESSERA_ASSIGN_OR_RETURN(PolygonRefinement refined,
                               refineDooSabin(mesh.topology, mesh.points, request.levels, request.maxFaces));
      return polygonSurface(refined.topology, std::move(refined.points));
    }
    default:
      return invalidArgument(std::string(schemeName(request.scheme)) + " does not refine polygons here");
  }
}

Expected<SurfaceMesh> refineTriangles(const BaseTopology& topology, std::span<const Vec3> points,
                                      const SchemeRequest& request) {
  if (const std::string why = limitUnavailableReason(request.scheme); request.limit && !why.empty()) {
    return unsupported(why);
  }
  if (request.scheme == Scheme::kButterfly) {
    TESSERA_ASSIGN_OR_RETURN(TriangleRefinement refined,
                             refineButterfly(topology, points, request.levels, request.maxFaces));
    return refined.surface();
  }
  if (request.scheme == Scheme::kSqrt3) {
    TESSERA_ASSIGN_OR_RETURN(TriangleRefinement refined,
                             refineSqrt3(topology, points, request.levels, request.maxFaces));
    SurfaceMesh surface = refined.surface();
    if (request.limit) surface.positions = sqrt3LimitPositions(refined.levels.back(), refined.points);
    return surface;
  }
  return invalidArgument(std::string(schemeName(request.scheme)) + " does not refine triangles here");
}

}  // namespace tessera::schemes
