// An edit under many cameras (docs/VIEWS.md "Edits and tiles"): the work
// the server does between an edit and its tile deltas, without the
// network. Setup, not timed: a document held to level 4; N phone cameras on
// orbits of their own (bench/orbit_cameras.h) select their tiles once, and
// every tile their walks read is built and measured, every tile selected
// encoded. Each iteration then moves one of the first 2,000 level-0
// vertices by up to 0.2 per axis (the editors of bench/views_load.sh),
// forgets the tiles the edit reached (core/view/tile_invalidation.h) and
// builds and measures again every one of them the walks read, and encodes
// again those selected: what the server's flush does before it sends.
//
// The reference, in the same run: the whole-document profile the views
// load compares with (level 1 everywhere) on a second document, updated for
// the same edits, its changed regions encoded (as bench/delta_bench.cc).
// The ratio printed is tiles / profile, of the medians.
//
//   tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C /tmp data/meshes/armadillo.off
//   build/release/bench/tessera_bench_tile_edit --mesh /tmp/data/meshes/armadillo.off
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_mesh.h"
#include "bench/orbit_cameras.h"
#include "bench/percentile.h"
#include "core/document/document.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/tessellation.h"
#include "core/view/tile_catalogue.h"
#include "core/view/tile_encoding.h"
#include "core/view/tile_invalidation.h"
#include "core/view/tile_selection.h"

