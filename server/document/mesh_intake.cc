#include "server/document/mesh_intake.h"

#include <algorithm>
#include <string>

#include "core/io/tag_file.h"
#include "server/document/mesh_format.h"

namespace tessera::server {

Expected<Document> importDocument(const wire::CreateDocument& request, int maxLevel, ImportReport& report) {
  const char* extension = meshExtensionOf(request.mesh_format());
  if (extension == nullptr) return invalidArgument("create: mesh_format is not set");
  const std::string meshName =
      request.file_name().empty() ? "mesh '" + request.name() + "'" : request.file_name();
  ImportOptions import;
  import.triangulate = request.triangulate();
  import.dropUnused = request.drop_unused();
  if (request.crease_by_angle()) {
    if (!(request.crease_angle() >= 0 && request.crease_angle() <= 180)) {
      return invalidArgument("create: crease_angle " + std::to_string(request.crease_angle()) +
                             " is outside 0 to 180 degrees");
    }
    import.creaseAngle = request.crease_angle();
  }
  TESSERA_ASSIGN_OR_RETURN(ImportedMesh imported,
                           importMeshFromBytesWithReport(request.mesh(), extension, meshName, import));
  BaseMesh& mesh = imported.mesh;
  report = imported.report;
  if (!request.tags().empty()) {
    const std::string tagsName =
        request.tags_file_name().empty() ? "tags of '" + request.name() + "'" : request.tags_file_name();
    TESSERA_ASSIGN_OR_RETURN(auto tags, parseTags(request.tags(), tagsName));
    // Tags name the file's vertices, renumbered like the mesh (drop_unused).
    TESSERA_RETURN_IF_ERROR(applyTags(tags, tagsName, mesh, report.renumbering));
  }
  DocumentOptions options;
  if (request.crease_method() == wire::CREASE_METHOD_CHAIKIN)
    options.loop.creaseMethod = CreaseMethod::kChaikin;
  if (request.boundary() == wire::BOUNDARY_INTERPOLATION_EDGE_AND_CORNER) {
    options.loop.boundary = BoundaryInterpolation::kEdgeAndCorner;
  }
  options.maxLevel = request.max_level() == 0 ? std::min(5, maxLevel) : static_cast<int>(request.max_level());
  if (options.maxLevel > maxLevel) {
    return invalidArgument("create: max level " + std::to_string(request.max_level()) +
                           " exceeds the server's " + std::to_string(maxLevel));
  }
  auto doc = Document::create(mesh, options);
  if (!doc.isOk()) return doc.status().withContext(meshName);
  return doc;
}

}  // namespace tessera::server
