// tessera refine: uniform Loop refinement with sharp features, written as
// control points or as the limit surface with limit normals.
#include <cstdio>

#include "client/cli/arguments.h"
#include "client/cli/commands.h"
#include "client/cli/mesh_loading.h"
#include "core/io/mesh_export.h"
#include "core/loop/loop_refiner.h"

namespace tessera::cli {

namespace {

constexpr const char* kHelp =
    "usage: tessera refine IN --level N [options] -o OUT\n"
    "\n"
    "Refines IN N times with Loop's scheme and its sharp features (creases,\n"
    "corners, darts, cusps; OpenSubdiv 3.5 semantics) and writes OUT.\n"
    "\n"
    "  IN                     .obj .off .ply .stl .gltf .glb\n"
    "  -o, --output OUT       .obj, .ply or .glb (chosen by extension)\n"
    "  --level N              refinement level, 0 or more\n"
    "  --limit                write limit positions and limit normals instead of control points\n"
    "  --tags FILE            feature tags: 'crease I J S' and 'corner I S' lines\n"
    "  --triangulate          fan polygons with more than three corners\n"
    "  --draco                GLB only: compress with KHR_draco_mesh_compression\n"
    "  --crease-method M      uniform (default) or chaikin\n"
    "  --boundary B           edge-only (default) or edge-and-corner\n";

// Progress only where a person would wait for it.
constexpr long long kProgressFaces = 1'000'000;

int fail(const Status& status) {
  std::fprintf(stderr, "tessera refine: %s\n", status.toString().c_str());
  return 1;
}

int usage(const std::string& message) {
  std::fprintf(stderr, "tessera refine: %s\n\n%s", message.c_str(), kHelp);
  return 2;
}

}  // namespace

int runRefine(const std::vector<std::string>& rawArgs) {
  ArgumentSpec spec{{"--limit", "--triangulate", "--draco"},
                    {"--level", "--tags", "--output", "--crease-method", "--boundary"}};
  auto args = parseArguments(rawArgs, spec);
  if (!args.isOk()) return usage(args.status().message());
  if (args->has("--help")) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  if (args->positional.size() != 1) return usage("expected one input mesh");
  if (!args->option("--level")) return usage("--level is required");
  if (!args->option("--output")) return usage("-o OUT is required");
  auto level = parseLevel("--level", *args->option("--level"));
  if (!level.isOk()) return usage(level.status().message());

  LoopOptions options;
  if (const std::string* m = args->option("--crease-method")) {
    if (*m == "uniform") options.creaseMethod = CreaseMethod::kUniform;
    else if (*m == "chaikin") options.creaseMethod = CreaseMethod::kChaikin;
    else return usage("--crease-method expects uniform or chaikin, got '" + *m + "'");
  }
  if (const std::string* b = args->option("--boundary")) {
    if (*b == "edge-only") options.boundary = BoundaryInterpolation::kEdgeOnly;
    else if (*b == "edge-and-corner") options.boundary = BoundaryInterpolation::kEdgeAndCorner;
    else return usage("--boundary expects edge-only or edge-and-corner, got '" + *b + "'");
  }

  auto mesh = loadMesh(args->positional[0], args->option("--tags"), args->has("--triangulate"));
  if (!mesh.isOk()) return fail(mesh.status());

  const bool limit = args->has("--limit");
  LoopRefiner::Uniform uniform;
  uniform.levels = *level;
  uniform.fullTopologyInLastLevel = limit;
  // Stop multiplying once past the threshold: --level may be large (the
  // refiner then refuses it with a clear error).
  long long finestFaces = mesh->numFaces();
  for (int l = 0; l < *level && finestFaces < kProgressFaces; ++l) finestFaces *= 4;
  const bool showProgress = finestFaces >= kProgressFaces;
  if (showProgress) {
    uniform.onLevel = [](int done, int total) {
      std::fprintf(stderr, "tessera refine: topology level %d/%d\n", done, total);
    };
  }
  auto refiner = LoopRefiner::create(*mesh, options, uniform);
  if (!refiner.isOk()) return fail(refiner.status().withContext(args->positional[0]));
  if (showProgress) std::fprintf(stderr, "tessera refine: positions\n");
  auto points = refiner->refinePoints(mesh->positions());

  SurfaceMesh surface;
  if (limit) {
    if (showProgress) std::fprintf(stderr, "tessera refine: limit positions and normals\n");
    auto limitSurface = refiner->limitSurface(points);
    if (!limitSurface.isOk()) return fail(limitSurface.status());
    surface = std::move(limitSurface).value();
  } else {
    surface = refiner->controlSurface(points);
  }

  ExportOptions exportOptions;
  exportOptions.draco = args->has("--draco");
  if (showProgress) std::fprintf(stderr, "tessera refine: writing %s\n", args->option("--output")->c_str());
  Status written = exportMesh(surface, *args->option("--output"), exportOptions);
  if (!written.isOk()) return fail(written);
  std::printf("wrote %s: %zu vertices, %zu triangles (level %d%s)\n", args->option("--output")->c_str(),
              surface.positions.size(), surface.triangles.size(), *level, limit ? ", limit surface" : "");
  return 0;
}

}  // namespace tessera::cli
