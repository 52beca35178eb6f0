#include "client/cli/mesh_loading.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "client/cli/command_line.h"
#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"
#include "core/util/file_io.h"

namespace tessera::cli {

void addMeshInputOptions(CLI::App& app, MeshInputArgs& args) {
  app.add_option("IN", args.input,
                 "the base mesh: .obj .off .ply .stl .gltf .glb (Draco-compressed GLB too) .usda")
      ->required();
  app.add_option("--tags", args.tags, "feature tags: 'crease I J S' and 'corner I S' lines (docs/FORMATS.md)")
      ->type_name("FILE");
  app.add_flag("--triangulate", args.triangulate,
               "triangulate polygons with more than three corners (concave and non-planar ones too)");
  app.add_flag("--drop-unused", args.dropUnused,
               "drop vertices no face uses instead of refusing the mesh (--tags keeps the file's numbers)");
  app.add_option("--crease-angle", args.creaseAngle,
                 "make edges whose dihedral angle exceeds DEG degrees infinitely sharp (0 to 180)")
      ->check(degrees())
      ->type_name("DEG");
  app.add_option("--usd-prim", args.usdPrim,
                 ".usda: the Mesh prim to read, by path (/World/Cube) or name, when the layer has several")
      ->type_name("PATH");
  // The command as people type it ("doc new"), for notes on stderr.
  const CLI::App* parent = app.get_parent();
  args.command =
      (parent != nullptr && parent->get_parent() != nullptr ? parent->get_name() + " " : "") + app.get_name();
}

std::vector<std::string> givenTriangleImportOptions(const CLI::App& app) {
  std::vector<std::string> given;
  for (const char* name : {"--triangulate", "--drop-unused", "--crease-angle"}) {
    const CLI::Option* option = app.get_option_no_throw(name);
    if (option != nullptr && option->count() > 0) given.push_back(name);
  }
  return given;
}

void addSchemeOptions(CLI::App& app, SchemeArgs& args) {
  app.add_option("--crease-method", args.creaseMethod, "semi-sharp crease rule: uniform (default) or chaikin")
      ->check(oneOf({"uniform", "chaikin"}))
      ->type_name("M");
  app.add_option("--boundary", args.boundary, "boundary rule: edge-only (default) or edge-and-corner")
      ->check(oneOf({"edge-only", "edge-and-corner"}))
      ->type_name("B");
}

void addDocumentOptions(CLI::App& app, DocumentArgs& args) {
  app.add_option("--max-level", args.maxLevel, "deepest level edits may address (default 6)")
      ->check(wholeNumber())
      ->type_name("N");
  addSchemeOptions(app, args.scheme);
}

LoopOptions loopOptions(const SchemeArgs& args) {
  LoopOptions options;
  if (args.creaseMethod == "chaikin") options.creaseMethod = CreaseMethod::kChaikin;
  if (args.boundary == "edge-and-corner") options.boundary = BoundaryInterpolation::kEdgeAndCorner;
  return options;
}

DocumentOptions documentOptions(const DocumentArgs& args, int maxLevelDefault) {
  DocumentOptions options;
  options.loop = loopOptions(args.scheme);
  options.maxLevel = args.maxLevel >= 0 ? args.maxLevel : maxLevelDefault;
  return options;
}

ImportOptions importOptions(const MeshInputArgs& args) {
  ImportOptions options;
  options.triangulate = args.triangulate;
  options.dropUnused = args.dropUnused;
  options.creaseAngle = args.creaseAngle;
  options.usdPrim = args.usdPrim;
  return options;
}

Status withFileScheme(SchemeArgs& args, const std::string& boundary, const std::string& creaseMethod,
                      const std::string& file) {
  auto adopt = [&](std::string& given, const std::string& stated, const char* option, const char* tag) {
    if (stated.empty()) return Status::ok();
    if (given.empty()) {
      given = stated;
      return Status::ok();
    }
    if (given == stated) return Status::ok();
    return invalidArgument(std::string(option) + " " + given + ": " + file + " says " + stated + " (" + tag +
                           "); give the same, or none");
  };
  const bool usd = file.ends_with(".usda") || file.ends_with(".USDA");
  TESSERA_RETURN_IF_ERROR(
      adopt(args.boundary, boundary, "--boundary", usd ? "interpolateBoundary" : "t interpolateboundary"));
  return adopt(args.creaseMethod, creaseMethod, "--crease-method",
               usd ? "tessera:creaseMethod" : "t creasemethod");
}

Status withFileSubdivisionScheme(std::string& scheme, bool given, const std::string& stated,
                                 const std::vector<std::string>& accepted, const std::string& file) {
  if (stated.empty() || stated == "none") return Status::ok();
  if (given) {
    if (scheme == stated) return Status::ok();
    return invalidArgument("--scheme " + scheme + ": " + file + " says " + stated +
                           " (subdivisionScheme); give the same, or none");
  }
  if (std::find(accepted.begin(), accepted.end(), stated) == accepted.end())
    return unsupported(file + ": subdivisionScheme " + stated + " is not available here");
  scheme = stated;
  return Status::ok();
}

Expected<std::string> statedSchemeOf(const MeshInputArgs& args) {
  const std::string ext = std::filesystem::path(args.input).extension().string();
  if (ext != ".usda" && ext != ".USDA") return std::string();
  TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(args.input));
  TESSERA_ASSIGN_OR_RETURN(const PolygonSoup soup, importPolygonSoup(text, ext, args.input, args.usdPrim));
  return soup.scheme;
}

namespace {

// The tag file and the note on what the import did, after either reading.
Expected<BaseMesh> finishLoad(const MeshInputArgs& args, const ImportOptions& options,
                              Expected<ImportedMesh> read, ImportReport* report) {
  TESSERA_ASSIGN_OR_RETURN(ImportedMesh imported, std::move(read));
  // Tags name the file's vertices: renumbered like the mesh.
  if (!args.tags.empty())
    TESSERA_RETURN_IF_ERROR(applyTagFile(args.tags, imported.mesh, imported.report.renumbering));
  const std::string note = describeImport(imported.report, options);
  if (!note.empty())
    std::fprintf(stderr, "tessera %s: %s: %s\n", args.command.c_str(), args.input.c_str(), note.c_str());
  if (report) *report = std::move(imported.report);
  return std::move(imported.mesh);
}

}  // namespace

Expected<BaseMesh> loadMesh(const MeshInputArgs& args, ImportReport* report) {
  const ImportOptions options = importOptions(args);
  return finishLoad(args, options, importMeshWithReport(args.input, options), report);
}

Expected<BaseMesh> loadMeshFromSoup(const MeshInputArgs& args, PolygonSoup soup, ImportReport* report) {
  const ImportOptions options = importOptions(args);
  return finishLoad(args, options, importSoupWithReport(std::move(soup), args.input, options), report);
}

void addDocumentSchemeOption(CLI::App& app, std::string& scheme) {
  app.add_option("--scheme", scheme,
                 "loop (triangles) or catmull-clark (any polygons); default: catmull-clark when a face "
                 "is not a triangle, otherwise loop")
      ->check(oneOf({"loop", "catmull-clark"}))
      ->type_name("S");
}

}  // namespace tessera::cli
