// tessera doc: hierarchical documents -- create, edit by script, inspect, export.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "client/cli/arguments.h"
#include "client/cli/commands.h"
#include "client/cli/mesh_loading.h"
#include "core/document/document_file.h"
#include "core/document/edit_script.h"
#include "core/tessellation/tessellation.h"

namespace tessera::cli {

namespace {

constexpr const char* kHelp =
    "usage: tessera doc <new|edit|info|export> ...\n"
    "\n"
    "  doc new IN [--tags FILE] [--triangulate] [--max-level N] [--crease-method M]\n"
    "          [--boundary B] -o DOC          create a document from a base mesh\n"
    "  doc edit DOC --script FILE               apply an edit script (all or nothing)\n"
    "  doc info DOC                             base mesh, options and the edit history\n"
    "  doc export DOC --level N [--limit] [--draco] -o OUT\n"
    "                                           write the surface at level N (.obj .ply .glb)\n"
    "  doc export DOC --adaptive [--base-level N] [--max-level N] [--angle DEG] [--draco] -o OUT\n"
    "                                           write the adaptive, crack-free limit tessellation\n"
    "                                           (defaults: base level 2, max level 5, 10 degrees)\n"
    "\n"
    "Edit scripts: one command per line ('#' comments), ids as 'doc info' prints them:\n"
    "  move v2:40 [v2:41 ...] to X Y Z     put v2:40's limit at X Y Z; others move alike\n"
    "  offset v3:7 [...] by DX DY DZ       displace control points\n"
    "  crease e1:5 S                       edge sharpness at that level (S or inf)\n"
    "  corner v4:900 S                     vertex sharpness (0 smooth, > 0 corner or cusp)\n"
    "  undo N | redo N | remove N          by edit id\n"
    "";

int fail(const char* command, const Status& status) {
  std::fprintf(stderr, "tessera doc %s: %s\n", command, status.toString().c_str());
  return 1;
}

int usage(const std::string& message) {
  std::fprintf(stderr, "tessera doc: %s\n\n%s", message.c_str(), kHelp);
  return 2;
}

int runNew(const Arguments& args) {
  if (args.positional.size() != 1) return usage("doc new expects one input mesh");
  const std::string* out = args.option("--output");
  if (!out) return usage("doc new needs -o DOC");
  DocumentOptions options;
  if (const std::string* level = args.option("--max-level")) {
    auto parsed = parseLevel("--max-level", *level);
    if (!parsed.isOk()) return usage(parsed.status().message());
    options.maxLevel = *parsed;
  }
  if (const std::string* m = args.option("--crease-method")) {
    if (*m != "uniform" && *m != "chaikin") return usage("--crease-method expects uniform or chaikin");
    options.loop.creaseMethod = *m == "uniform" ? CreaseMethod::kUniform : CreaseMethod::kChaikin;
  }
  if (const std::string* b = args.option("--boundary")) {
    if (*b != "edge-only" && *b != "edge-and-corner") return usage("--boundary expects edge-only or edge-and-corner");
    options.loop.boundary = *b == "edge-only" ? BoundaryInterpolation::kEdgeOnly : BoundaryInterpolation::kEdgeAndCorner;
  }
  auto mesh = loadMesh(args.positional[0], args.option("--tags"), args.has("--triangulate"));
  if (!mesh.isOk()) return fail("new", mesh.status());
  auto doc = Document::create(*mesh, options);
  if (!doc.isOk()) return fail("new", doc.status().withContext(args.positional[0]));
  Status saved = saveDocument(*doc, *out);
  if (!saved.isOk()) return fail("new", saved);
  std::printf("wrote %s: %d vertices, %zu faces, max level %d\n", out->c_str(), doc->baseTopology().numVertices,
              doc->baseTopology().triangles.size(), options.maxLevel);
  return 0;
}

int runEdit(const Arguments& args) {
  if (args.positional.size() != 1) return usage("doc edit expects one document");
  const std::string* script = args.option("--script");
  if (!script) return usage("doc edit needs --script FILE");
  auto doc = loadDocument(args.positional[0]);
  if (!doc.isOk()) return fail("edit", doc.status());
  std::ifstream in(*script);
  if (!in) return fail("edit", notFound(*script + ": cannot open the script"));
  std::stringstream text;
  text << in.rdbuf();
  auto result = applyEditScript(text.str(), *script, *doc);
  if (!result.isOk()) return fail("edit", result.status());
  Status saved = saveDocument(*doc, args.positional[0]);
  if (!saved.isOk()) return fail("edit", saved);
  std::printf("applied %d commands; %zu edits in %s\n", result->commands, doc->edits().size(),
              args.positional[0].c_str());
  return 0;
}

const char* kindName(const Edit& e) {
  if (std::holds_alternative<MoveEdit>(e.change)) return "move";
  if (std::holds_alternative<EdgeSharpnessEdit>(e.change)) return "crease";
  return "corner";
}

int runInfo(const Arguments& args) {
  if (args.positional.size() != 1) return usage("doc info expects one document");
  auto doc = loadDocument(args.positional[0]);
  if (!doc.isOk()) return fail("info", doc.status());
  const auto& o = doc->options();
  std::printf("document        %s\n", args.positional[0].c_str());
  std::printf("base            %d vertices, %llu edges, %zu faces\n", doc->baseTopology().numVertices,
              static_cast<unsigned long long>(doc->counts().edges(0)), doc->baseTopology().triangles.size());
  std::printf("scheme          loop, %s creases, %s boundary\n",
              o.loop.creaseMethod == CreaseMethod::kUniform ? "uniform" : "chaikin",
              o.loop.boundary == BoundaryInterpolation::kEdgeOnly ? "edge-only" : "edge-and-corner");
  std::printf("max level       %d (%llu faces there)\n", o.maxLevel,
              static_cast<unsigned long long>(doc->counts().faces(o.maxLevel)));
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
      std::printf("%s %g", c->edge.toString().c_str(), c->sharpness);
    } else {
      const auto& v = std::get<VertexSharpnessEdit>(e.change);
      std::printf("%s %g", v.vertex.toString().c_str(), v.sharpness);
    }
    std::printf("\n");
  }
  return 0;
}

