// tessera refine: uniform Loop refinement with sharp features, written as
// control points or as the limit surface with limit normals; --scheme picks
// another of the classic schemes (core/schemes/scheme.h).
#include <cstdio>
#include <memory>

#include "client/cli/commands.h"
#include "client/cli/human_format.h"
#include "client/cli/mesh_loading.h"
#include "core/io/mesh_export.h"
#include "core/loop/loop_refiner.h"
#include "core/schemes/scheme.h"
#include "core/topology/cage_tags.h"

namespace tessera::cli {

namespace {

struct RefineArgs {
  MeshInputArgs mesh;
  SchemeArgs scheme;
  int level = 0;
  bool limit = false;
  bool draco = false;
  std::string output;
  std::string schemeName = "loop";
  bool schemeGiven = false;  // --scheme on the command line (else a .usda file's may choose)
  // Import options given on the command line that the polygon reader of
  // the polygon schemes does not apply.
  std::vector<std::string> polygonUnsupported;
};

// Progress only where a person would wait for it.
constexpr long long kProgressFaces = 1'000'000;

Status writeSurface(const RefineArgs& args, const SurfaceMesh& surface) {
  ExportOptions exportOptions;
  exportOptions.draco = args.draco;
  TESSERA_RETURN_IF_ERROR(exportMesh(surface, args.output, exportOptions));
  // The polygon formats keep a polygon surface's faces (mesh_export.h).
  const bool polygons = surface.numPolygons() > 0 && exportKeepsPolygons(args.output);
  std::printf("wrote %s: %s vertices, %s %s (level %d%s)\n", args.output.c_str(),
              formatCount(surface.positions.size()).c_str(),
              formatCount(polygons ? surface.numPolygons() : surface.triangles.size()).c_str(),
              polygons ? "polygons" : "triangles", args.level, args.limit ? ", limit surface" : "");
  return Status::ok();
}

// Every scheme but Loop: polygons or triangles in, one refine call.
int runOtherScheme(const RefineArgs& args) {
  using namespace schemes;
  const Scheme scheme = parseScheme(args.schemeName).value();  // checked by the option
  const std::string name = schemeName(scheme);
  if (!schemeHasCreases(scheme)) {
    if (!args.mesh.tags.empty())
      return usage("refine", "--tags: the " + name + " scheme has no sharp features");
    if (!args.scheme.creaseMethod.empty() || !args.scheme.boundary.empty()) {
      return usage("refine",
                   std::string(args.scheme.creaseMethod.empty() ? "--boundary" : "--crease-method") +
                       ": the " + name + " scheme has no crease rules");
    }
  }
  if (const std::string why = limitUnavailableReason(scheme); args.limit && !why.empty()) {
    return usage("refine", "--limit: " + why);
  }
  SchemeRequest request;
  request.scheme = scheme;
  request.levels = args.level;
  request.limit = args.limit;
  Expected<SurfaceMesh> surface = invalidArgument("no input");
  if (schemeTakesPolygons(scheme)) {
    if (!args.polygonUnsupported.empty()) {
      return usage("refine", args.polygonUnsupported.front() + ": not available with --scheme " + name +
                                 ", which reads the file's polygons as they are");
    }
    auto mesh = importPolygonMesh(args.mesh.input, args.mesh.tags, args.mesh.usdPrim);
    if (!mesh.isOk()) return fail("refine", mesh.status());
    SchemeArgs stated = args.scheme;
    if (schemeHasCreases(scheme)) {
      if (Status s = withFileScheme(stated, mesh->boundary, mesh->creaseMethod, args.mesh.input); !s.isOk())
        return usage("refine", s.message());
    }
    request.crease = loopOptions(stated);
    surface = refinePolygons(*mesh, request);
  } else {
    auto mesh = loadMesh(args.mesh);
    if (!mesh.isOk()) return fail("refine", mesh.status());
    request.crease = loopOptions(args.scheme);
    surface = refineTriangles(BaseTopology::fromBaseMesh(*mesh), mesh->positions(), request);
  }
  if (!surface.isOk()) return fail("refine", surface.status().withContext(args.mesh.input));
  // A cage of the schemes USD names states it (subdivisionScheme); others
  // are written as plain polygon meshes.
  if (!args.limit && (scheme == Scheme::kCatmullClark || scheme == Scheme::kBilinear)) surface->scheme = name;
  if (Status written = writeSurface(args, *surface); !written.isOk()) return fail("refine", written);
  return 0;
}

int runRefine(const RefineArgs& given) {
  if (Status same = checkOutputIsNotInput(given.mesh.input, given.output); !same.isOk()) {
    return usage("refine", same.message());
  }
  // A .usda file states its scheme (subdivisionScheme; USD's fallback is
  // catmullClark): it chooses where --scheme does not.
  RefineArgs args = given;
  auto fileScheme = statedSchemeOf(args.mesh);
  if (!fileScheme.isOk()) return fail("refine", fileScheme.status());
  if (Status s = withFileSubdivisionScheme(args.schemeName, args.schemeGiven, *fileScheme,
                                           {"loop", "catmull-clark", "bilinear"}, args.mesh.input);
      !s.isOk())
    return usage("refine", s.message());
  if (args.schemeName != "loop") return runOtherScheme(args);
  ImportReport report;
  auto mesh = loadMesh(args.mesh, &report);
  if (!mesh.isOk()) return fail("refine", mesh.status());
  SchemeArgs stated = args.scheme;
  if (Status s = withFileScheme(stated, report.boundary, report.creaseMethod, args.mesh.input); !s.isOk())
    return usage("refine", s.message());

  LoopRefiner::Uniform uniform;
  uniform.levels = args.level;
  // A limit needs the finest level's edges and rings; so does a .usda cage,
  // whose tags are that level's edges (core/topology/cage_tags.h).
  uniform.fullTopologyInLastLevel = args.limit || exportStatesScheme(args.output);
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
  auto refiner = LoopRefiner::create(*mesh, loopOptions(stated), uniform);
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
    if (exportStatesScheme(args.output)) {
      // To USD, the finest level is the cage it is: its tags and scheme too.
      addCageTags(refiner->finestLevel(), surface);
      surface.boundary = stated.boundary == "edge-and-corner" ? "edge-and-corner" : "edge-only";
      surface.creaseMethod = stated.creaseMethod == "chaikin" ? "chaikin" : "uniform";
      surface.scheme = "loop";
    }
  }

