#include "server/document/mesh_intake.h"

#include <algorithm>
#include <string>

#include "core/io/tag_file.h"
#include "core/schemes/polygon_reader.h"
#include "server/document/mesh_format.h"

namespace tessera::server {

namespace {

struct Names {
  std::string mesh, tags;
};

Names namesOf(const wire::CreateDocument& request) {
  return {request.file_name().empty() ? "mesh '" + request.name() + "'" : request.file_name(),
          request.tags_file_name().empty() ? "tags of '" + request.name() + "'" : request.tags_file_name()};
}

Expected<DocumentOptions> optionsOf(const wire::CreateDocument& request, int maxLevel) {
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
  return options;
}

// A Catmull-Clark document of the file's polygons as they are (the import
// options that change them are refused, as `tessera doc new` refuses them).
Expected<Document> catmarkDocument(const wire::CreateDocument& request, schemes::PolygonMesh mesh,
                                   const DocumentOptions& given) {
  const Names names = namesOf(request);
  for (auto [set, option] :
       {std::pair{request.triangulate(), "triangulate"}, std::pair{request.drop_unused(), "drop_unused"},
        std::pair{request.crease_by_angle(), "crease_by_angle"}}) {
    if (set) {
      return invalidArgument(std::string("create: ") + option +
                             " is not available for a catmull-clark document, which reads the file's "
                             "polygons as they are");
    }
  }
  if (!request.tags().empty())
    TESSERA_RETURN_IF_ERROR(schemes::applyPolygonTags(request.tags(), names.tags, mesh));
  DocumentOptions options = given;
  options.scheme = DocumentScheme::kCatmullClark;
  auto doc = Document::create(std::move(mesh.topology), std::move(mesh.points), options);
  if (!doc.isOk()) return doc.status().withContext(names.mesh);
  return doc;
}

Expected<ImportOptions> importOptionsOf(const wire::CreateDocument& request) {
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
  return import;
}

Expected<Document> loopDocument(const wire::CreateDocument& request, Expected<ImportedMesh> imported,
                                const DocumentOptions& options, ImportReport& report) {
  const Names names = namesOf(request);
  if (!imported.isOk()) return imported.status();
  BaseMesh& mesh = imported->mesh;
  report = imported->report;
  if (!request.tags().empty()) {
    TESSERA_ASSIGN_OR_RETURN(auto tags, parseTags(request.tags(), names.tags));
    // Tags name the file's vertices, renumbered like the mesh (drop_unused).
    TESSERA_RETURN_IF_ERROR(applyTags(tags, names.tags, mesh, report.renumbering));
  }
  auto doc = Document::create(mesh, options);
  if (!doc.isOk()) return doc.status().withContext(names.mesh);
  return doc;
}

}  // namespace

Expected<Document> importDocument(const wire::CreateDocument& request, int maxLevel, ImportReport& report) {
  const char* extension = meshExtensionOf(request.mesh_format());
  if (extension == nullptr) return invalidArgument("create: mesh_format is not set");
  const Names names = namesOf(request);
  TESSERA_ASSIGN_OR_RETURN(const DocumentOptions options, optionsOf(request, maxLevel));
  TESSERA_ASSIGN_OR_RETURN(const ImportOptions import, importOptionsOf(request));
  // The scheme, as `tessera doc new` chooses it: asked for, or Catmull-Clark
  // for a file with faces that are not triangles unless triangulated. The
  // file is read once, as polygons, and then built into either.
  const wire::SubdivisionScheme scheme = request.scheme();
  const bool catmark = scheme == wire::SUBDIVISION_SCHEME_CATMULL_CLARK;
  if (catmark && !readsPolygonSoup(extension)) {
    return invalidArgument(
        std::string("create: a catmull-clark document reads OBJ, OFF or PLY polygons, not ") + extension +
        " (" + names.mesh + ")");
  }
  if (catmark || (scheme == wire::SUBDIVISION_SCHEME_UNSPECIFIED && !request.triangulate() &&
                  readsPolygonSoup(extension))) {
    TESSERA_ASSIGN_OR_RETURN(PolygonSoup soup, importPolygonSoup(request.mesh(), extension, names.mesh));
    // A scheme the file states (USD's subdivisionScheme, docs/FORMATS.md
    // "USD") chooses where the request does not.
    const bool statedLoop = soup.scheme == "loop", statedCatmark = soup.scheme == "catmull-clark";
    if (catmark || statedCatmark || (!statedLoop && countFacesNotTriangles(soup.faceOffsets) > 0)) {
      TESSERA_ASSIGN_OR_RETURN(schemes::PolygonMesh polygons,
                               schemes::polygonMeshOf(std::move(soup), names.mesh, ""));
      return catmarkDocument(request, std::move(polygons), options);
    }
    return loopDocument(request, importSoupWithReport(std::move(soup), names.mesh, import), options, report);
  }
  return loopDocument(request, importMeshFromBytesWithReport(request.mesh(), extension, names.mesh, import),
                      options, report);
}

}  // namespace tessera::server