namespace {

using namespace tessera;
using Clock = std::chrono::steady_clock;

constexpr int kMaxLevel = 4;
constexpr int kEditedVertices = 2000;
constexpr double kStep = 0.2;
const LodProfile kProfile{.baseLevel = 1, .maxLevel = 1, .angleThresholdDegrees = 10};

struct Input {
  BaseMesh mesh;
  bench::OrbitCentre around;
  std::map<std::string, double> medians;  // seconds, by benchmark
};

Input& input() {
  static Input in;
  return in;
}

// The edits of a run, the same in both benchmarks: each moves a random one
// of the first kEditedVertices level-0 vertices by up to kStep per axis.
struct Edits {
  explicit Edits(uint32_t seed) : rng(seed) {}
  Status applyNext(Document& doc) {
    std::uniform_int_distribution<uint64_t> vertex(0, kEditedVertices - 1);
    std::uniform_real_distribution<double> offset(-kStep, kStep);
    const VertexId v(0, vertex(rng));
    const Vec3 by(offset(rng), offset(rng), offset(rng));
    return doc.moveBy(std::span(&v, 1), by).status();
  }
  std::mt19937 rng;
};

void failed(benchmark::State& bm, const Status& status) {
  bm.SkipWithError(status.toString().c_str());
}

void editUnderCameras(benchmark::State& bm) {
  const int n = static_cast<int>(bm.range(0));
  auto doc = Document::create(input().mesh, {.maxLevel = kMaxLevel});
  if (!doc.isOk()) return failed(bm, doc.status());
  auto grid = documentGrid(*doc);
  if (!grid.isOk()) return failed(bm, grid.status());
  TileCatalogue catalogue(*doc);
  std::vector<View> views;
  for (int c = 0; c < n; ++c) views.push_back(bench::orbitCamera(input().around, c, n, 0));
  const std::vector<int64_t> budgets(views.size(), 0);
  auto selections = selectTilesForEach(views, catalogue, budgets);
  if (!selections.isOk()) return failed(bm, selections.status());
  std::set<TileKey> selected;
  for (const TileSelection& s : *selections) {
    for (const SelectedTile& t : s.tiles) selected.insert(t.key);
  }
  uint64_t version = 1;
  auto encode = [&](const TileKey& key) -> Status {
    TESSERA_ASSIGN_OR_RETURN(const RegionMesh* mesh, catalogue.mesh(key));
    TESSERA_ASSIGN_OR_RETURN(EncodedTile tile, encodeTile(*doc, key, *mesh, *grid, version));
    benchmark::DoNotOptimize(tile.bytes->data());
    catalogue.releaseMesh(key);
    return Status::ok();
  };
  for (const TileKey& key : selected) {
    if (Status s = encode(key); !s.isOk()) return failed(bm, s);
  }
  Edits edits(11);
  std::vector<double> samples, rebuild, encodeTimes;
  double reached = 0, encoded = 0, triangles = 0;
  for (auto _ : bm) {
    const auto start = Clock::now();
    if (Status moved = edits.applyNext(*doc); !moved.isOk()) return failed(bm, moved);
    ++version;
    const auto gone =
        catalogue.forget(TouchedTiles(doc->hierarchy(), catalogue.tree(), doc->lastUpdate().limits));
    for (const TileKey& key : gone) {
      auto tile = catalogue.get(key);
      if (!tile.isOk()) return failed(bm, tile.status());
      triangles += static_cast<double>((*tile)->triangles);
    }
    const auto rebuilt = Clock::now();
    for (const TileKey& key : gone) {
      if (!selected.count(key)) continue;
      if (Status s = encode(key); !s.isOk()) return failed(bm, s);
      ++encoded;
    }
    const auto end = Clock::now();
    const double seconds = std::chrono::duration<double>(end - start).count();
    bm.SetIterationTime(seconds);
    samples.push_back(seconds);
    rebuild.push_back(std::chrono::duration<double>(rebuilt - start).count());
    encodeTimes.push_back(std::chrono::duration<double>(end - rebuilt).count());
    reached += static_cast<double>(gone.size());
  }
  const double iterations = static_cast<double>(samples.size());
  input().medians["tiles"] = bench::percentile(samples, 0.5);
  bm.counters["p50_ms"] = bench::percentile(samples, 0.5) * 1e3;
  bm.counters["p99_ms"] = bench::percentile(samples, 0.99) * 1e3;
  // The edit, the reached tiles built and measured, and those selected
  // encoded; medians.
  bm.counters["rebuild_p50_ms"] = bench::percentile(rebuild, 0.5) * 1e3;
  bm.counters["encode_p50_ms"] = bench::percentile(encodeTimes, 0.5) * 1e3;
  bm.counters["tiles_reached"] = reached / iterations;
  bm.counters["tiles_encoded"] = encoded / iterations;
  bm.counters["tile_triangles"] = triangles / iterations;
}

void editUnderProfile(benchmark::State& bm) {
  auto doc = Document::create(input().mesh, {.maxLevel = kMaxLevel});
  if (!doc.isOk()) return failed(bm, doc.status());
  auto grid = documentGrid(*doc);
  if (!grid.isOk()) return failed(bm, grid.status());
  auto tessellation = Tessellation::build(*doc, kProfile);
  if (!tessellation.isOk()) return failed(bm, tessellation.status());
  Edits edits(11);
  uint64_t version = 1;
  std::vector<double> samples;
  double regions = 0;
  for (auto _ : bm) {
    const auto start = Clock::now();
    if (Status moved = edits.applyNext(*doc); !moved.isOk()) return failed(bm, moved);
    ++version;
    auto changes = tessellation->update(*doc);
    if (!changes.isOk()) return failed(bm, changes.status());
    for (uint64_t region : changes->changed) {
      const RegionHeader header{
          .regionId = region, .documentVersion = version, .profile = kProfile, .grid = *grid};
      auto bytes = encodeRegion(header, tessellation->regions().at(region));
      if (!bytes.isOk()) return failed(bm, bytes.status());
      benchmark::DoNotOptimize(bytes->data());
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    bm.SetIterationTime(seconds);
    samples.push_back(seconds);
    regions += static_cast<double>(changes->changed.size());
  }
  input().medians["profile"] = bench::percentile(samples, 0.5);
  bm.counters["p50_ms"] = bench::percentile(samples, 0.5) * 1e3;
  bm.counters["p99_ms"] = bench::percentile(samples, 0.99) * 1e3;
  bm.counters["regions"] = regions / static_cast<double>(samples.size());
}

BENCHMARK(editUnderCameras)
    ->Name("EditUnderCameras/Tiles")
    ->Arg(100)
    ->Iterations(200)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(editUnderProfile)
    ->Name("EditUnderCameras/Profile")
    ->Iterations(200)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  auto mesh = tessera::bench::benchMesh(argc, argv, "tessera_bench_tile_edit");
  if (!mesh.isOk()) return 1;
  input().mesh = *mesh;
  input().around = tessera::bench::orbitCentreOf(*mesh);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  const auto& m = input().medians;
  if (m.count("tiles") && m.count("profile")) {
    std::printf("edit under cameras, medians: tiles / profile = %.2f\n", m.at("tiles") / m.at("profile"));
  }
  return 0;
}