Expected<LodProfile> profileFrom(const Arguments& args) {
  LodProfile profile{.baseLevel = 2, .maxLevel = 5, .angleThresholdDegrees = 10};
  if (const std::string* text = args.option("--base-level")) {
    TESSERA_ASSIGN_OR_RETURN(profile.baseLevel, parseLevel("--base-level", *text));
  }
  if (const std::string* text = args.option("--max-level")) {
    TESSERA_ASSIGN_OR_RETURN(profile.maxLevel, parseLevel("--max-level", *text));
  }
  if (const std::string* text = args.option("--angle")) {
    char* end = nullptr;
    profile.angleThresholdDegrees = std::strtod(text->c_str(), &end);
    if (text->empty() || *end != '\0') return invalidArgument("--angle expects degrees, got '" + *text + "'");
  }
  TESSERA_RETURN_IF_ERROR(profile.check());
  return profile;
}

int runAdaptiveExport(const Arguments& args) {
  const std::string* out = args.option("--output");
  if (!out) return usage("doc export needs -o OUT");
  if (args.option("--level") || args.has("--limit")) return usage("--adaptive replaces --level and --limit");
  auto profile = profileFrom(args);
  if (!profile.isOk()) return usage(profile.status().message());
  auto doc = loadDocument(args.positional[0]);
  if (!doc.isOk()) return fail("export", doc.status());
  auto tessellation = Tessellation::build(*doc, *profile);
  if (!tessellation.isOk()) return fail("export", tessellation.status().withContext(args.positional[0]));
  const SurfaceMesh surface = tessellation->surface();
  ExportOptions exportOptions;
  exportOptions.draco = args.has("--draco");
  Status written = exportMesh(surface, *out, exportOptions);
  if (!written.isOk()) return fail("export", written);
  std::printf("wrote %s: %zu vertices, %zu triangles in %zu regions (adaptive, %s)\n", out->c_str(),
              surface.positions.size(), surface.triangles.size(), tessellation->regions().size(),
              profile->key().c_str());
  return 0;
}

int runExport(const Arguments& args) {
  if (args.positional.size() != 1) return usage("doc export expects one document");
  if (args.has("--adaptive")) return runAdaptiveExport(args);
  const std::string* out = args.option("--output");
  const std::string* levelText = args.option("--level");
  if (!out || !levelText) return usage("doc export needs --level N and -o OUT");
  auto level = parseLevel("--level", *levelText);
  if (!level.isOk()) return usage(level.status().message());
  auto doc = loadDocument(args.positional[0]);
  if (!doc.isOk()) return fail("export", doc.status());
  auto surface = doc->surface(*level, args.has("--limit") ? SurfaceKind::kLimit : SurfaceKind::kControl);
  if (!surface.isOk()) return fail("export", surface.status().withContext(args.positional[0]));
  ExportOptions exportOptions;
  exportOptions.draco = args.has("--draco");
  Status written = exportMesh(*surface, *out, exportOptions);
  if (!written.isOk()) return fail("export", written);
  std::printf("wrote %s: %zu vertices, %zu triangles (level %d)\n", out->c_str(), surface->positions.size(),
              surface->triangles.size(), *level);
  return 0;
}

}  // namespace

int runDoc(const std::vector<std::string>& rawArgs) {
  if (rawArgs.empty() || rawArgs[0] == "--help" || rawArgs[0] == "-h") {
    std::fputs(kHelp, rawArgs.empty() ? stderr : stdout);
    return rawArgs.empty() ? 2 : 0;
  }
  const std::string sub = rawArgs[0];
  const std::vector<std::string> rest(rawArgs.begin() + 1, rawArgs.end());
  ArgumentSpec spec{{"--limit", "--draco", "--triangulate", "--adaptive"},
                    {"--tags", "--output", "--script", "--level", "--max-level", "--crease-method", "--boundary",
                     "--base-level", "--angle"}};
  auto args = parseArguments(rest, spec);
  if (!args.isOk()) return usage(args.status().message());
  if (args->has("--help")) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  if (sub == "new") return runNew(*args);
  if (sub == "edit") return runEdit(*args);
  if (sub == "info") return runInfo(*args);
  if (sub == "export") return runExport(*args);
  return usage("unknown doc command '" + sub + "'");
}

}  // namespace tessera::cli
