// Cameras moving around a document: what the server does for them between
// edits (docs/VIEWS.md "The server"), without the network. Each iteration
// starts from a fresh document held to level 4 and moves N phone-sized
// cameras (390x844, tolerance 1 px) on orbits of their own, S steps each.
// Each step selects every camera's tiles in one walk (selectTilesForEach)
// and builds the mesh of every tile selected, as the server's tile cache
// does before encoding. The hierarchy grows under the tiles as they are
// first needed (sparse_hierarchy.h): that growth is what this measures.
//
// The reference, in the same run: OpenSubdiv refining the whole document
// uniformly to the deepest level the sweep read (one below the finest tile
// shown), points and limits, once. Sparse growth exists to cost less than
// that; the ratio printed is sweep / reference.
//
//   tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C /tmp data/meshes/armadillo.off
//   build/release/bench/tessera_bench_view_growth --mesh /tmp/data/meshes/armadillo.off
#include <cstdio>
#include <map>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_mesh.h"
#include "bench/orbit_cameras.h"
#include "bench/ratio_reporter.h"
#include "core/document/document.h"
#include "core/view/tile_selection.h"
#include "oracle/osd_adapter.h"

namespace {

using namespace tessera;
namespace Far = OpenSubdiv::Far;

constexpr int kMaxLevel = 4;
constexpr int kSteps = 10;

struct Input {
  BaseMesh mesh;
  bench::OrbitCentre around;
  std::unique_ptr<oracle::OsdInput> osd;
  std::vector<oracle::OsdPoint> osdPoints;
  std::map<int, int> deepestRead;  // per camera count: one below the finest tile a sweep showed
};

Input& input() {
  static Input in;
  return in;
}

void sweepTessera(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  int64_t tiles = 0, built = 0;
  int deepest = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto doc = std::make_unique<Expected<Document>>(Document::create(input().mesh, {.maxLevel = kMaxLevel}));
    if (!doc->isOk()) return state.SkipWithError(doc->status().toString().c_str());
    auto catalogue = std::make_unique<TileCatalogue>(**doc);
    state.ResumeTiming();
    tiles = 0;
    for (int s = 0; s < kSteps; ++s) {
      std::vector<View> views;
      for (int c = 0; c < n; ++c) views.push_back(bench::orbitCamera(input().around, c, n, s));
      const std::vector<int64_t> budgets(views.size(), 0);
      auto selections = selectTilesForEach(views, *catalogue, budgets);
      if (!selections.isOk()) return state.SkipWithError(selections.status().toString().c_str());
      for (const TileSelection& selection : *selections) {
        for (const SelectedTile& t : selection.tiles) {
          auto mesh = catalogue->mesh(t.key);
          if (!mesh.isOk()) return state.SkipWithError(mesh.status().toString().c_str());
          deepest = std::max(deepest, t.key.level);
          ++tiles;
        }
      }
    }
    built = catalogue->built();
    state.PauseTiming();  // the teardown is not timed
    catalogue.reset();
    doc.reset();
    state.ResumeTiming();
  }
  input().deepestRead[n] = std::min(deepest + 1, kMaxLevel);
  state.counters["tiles_selected"] = static_cast<double>(tiles);
  state.counters["tiles_built"] = static_cast<double>(built);
  state.counters["deepest_read"] = input().deepestRead[n];
}

void sweepOpenSubdiv(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  if (!input().deepestRead.count(n))
    return state.SkipWithError("run Sweep/Tessera with the same argument first");
  const int level = input().deepestRead.at(n);
  for (auto _ : state) {
    auto refiner = oracle::createOsdRefiner(*input().osd, LoopOptions{}, level, true);
    auto points = oracle::interpolateOsd(*refiner, input().osdPoints, level);
    std::vector<oracle::OsdPoint> positions(points.size()), t1(points.size()), t2(points.size());
    oracle::OsdPoint *p = positions.data(), *a = t1.data(), *b = t2.data();
    Far::PrimvarRefiner(*refiner).Limit(points.data(), p, a, b);
    benchmark::DoNotOptimize(positions.data());
  }
  state.counters["level"] = level;
}

BENCHMARK(sweepTessera)
    ->Name("Sweep/Tessera")
    ->Arg(20)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(sweepOpenSubdiv)
    ->Name("Sweep/OpenSubdiv")
    ->Arg(20)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

int main(int argc, char** argv) {
  auto mesh = tessera::bench::benchMesh(argc, argv, "tessera_bench_view_growth");
  if (!mesh.isOk()) return 1;
  Input& in = input();
  in.mesh = *mesh;
  in.around = bench::orbitCentreOf(*mesh);
  in.osd = std::make_unique<oracle::OsdInput>(BaseTopology::fromBaseMesh(*mesh));
  for (const Vec3& p : mesh->positions()) in.osdPoints.push_back(oracle::OsdPoint::from(p));

  return tessera::bench::runWithRatios(argc, argv);
}