  if (showProgress) std::fprintf(stderr, "tessera refine: writing %s\n", args.output.c_str());
  if (Status written = writeSurface(args, surface); !written.isOk()) return fail("refine", written);
  return 0;
}

}  // namespace

void addRefineCommand(CLI::App& app, Action& action) {
  CLI::App* refine = app.add_subcommand("refine", "Refine a base mesh (Loop or another scheme) and write it");
  refine->footer(
      "Refines IN N times with Loop's scheme and its sharp features (creases,\n"
      "corners, darts, cusps; OpenSubdiv 3.5 semantics) and writes OUT.\n"
      "--scheme catmull-clark (OpenSubdiv's creases too) and bilinear refine the\n"
      "polygons of an OBJ, OFF or PLY file as they are; doo-sabin too; butterfly\n"
      "and sqrt3 (closed meshes) refine triangles. The polygon schemes' faces\n"
      "(quads; Doo-Sabin's n-gons) stay polygons in OBJ, OFF and PLY; STL and\n"
      "GLB take triangles. --limit: loop, catmull-clark, sqrt3 (positions only).");
  auto args = std::make_shared<RefineArgs>();
  addMeshInputOptions(*refine, args->mesh);
  refine->add_option("--level", args->level, "refinement level, 0 or more")->required()->check(wholeNumber());
  refine
      ->add_option("-o,--output", args->output, ".obj, .off, .ply, .stl, .glb or .usda (chosen by extension)")
      ->required()
      ->type_name("OUT");
  refine->add_flag("--limit", args->limit,
                   "write limit positions and limit normals instead of control points");
  refine->add_flag("--draco", args->draco, "GLB only: compress with KHR_draco_mesh_compression");
  addSchemeOptions(*refine, args->scheme);
  refine
      ->add_option("--scheme", args->schemeName,
                   "loop (default), catmull-clark, bilinear, butterfly, sqrt3 or doo-sabin")
      ->check(oneOf(schemes::schemeNames()))
      ->type_name("S");
  onChosen(*refine, action, [args, refine] {
    args->polygonUnsupported = givenTriangleImportOptions(*refine);
    args->schemeGiven = refine->get_option("--scheme")->count() > 0;
    return runRefine(*args);
  });
}

}  // namespace tessera::cli
