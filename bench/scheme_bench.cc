// Catmull-Clark uniform refinement (topology + positions), limit evaluation
// and the sparse hierarchy held whole of a real mesh, Tessera against
// OpenSubdiv Far in the same run.
//
//   build/release/bench/tessera_bench_scheme [--mesh PATH] [benchmark flags]
//
// The *SemiSharp rows tag the mesh's feature edges (dihedral angle above
// 30 degrees: fandisk's creases) with sharpness 2.5, as an artist softens
// a model's edges, so that the limits of levels 0 to 2 near them take the
// decayed ring's exact masks (core/catmark/semi_sharp_limit.h), where
// OpenSubdiv's Limit() counts the edges as sharp.
//
// The mesh is read as polygons (OBJ/OFF) or triangles (other formats); fandisk
// (12,946 triangles, from libcgal-demo) by default. Both start from the same
// faces and double-precision points; OpenSubdiv uses TopologyRefinerFactory +
// RefineUniform + PrimvarRefiner::Interpolate (and ::Limit), SCHEME_CATMARK.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>
#include <opensubdiv/far/primvarRefiner.h>

#include "bench/ratio_reporter.h"
#include "core/catmark/limit.h"
#include "core/catmark/polygon_level.h"
#include "core/hierarchy/sparse_hierarchy.h"
#include "core/mesh/polygon_triangulation.h"
#include "core/schemes/polygon_reader.h"
#include "core/schemes/quad_refiner.h"
#include "core/util/heap_policy.h"
#include "oracle/osd_adapter.h"
#include "oracle/osd_catmark_reference.h"
#include "support/sparse_levels.h"

namespace {

using namespace tessera;
using namespace tessera::schemes;
namespace Far = OpenSubdiv::Far;
using oracle::OsdPoint;

struct Input {
  PolygonMesh mesh;
  std::vector<OsdPoint> osdPoints;
  std::unique_ptr<oracle::OsdPolyInput> osd;
  PolyTopology semiSharp;  // the mesh with its feature edges semi-sharp
  std::unique_ptr<oracle::OsdPolyInput> osdSemiSharp;
};

// Edges whose faces' normals differ by more than `degrees`, tagged with
// `sharpness`.
PolyTopology withSemiSharpFeatures(const PolygonMesh& mesh, double degrees, float sharpness) {
  PolyTopology out = mesh.topology;
  const auto& t = mesh.topology;
  std::map<std::pair<int, int>, std::vector<Vec3>> normals;
  for (int f = 0; f < t.numFaces(); ++f) {
    const int from = t.faceOffsets[f], n = t.faceOffsets[f + 1] - from;
    const Vec3 normal = polygonNormal(
        mesh.points, std::span(t.indices).subspan(static_cast<size_t>(from), static_cast<size_t>(n)));
    for (int j = 0; j < n; ++j) {
      const int a = t.indices[from + j], b = t.indices[from + (j + 1) % n];
      normals[{std::min(a, b), std::max(a, b)}].push_back(normal.normalized());
    }
  }
  const double limit = std::cos(degrees * 3.14159265358979323846 / 180.0);
  for (const auto& [edge, ns] : normals) {
    if (ns.size() == 2 && (ns[0] | ns[1]) < limit)
      out.creases.push_back({edge.first, edge.second, sharpness});
  }
  return out;
}

Input& input() {
  static Input in;
  return in;
}

std::unique_ptr<Far::TopologyRefiner> osdRefiner(int level, bool fullTopology, bool semiSharp = false) {
  return oracle::createOsdQuadRefiner(semiSharp ? *input().osdSemiSharp : *input().osd,
                                      QuadScheme::kCatmullClark, CreaseOptions{}, level, fullTopology);
}

const PolyTopology& topologyOf(bool semiSharp) {
  return semiSharp ? input().semiSharp : input().mesh.topology;
}

// Refine: the finest level gets faces only (OpenSubdiv's default).
void refineTessera(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto refiner = QuadRefiner::create(input().mesh.topology, QuadScheme::kCatmullClark, CreaseOptions{},
                                       {.levels = level, .fullTopologyInLastLevel = false});
    auto points = refiner->refinePoints(input().mesh.points);
    benchmark::DoNotOptimize(points.data());
  }
}

void refineOpenSubdiv(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto refiner = osdRefiner(level, false);
    auto points = oracle::interpolateOsd(*refiner, input().osdPoints, level);
    benchmark::DoNotOptimize(points.data());
  }
}

template <bool kSemiSharp>
void limitTessera(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  auto refiner = QuadRefiner::create(topologyOf(kSemiSharp), QuadScheme::kCatmullClark, CreaseOptions{},
                                     {.levels = level});
  auto points = refiner->refinePoints(input().mesh.points);
  std::vector<Vec3> positions(points.size()), normals(points.size());
  for (auto _ : state) {
    auto status = computeCatmarkLimit(refiner->finestLevel(), CreaseOptions{}, points, positions, normals);
    benchmark::DoNotOptimize(positions.data());
    if (!status.isOk()) state.SkipWithError(status.toString().c_str());
  }
}

