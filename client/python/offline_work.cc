#include "client/python/offline_work.h"

#include <utility>
#include <vector>

#include "core/io/tag_file.h"

namespace tessera::python {

namespace {

ImportOptions importOptions(const ImportArgs& a) {
  return {
      .triangulate = a.triangulate, .dropUnused = a.dropUnused, .creaseAngle = a.creaseAngle.value_or(-1)};
}

Expected<BaseMesh> withTags(Expected<ImportedMesh> imported, const ImportArgs& args) {
  if (!imported.isOk()) return imported.status();
  if (args.tags)
    TESSERA_RETURN_IF_ERROR(applyTagFile(*args.tags, imported->mesh, imported->report.renumbering));
  return std::move(imported->mesh);
}

}  // namespace

Expected<BaseMesh> baseMeshFromFile(const std::string& path, const ImportArgs& args) {
  return withTags(importMeshWithReport(path, importOptions(args)), args);
}

Expected<BaseMesh> baseMeshFromArrays(PolygonSoup soup, const ImportArgs& args) {
  return withTags(importSoupWithReport(std::move(soup), "arrays", importOptions(args)), args);
}

Expected<BaseMesh> baseMeshOf(SchemeSource source, const ImportArgs& args) {
  if (source.path) return baseMeshFromFile(*source.path, args);
  return baseMeshFromArrays(std::move(source.soup), args);
}

Expected<LoopOptions> loopOptionsNamed(const std::string& creaseMethod, const std::string& boundary) {
  LoopOptions o;
  if (creaseMethod == "chaikin")
    o.creaseMethod = CreaseMethod::kChaikin;
  else if (creaseMethod != "uniform")
    return invalidArgument("crease_method must be 'uniform' or 'chaikin'");
  if (boundary == "edge-and-corner")
    o.boundary = BoundaryInterpolation::kEdgeAndCorner;
  else if (boundary != "edge-only")
    return invalidArgument("boundary must be 'edge-only' or 'edge-and-corner'");
  return o;
}

Expected<SurfaceMesh> refineLoop(const BaseMesh& mesh, const LoopOptions& options, int level, bool limit) {
  if (level < 0) return invalidArgument("level must be 0 or more");
  TESSERA_ASSIGN_OR_RETURN(
      LoopRefiner refiner,
      LoopRefiner::create(mesh, options, {.levels = level, .fullTopologyInLastLevel = limit}));
  const std::vector<Vec3> points = refiner.refinePoints(mesh.positions());
  if (limit) return refiner.limitSurface(points);
  return refiner.controlSurface(points);
}

Expected<schemes::Scheme> checkSchemeArguments(const std::string& schemeName, const ImportArgs& args,
                                               bool defaultOptions, int level, bool limit) {
  TESSERA_ASSIGN_OR_RETURN(const schemes::Scheme scheme, schemes::parseScheme(schemeName));
  if (level < 0) return invalidArgument("level must be 0 or more");
  if (scheme == schemes::Scheme::kLoop) return scheme;
  if (!schemes::schemeHasCreases(scheme) && (args.tags || !defaultOptions))
    return invalidArgument(std::string("the ") + schemeName +
                           " scheme has no crease rules: no tags, crease_method or boundary");
  if (const std::string why = schemes::limitUnavailableReason(scheme); limit && !why.empty())
    return invalidArgument("limit: " + why);
  if (schemes::schemeTakesPolygons(scheme) && (args.triangulate || args.dropUnused || args.creaseAngle))
    return invalidArgument(
        std::string("triangulate, drop_unused and crease_angle are not available with the ") + schemeName +
        " scheme, which reads the polygons as they are");
  return scheme;
}

Expected<SurfaceMesh> refineScheme(const std::string& schemeName, SchemeSource source, const ImportArgs& args,
                                   const LoopOptions& options, bool defaultOptions, int level, bool limit) {
  TESSERA_ASSIGN_OR_RETURN(const schemes::Scheme scheme,
                           checkSchemeArguments(schemeName, args, defaultOptions, level, limit));
  if (scheme == schemes::Scheme::kLoop) {
    TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, baseMeshOf(std::move(source), args));
    return refineLoop(mesh, options, level, limit);
  }
  schemes::SchemeRequest request{.scheme = scheme, .levels = level, .limit = limit, .crease = options};
  if (schemes::schemeTakesPolygons(scheme)) {
    if (args.triangulate || args.dropUnused || args.creaseAngle)
      return invalidArgument(
          std::string("triangulate, drop_unused and crease_angle are not available with the ") + schemeName +
          " scheme, which reads the polygons as they are");
    const std::string tags = args.tags.value_or("");
    TESSERA_ASSIGN_OR_RETURN(schemes::PolygonMesh mesh,
                             source.path ? schemes::importPolygonMesh(*source.path, tags)
                                         : schemes::polygonMeshOf(std::move(source.soup), "arrays", tags));
    return schemes::refinePolygons(mesh, request);
  }
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, baseMeshOf(std::move(source), args));
  return schemes::refineTriangles(BaseTopology::fromBaseMesh(mesh), mesh.positions(), request);
}

}  // namespace tessera::python
