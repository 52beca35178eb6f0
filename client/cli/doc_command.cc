// tessera doc: hierarchical documents -- create, edit by script, inspect, export.
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "client/cli/command_line.h"
#include "client/cli/commands.h"
#include "client/cli/doc_edit.h"
#include "client/cli/doc_view.h"
#include "client/cli/human_format.h"
#include "client/cli/mesh_loading.h"
#include "core/document/document_cage.h"
#include "core/document/document_file.h"
#include "core/io/mesh_export.h"
#include "core/schemes/polygon_reader.h"
#include "core/tessellation/tessellation.h"
#include "core/util/file_io.h"

namespace tessera::cli {

namespace {

constexpr const char* kScriptHelp =
    "Edit scripts: one command per line ('#' comments), ids as 'doc info' prints them:\n"
    "  move v2:40 [v2:41 ...] to X Y Z     put v2:40's limit at X Y Z; others move alike\n"
    "  offset v3:7 [...] by DX DY DZ       displace control points\n"
    "  crease e1:5 S                       edge sharpness at that level (S or inf)\n"
    "  corner v4:900 S                     vertex sharpness (0 smooth, > 0 corner or cusp)\n"
    "  undo N | redo N | remove N          by edit id";

struct NewArgs {
  MeshInputArgs mesh;
  DocumentArgs document;
  std::string output;
  std::string scheme;  // empty: from the faces
  // Import options given that the polygon reader does not apply.
  std::vector<std::string> polygonUnsupported;
};

struct ExportArgs {
  std::string document, output;
  int level = -1;
  bool limit = false, draco = false, adaptive = false;
  int baseLevel = 2, maxLevel = 5;
  double angle = 10;
};

int reportNew(const NewArgs& args, const Document& doc) {
  Status saved = saveDocument(doc, args.output);
  if (!saved.isOk()) return fail("doc new", saved);
  std::printf("wrote %s: %s vertices, %s faces, %s, max level %d\n", args.output.c_str(),
              formatCount(doc.counts().vertices(0)).c_str(), formatCount(doc.counts().faces(0)).c_str(),
              documentSchemeName(doc.scheme()), doc.options().maxLevel);
  return 0;
}

// The polygons of the file as they are, for a Catmull-Clark document.
int runNewCatmark(const NewArgs& args, schemes::PolygonMesh mesh) {
  if (!args.polygonUnsupported.empty()) {
    return usage("doc new", args.polygonUnsupported.front() +
                                ": not available for a catmull-clark document, which reads the file's "
                                "polygons as they are");
  }
  DocumentArgs stated = args.document;
  if (Status s = withFileScheme(stated.scheme, mesh.boundary, mesh.creaseMethod, args.mesh.input); !s.isOk())
    return usage("doc new", s.message());
  DocumentOptions options = documentOptions(stated);
  options.scheme = DocumentScheme::kCatmullClark;
  auto doc = Document::create(std::move(mesh.topology), std::move(mesh.points), options);
  if (!doc.isOk()) return fail("doc new", doc.status().withContext(args.mesh.input));
  return reportNew(args, *doc);
}

// Loop's triangles, as the triangle import built them.
int runNewLoop(const NewArgs& args, Expected<BaseMesh> mesh, const ImportReport& report) {
  if (!mesh.isOk()) return fail("doc new", mesh.status());
  DocumentArgs stated = args.document;
  if (Status s = withFileScheme(stated.scheme, report.boundary, report.creaseMethod, args.mesh.input);
      !s.isOk())
    return usage("doc new", s.message());
  auto doc = Document::create(*mesh, documentOptions(stated));
  if (!doc.isOk()) return fail("doc new", doc.status().withContext(args.mesh.input));
  return reportNew(args, *doc);
}

int runNew(const NewArgs& given) {
  NewArgs args = given;
  // A .usda file states its scheme (subdivisionScheme; USD's fallback is
  // catmullClark): it chooses where --scheme does not.
  auto stated = statedSchemeOf(args.mesh);
  if (!stated.isOk()) return fail("doc new", stated.status());
  if (Status s = withFileSubdivisionScheme(args.scheme, !given.scheme.empty(), *stated,
                                           {"loop", "catmull-clark"}, args.mesh.input);
      !s.isOk())
    return usage("doc new", s.message());
  if (Status same = checkOutputIsNotInput(args.mesh.input, args.output); !same.isOk()) {
    return usage("doc new", same.message());
  }
  // Without --scheme, a file with faces that are not triangles becomes a
  // Catmull-Clark document (as OpenSubdiv and USD subdivide it), unless
  // --triangulate asks for Loop's triangles. An OBJ, OFF or PLY file is read
  // once, as polygons, and built into either.
  const bool catmark = args.scheme == "catmull-clark";
  const std::string extension = std::filesystem::path(args.mesh.input).extension().string();
  if (catmark && !readsPolygonSoup(extension)) {
    auto polygons = schemes::importPolygonMesh(args.mesh.input, args.mesh.tags, args.mesh.usdPrim);
    if (!polygons.isOk()) return fail("doc new", polygons.status());
    return runNewCatmark(args, std::move(*polygons));
  }
  if (catmark || (args.scheme.empty() && !args.mesh.triangulate && readsPolygonSoup(extension))) {
    auto text = readFile(args.mesh.input);
    if (!text.isOk()) return fail("doc new", text.status());
    auto soup = importPolygonSoup(*text, extension, args.mesh.input, args.mesh.usdPrim);
    if (!soup.isOk()) return fail("doc new", soup.status());
    const int others = countFacesNotTriangles(soup->faceOffsets);
    if (catmark || others > 0) {
      if (!catmark) {
        std::fprintf(stderr,
                     "tessera doc new: %s: %d of %d faces are not triangles: a catmull-clark document "
                     "(--scheme loop --triangulate for Loop's triangles)\n",
                     args.mesh.input.c_str(), others, soup->numFaces());
      }
      auto polygons = schemes::polygonMeshOf(std::move(*soup), args.mesh.input, args.mesh.tags);
      if (!polygons.isOk()) return fail("doc new", polygons.status());
      return runNewCatmark(args, std::move(*polygons));
    }
    ImportReport report;
    auto mesh = loadMeshFromSoup(args.mesh, std::move(*soup), &report);
    return runNewLoop(args, std::move(mesh), report);
  }
  ImportReport report;
  auto mesh = loadMesh(args.mesh, &report);
  return runNewLoop(args, std::move(mesh), report);
}

const char* kindName(const Edit& e) {
  if (std::holds_alternative<MoveEdit>(e.change)) return "move";
  if (std::holds_alternative<EdgeSharpnessEdit>(e.change)) return "crease";
  if (std::holds_alternative<InterpolationEdit>(e.change)) return "interp";
  return "corner";
}

int runInfo(const std::string& path) {
  auto doc = loadDocument(path);
  if (!doc.isOk()) return fail("doc info", doc.status());
  const auto& o = doc->options();
  std::printf("document        %s\n", path.c_str());
  std::printf("base            %s vertices, %s edges, %s faces\n",
              formatCount(doc->counts().vertices(0)).c_str(), formatCount(doc->counts().edges(0)).c_str(),
              formatCount(doc->counts().faces(0)).c_str());
  std::printf("scheme          %s, %s creases, %s boundary\n", documentSchemeName(doc->scheme()),
              o.loop.creaseMethod == CreaseMethod::kUniform ? "uniform" : "chaikin",
              o.loop.boundary == BoundaryInterpolation::kEdgeOnly ? "edge-only" : "edge-and-corner");
  std::printf("max level       %d (%s faces there)\n", o.maxLevel,
              formatCount(doc->counts().faces(o.maxLevel)).c_str());
  int active = 0;
  std::map<int, int> perLevel;
  for (const Edit& e : doc->edits()) {
    active += e.active ? 1 : 0;
    ++perLevel[e.level()];
  }
  std::printf("edits           %zu (%d active, %zu undone)\n", doc->edits().size(), active,
              doc->edits().size() - active);
  for (const auto& [level, count] : perLevel) std::printf("  level %-8d %d\n", level, count);
  for (const Edit& e : doc->edits()) {
    std::printf("  %-8s %-6s %s", e.id.toString().c_str(), kindName(e), e.active ? "" : "(undone) ");
    if (const auto* m = std::get_if<MoveEdit>(&e.change)) {
      for (const auto& off : m->offsets) std::printf("%s ", off.vertex.toString().c_str());
    } else if (const auto* c = std::get_if<EdgeSharpnessEdit>(&e.change)) {
      std::printf("%s %s", c->edge.toString().c_str(), formatSharpness(c->sharpness).c_str());
    } else if (const auto* t = std::get_if<InterpolationEdit>(&e.change)) {
      if (t->interpolating) {
        std::printf("%s tension %g", t->vertex.toString().c_str(), t->tension);
      } else {
        std::printf("%s off", t->vertex.toString().c_str());
      }
    } else {
      const auto& v = std::get<VertexSharpnessEdit>(e.change);
      std::printf("%s %s", v.vertex.toString().c_str(), formatSharpness(v.sharpness).c_str());
    }
    std::printf("\n");
  }
  return 0;
}

int runAdaptiveExport(const ExportArgs& args) {
  const LodProfile profile{
      .baseLevel = args.baseLevel, .maxLevel = args.maxLevel, .angleThresholdDegrees = args.angle};
  if (Status valid = profile.check(); !valid.isOk()) return usage("doc export", valid.message());
  auto doc = loadDocument(args.document);
  if (!doc.isOk()) return fail("doc export", doc.status());
  auto tessellation = Tessellation::build(*doc, profile);
  if (!tessellation.isOk()) return fail("doc export", tessellation.status().withContext(args.document));
  const SurfaceMesh surface = tessellation->surface();
  ExportOptions exportOptions;
  exportOptions.draco = args.draco;
  Status written = exportMesh(surface, args.output, exportOptions);
  if (!written.isOk()) return fail("doc export", written);
  std::printf("wrote %s: %s vertices, %s triangles in %s regions (adaptive: %s)\n", args.output.c_str(),
              formatCount(surface.positions.size()).c_str(), formatCount(surface.triangles.size()).c_str(),
              formatCount(tessellation->regions().size()).c_str(), profile.describe().c_str());
  return 0;
}

int runExport(const ExportArgs& args) {
  if (Status same = checkOutputIsNotInput(args.document, args.output); !same.isOk()) {
    return usage("doc export", same.message());
  }
  if (args.adaptive) return runAdaptiveExport(args);
  if (args.level < 0) return usage("doc export", "--level N is required (or --adaptive)");
  auto doc = loadDocument(args.document);
  if (!doc.isOk()) return fail("doc export", doc.status());
  // To USD, the control points are the cage they are: the level's tags and
  // the document's scheme with them (core/document/document_cage.h).
  auto surface = !args.limit && exportStatesScheme(args.output)
                     ? documentCage(*doc, args.level)
                     : doc->surface(args.level, args.limit ? SurfaceKind::kLimit : SurfaceKind::kControl);
  if (!surface.isOk()) return fail("doc export", surface.status().withContext(args.document));
  ExportOptions exportOptions;
  exportOptions.draco = args.draco;
  Status written = exportMesh(*surface, args.output, exportOptions);
  if (!written.isOk()) return fail("doc export", written);
  // The polygon formats keep a Catmull-Clark document's faces (mesh_export.h).
  const bool polygons = surface->numPolygons() > 0 && exportKeepsPolygons(args.output);
  std::printf("wrote %s: %s vertices, %s %s (level %d)\n", args.output.c_str(),
              formatCount(surface->positions.size()).c_str(),
              formatCount(polygons ? surface->numPolygons() : surface->triangles.size()).c_str(),
              polygons ? "polygons" : "triangles", args.level);
  return 0;
}

void addNew(CLI::App& doc, Action& action) {
  CLI::App* sub = doc.add_subcommand("new", "create a document from a base mesh");
  auto args = std::make_shared<NewArgs>();
  addMeshInputOptions(*sub, args->mesh);
  addDocumentOptions(*sub, args->document);
  addDocumentSchemeOption(*sub, args->scheme);
  sub->add_option("-o,--output", args->output, "the document file to write")->required()->type_name("DOC");
  onChosen(*sub, action, [args, sub] {
    args->polygonUnsupported = givenTriangleImportOptions(*sub);
    return runNew(*args);
  });
}

void addEdit(CLI::App& doc, Action& action) {
  CLI::App* sub = doc.add_subcommand(
      "edit", "apply an edit script to a document (all or nothing), under the server's bounds rule");
  sub->footer(kScriptHelp);
  auto args = std::make_shared<DocEditArgs>();
  sub->add_option("DOC", args->document, "the document file, rewritten in place")->required();
  sub->add_option("--script", args->script, "the edit script")->required()->type_name("FILE");
  sub->add_flag("--each", args->each,
                "each line on its own, as a server takes commands: refused lines are reported and skipped");
  onChosen(*sub, action, [args] { return runDocEdit(*args); });
}

void addView(CLI::App& doc, Action& action) {
  CLI::App* sub =
      doc.add_subcommand("view", "the tiles a camera would be sent, by level: triangles, bytes, errors");
  sub->footer("docs/VIEWS.md: tiles chosen by screen-space error.");
  auto args = std::make_shared<DocViewArgs>();
  sub->add_option("DOC", args->document, "the document file")->required();
  sub->add_option("--eye", args->eye, "where the camera is")->required()->type_name("X Y Z");
  sub->add_option("--target", args->target, "the point it looks at")->required()->type_name("X Y Z");
  sub->add_option("--up", args->up, "its up direction (default 0 1 0)")->type_name("X Y Z");
  sub->add_option("--fov", args->fovDegrees, "vertical field of view, degrees (default 50)")
      ->type_name("DEG");
  sub->add_option("--ortho", args->orthoHeight, "orthographic: the height in view")->type_name("HEIGHT");
  sub->add_option("--size", args->size, "viewport in pixels (default 390x844, a phone)")->type_name("WxH");
  sub->add_option("--tolerance", args->tolerance, "screen-space error allowed, pixels (default 1)")
      ->type_name("PX");
  sub->add_option("--budget", args->budget, "at most this many triangles (the tolerance rises)")
      ->type_name("N");
  onChosen(*sub, action, [args] { return runDocView(*args); });
}

void addInfo(CLI::App& doc, Action& action) {
  CLI::App* sub = doc.add_subcommand("info", "base mesh, options and the edit history of a document");
  auto document = std::make_shared<std::string>();
  sub->add_option("DOC", *document, "the document file")->required();
  onChosen(*sub, action, [document] { return runInfo(*document); });
}

void addExport(CLI::App& doc, Action& action) {
  CLI::App* sub = doc.add_subcommand("export", "write the surface at a level, or the adaptive tessellation");
  sub->footer(
      "With --level N: the control points (or, with --limit, the limit surface) at level N.\n"
      "With --adaptive: the crack-free adaptive limit tessellation of the LOD profile\n"
      "--base-level, --max-level, --angle (defaults 2, 5, 10 degrees).");
  auto args = std::make_shared<ExportArgs>();
  sub->add_option("DOC", args->document, "the document file")->required();
  sub->add_option("-o,--output", args->output,
                  ".obj, .off, .ply, .stl, .glb or .usda (chosen by extension; .usda without --limit: the "
                  "level's cage with its tags and scheme)")
      ->required()
      ->type_name("OUT");
  CLI::Option* level =
      sub->add_option("--level", args->level, "uniform level to write")->check(wholeNumber());
  CLI::Option* limit =
      sub->add_flag("--limit", args->limit, "limit positions and normals instead of control points");
  sub->add_flag("--draco", args->draco, "GLB only: compress with KHR_draco_mesh_compression");
  CLI::Option* adaptive = sub->add_flag("--adaptive", args->adaptive,
                                        "the adaptive, crack-free limit tessellation instead of a level");
  adaptive->excludes(level)->excludes(limit);
  const char* group = "Adaptive (with --adaptive)";
  sub->add_option("--base-level", args->baseLevel, "every face at least this fine (default 2)")
      ->check(wholeNumber())
      ->needs(adaptive)
      ->group(group);
  sub->add_option("--max-level", args->maxLevel, "never finer than this (default 5)")
      ->check(wholeNumber())
      ->needs(adaptive)
      ->group(group);
  sub->add_option("--angle", args->angle, "refine where limit normals differ more (degrees, default 10)")
      ->needs(adaptive)
      ->type_name("DEG")
      ->group(group);
  onChosen(*sub, action, [args] { return runExport(*args); });
}

}  // namespace

void addDocCommand(CLI::App& app, Action& action) {
  CLI::App* doc = app.add_subcommand("doc", "hierarchical documents with edits at any level");
  doc->require_subcommand(1);
  addNew(*doc, action);
  addEdit(*doc, action);
  addInfo(*doc, action);
  addExport(*doc, action);
  addView(*doc, action);
}

}  // namespace tessera::cli