template <bool kSemiSharp>
void limitOpenSubdiv(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  auto refiner = osdRefiner(level, true, kSemiSharp);
  auto points = oracle::interpolateOsd(*refiner, input().osdPoints, level);
  Far::PrimvarRefiner primvar(*refiner);
  std::vector<OsdPoint> positions(points.size()), t1(points.size()), t2(points.size());
  for (auto _ : state) {
    OsdPoint *p = positions.data(), *a = t1.data(), *b = t2.data();
    primvar.Limit(points.data(), p, a, b);
    benchmark::DoNotOptimize(positions.data());
  }
}

// The sparse hierarchy held whole to `level` (core/hierarchy/sparse_hierarchy.h,
// the working state of a document): every level's points and the limits of
// every level of quads, against OpenSubdiv's refinement, interpolation and
// Limit() of the finest level alone.
template <bool kSemiSharp>
void hierarchyTessera(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto level0 = buildPolyLevel(topologyOf(kSemiSharp), CreaseOptions{});
    if (!level0.isOk()) return state.SkipWithError(level0.status().toString().c_str());
    const LevelCounts counts = tessera::testing::quadCountsOf(*level0, level);
    auto h =
        SparseHierarchy::create(std::move(*level0), input().mesh.points, CreaseOptions{}, counts, level, {});
    if (!h.isOk()) return state.SkipWithError(h.status().toString().c_str());
    benchmark::DoNotOptimize(h->points(level).data());
  }
}

template <bool kSemiSharp>
void hierarchyOpenSubdiv(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto refiner = osdRefiner(level, true, kSemiSharp);
    auto points = oracle::interpolateOsd(*refiner, input().osdPoints, level);
    std::vector<OsdPoint> positions(points.size()), t1(points.size()), t2(points.size());
    OsdPoint *p = positions.data(), *a = t1.data(), *b = t2.data();
    Far::PrimvarRefiner(*refiner).Limit(points.data(), p, a, b);
    benchmark::DoNotOptimize(positions.data());
  }
}

BENCHMARK(refineTessera)->Name("CatmarkRefine/Tessera")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(refineOpenSubdiv)
    ->Name("CatmarkRefine/OpenSubdiv")
    ->DenseRange(1, 4)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(limitTessera<false>)->Name("CatmarkLimit/Tessera")->DenseRange(1, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(limitOpenSubdiv<false>)
    ->Name("CatmarkLimit/OpenSubdiv")
    ->DenseRange(1, 3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(hierarchyTessera<false>)
    ->Name("CatmarkHierarchy/Tessera")
    ->DenseRange(1, 3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(hierarchyOpenSubdiv<false>)
    ->Name("CatmarkHierarchy/OpenSubdiv")
    ->DenseRange(1, 3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(limitTessera<true>)
    ->Name("CatmarkLimitSemiSharp/Tessera")
    ->DenseRange(1, 3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(limitOpenSubdiv<true>)
    ->Name("CatmarkLimitSemiSharp/OpenSubdiv")
    ->DenseRange(1, 3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(hierarchyTessera<true>)
    ->Name("CatmarkHierarchySemiSharp/Tessera")
    ->DenseRange(1, 3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(hierarchyOpenSubdiv<true>)
    ->Name("CatmarkHierarchySemiSharp/OpenSubdiv")
    ->DenseRange(1, 3)
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  std::string path = std::string(TESSERA_TESTDATA_DIR) + "/cgal/fandisk.off";
  // The server's heap policy (core/util/heap_policy.h) for both rows, as
  // the server runs them; --default-heap measures glibc's defaults instead.
  bool serverHeap = true;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--default-heap") == 0) {
      serverHeap = false;
      for (int j = i; j + 1 <= argc; ++j) argv[j] = argv[j + 1];
      --argc;
      break;
    }
  }
  if (serverHeap && !tessera::keepFreedMemoryForReuse()) {
    std::fprintf(stderr, "tessera_bench_scheme: the C library refused the server's heap policy\n");
    return 1;
  }
  std::printf("heap: %s\n", serverHeap ? "the server's (freed memory kept for reuse)" : "glibc's defaults");
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--mesh") == 0) {
      path = argv[i + 1];
      for (int j = i; j + 2 <= argc; ++j) argv[j] = argv[j + 2];
      argc -= 2;
      break;
    }
  }
  auto mesh = importPolygonMesh(path, "");
  if (!mesh.isOk()) {
    std::fprintf(stderr, "tessera_bench_scheme: %s\n", mesh.status().toString().c_str());
    return 1;
  }
  Input& in = input();
  in.mesh = std::move(mesh).value();
  std::printf("mesh %s: %d vertices, %d faces\n", path.c_str(), in.mesh.topology.numVertices,
              in.mesh.topology.numFaces());
  for (const auto& p : in.mesh.points) in.osdPoints.push_back(OsdPoint::from(p));
  in.osd = std::make_unique<oracle::OsdPolyInput>(in.mesh.topology);
  in.semiSharp = withSemiSharpFeatures(in.mesh, 30.0, 2.5f);
  in.osdSemiSharp = std::make_unique<oracle::OsdPolyInput>(in.semiSharp);
  std::printf("semi-sharp rows: %zu feature edges of sharpness 2.5\n", in.semiSharp.creases.size());

  return tessera::bench::runWithRatios(argc, argv);
}
