// tessera refine: uniform Loop refinement with sharp features, written as
// control points or as the limit surface with limit normals.
#include <cstdio>
#include <memory>

#include "client/cli/commands.h"
#include "client/cli/human_format.h"
#include "client/cli/mesh_loading.h"
#include "core/io/mesh_export.h"
#include "core/loop/loop_refiner.h"

namespace tessera::cli {

namespace {

struct RefineArgs {
  MeshInputArgs mesh;
  SchemeArgs scheme;
  int level = 0;
  bool limit = false;
  bool draco = false;
  std::string output;
};

// Progress only where a person would wait for it.
constexpr long long kProgressFaces = 1'000'000;

int runRefine(const RefineArgs& args) {
  if (Status same = checkOutputIsNotInput(args.mesh.input, args.output); !same.isOk()) {
    return usage("refine", same.message());
  }
  auto mesh = loadMesh(args.mesh);
  if (!mesh.isOk()) return fail("refine", mesh.status());

  LoopRefiner::Uniform uniform;
  uniform.levels = args.level;
  uniform.fullTopologyInLastLevel = args.limit;
  // Stop multiplying once past the threshold: --level may be large (the
  // refiner then refuses it with a clear error).
  long long finestFaces = mesh->numFaces();
  for (int l = 0; l < args.level && finestFaces < kProgressFaces; ++l) finestFaces *= 4;
  const bool showProgress = finestFaces >= kProgressFaces;
  if (showProgress) {
    uniform.onLevel = [](int done, int total) {
      std::fprintf(stderr, "tessera refine: topology level %d/%d\n", done, total);
    };
  }
  auto refiner = LoopRefiner::create(*mesh, loopOptions(args.scheme), uniform);
  if (!refiner.isOk()) return fail("refine", refiner.status().withContext(args.mesh.input));
  if (showProgress) std::fprintf(stderr, "tessera refine: positions\n");
  auto points = refiner->refinePoints(mesh->positions());

  SurfaceMesh surface;
  if (args.limit) {
    if (showProgress) std::fprintf(stderr, "tessera refine: limit positions and normals\n");
    auto limitSurface = refiner->limitSurface(points);
    if (!limitSurface.isOk()) return fail("refine", limitSurface.status());
    surface = std::move(limitSurface).value();
  } else {
    surface = refiner->controlSurface(points);
  }

  ExportOptions exportOptions;
  exportOptions.draco = args.draco;
  if (showProgress) std::fprintf(stderr, "tessera refine: writing %s\n", args.output.c_str());
  Status written = exportMesh(surface, args.output, exportOptions);
  if (!written.isOk()) return fail("refine", written);
  std::printf("wrote %s: %s vertices, %s triangles (level %d%s)\n", args.output.c_str(),
              formatCount(surface.positions.size()).c_str(), formatCount(surface.triangles.size()).c_str(), args.level,
              args.limit ? ", limit surface" : "");
  return 0;
}

}  // namespace

void addRefineCommand(CLI::App& app, Action& action) {
  CLI::App* refine = app.add_subcommand("refine", "Loop-refine a base mesh with its sharp features and write it");
  refine->footer(
      "Refines IN N times with Loop's scheme and its sharp features (creases,\n"
      "corners, darts, cusps; OpenSubdiv 3.5 semantics) and writes OUT.");
  auto args = std::make_shared<RefineArgs>();
  addMeshInputOptions(*refine, args->mesh);
  refine->add_option("--level", args->level, "refinement level, 0 or more")->required()->check(wholeNumber());
  refine->add_option("-o,--output", args->output, ".obj, .ply or .glb (chosen by extension)")
      ->required()
      ->type_name("OUT");
  refine->add_flag("--limit", args->limit, "write limit positions and limit normals instead of control points");
  refine->add_flag("--draco", args->draco, "GLB only: compress with KHR_draco_mesh_compression");
  addSchemeOptions(*refine, args->scheme);
  onChosen(*refine, action, [args] { return runRefine(*args); });
}

}  // namespace tessera::cli
