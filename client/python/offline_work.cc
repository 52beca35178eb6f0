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

}  // namespace tessera::python
