#include "client/cli/mesh_loading.h"

#include "client/cli/command_line.h"
#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"

namespace tessera::cli {

void addMeshInputOptions(CLI::App& app, MeshInputArgs& args) {
  app.add_option("IN", args.input, "the base mesh: .obj .off .ply .stl .gltf .glb (Draco-compressed GLB too)")
      ->required();
  app.add_option("--tags", args.tags, "feature tags: 'crease I J S' and 'corner I S' lines (docs/FORMATS.md)")
      ->type_name("FILE");
  app.add_flag("--triangulate", args.triangulate, "fan polygons with more than three corners into triangles");
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

Expected<BaseMesh> loadMesh(const MeshInputArgs& args) {
  ImportOptions options;
  options.triangulate = args.triangulate;
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, importMesh(args.input, options));
  if (!args.tags.empty()) TESSERA_RETURN_IF_ERROR(applyTagFile(args.tags, mesh));
  return mesh;
}

}  // namespace tessera::cli
