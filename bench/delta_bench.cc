// Edit to encoded region deltas (docs/PERFORMANCE.md): a document whose
// displayed surface has more than 1M triangles, single-vertex edits at
// levels 0-4 timed from the call until every changed region is
// re-tessellated, hashed and Draco-encoded (each stage's median reported
// apart), against a full re-tessellation and a full encode of the whole
// surface in the same run.
//
//   build/release/bench/tessera_bench_delta [--mesh PATH] [benchmark flags]
//
// The document holds fandisk whole to level 4; the profile shows level 3
// everywhere and level 4 where limit normals differ by more than 5 degrees,
// so no edit makes the hierarchy grow (growth is measured apart, below).
// Each case runs on a Loop document and on a Catmull-Clark document of the
// same mesh (its triangles as polygons: three quads each at level 1), the
// third argument (0 Loop, 1 Catmull-Clark), so the two schemes are timed in
// the same run.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_edit.h"
#include "bench/bench_mesh.h"
#include "bench/percentile.h"
#include "core/document/document.h"
#include "core/loop/limit.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/surface_hash.h"
#include "core/tessellation/tessellation.h"
#include "core/util/parallel_for.h"

namespace {

using namespace tessera;
using Clock = std::chrono::steady_clock;

const LodProfile kProfile{
    .baseLevel = 3, .maxLevel = 4, .angleThresholdDegrees = 5, .triangleBudget = 20'000'000};

struct State {
  std::optional<Document> doc;
  std::optional<Tessellation> tessellation;
  QuantizationGrid grid;
  uint64_t version = 1;
};

constexpr int kSchemes = 2;  // Loop, Catmull-Clark

State& state(int scheme) {
  static State s[kSchemes];
  return s[scheme];
}

// Encodes the listed regions on `threads` threads, as a server's flush does
// (parallel_for.h); returns the bytes.
size_t encodeRegions(State& s, const std::vector<uint64_t>& ids, unsigned threads) {
  std::vector<Expected<std::string>> encoded(ids.size(), internalError("not encoded"));
  parallelFor(ids.size(), threads, [&](size_t i) {
    const RegionHeader header{.regionId = ids[i],
                              .documentVersion = s.version,
                              .profile = s.tessellation->profile(),
                              .grid = s.grid};
    encoded[i] = encodeRegion(header, s.tessellation->regions().at(ids[i]));
  });
  size_t bytes = 0;
  for (const auto& e : encoded) {
    if (!e.isOk()) {
      std::fprintf(stderr, "encode: %s\n", e.status().toString().c_str());
      std::exit(1);
    }
    bytes += e->size();
  }
  return bytes;
}

void editToDelta(benchmark::State& bm) {
  const int level = static_cast<int>(bm.range(0));
  const auto threads = static_cast<unsigned>(bm.range(1));
  setWorkThreads(threads);  // the re-tessellation's too
  State& s = state(static_cast<int>(bm.range(2)));
  Document& doc = *s.doc;
  std::mt19937 rng(7 + level);
  std::vector<double> samples, evaluate, tessellate, hash, encode;  // the stages, seconds
  double bytes = 0, regions = 0, rebuilds = 0;
  for (auto _ : bm) {
    const tessera::bench::LimitEdit edit = tessera::bench::randomLimitEdit(doc, level, rng);
    const auto start = Clock::now();
    auto id = doc.moveToLimit(std::span(&edit.vertex, 1), edit.target);
    const auto evaluated = Clock::now();
    auto changes = s.tessellation->update(doc);
    const auto tessellated = Clock::now();
    // The surface hash of each changed region, as a server keeps it
    // (docs/PROTOCOL.md 6.5).
    uint64_t sum = 0;
    for (uint64_t region : changes->changed)
      sum += regionSurfaceHashOnGrid(s.tessellation->regions().at(region), s.grid, kProfile.vertexIds);
    benchmark::DoNotOptimize(sum);
    const auto hashed = Clock::now();
    ++s.version;
    const size_t delta = encodeRegions(s, changes->changed, threads);
    const auto end = Clock::now();
    const double seconds = std::chrono::duration<double>(end - start).count();
    evaluate.push_back(std::chrono::duration<double>(evaluated - start).count());
    tessellate.push_back(std::chrono::duration<double>(tessellated - evaluated).count());
    hash.push_back(std::chrono::duration<double>(hashed - tessellated).count());
    encode.push_back(std::chrono::duration<double>(end - hashed).count());
    bm.SetIterationTime(seconds);
    samples.push_back(seconds);
    bytes += static_cast<double>(delta);
    regions += static_cast<double>(changes->changed.size());
    rebuilds += changes->rebuilt ? 1 : 0;
    // Restore the document outside the timing.
    (void)doc.remove(*id);
    (void)s.tessellation->update(doc);
    ++s.version;
  }
  const double n = static_cast<double>(samples.size());
  bm.counters["p50_us"] = tessera::bench::percentile(samples, 0.5) * 1e6;
  bm.counters["p99_us"] = tessera::bench::percentile(samples, 0.99) * 1e6;
  // Where the time goes: the edit and the hierarchy's update (evaluation),
  // the regions' re-tessellation, their surface hashes and their Draco
  // encoding; medians.
  bm.counters["evaluate_p50_us"] = tessera::bench::percentile(evaluate, 0.5) * 1e6;
  bm.counters["tessellate_p50_us"] = tessera::bench::percentile(tessellate, 0.5) * 1e6;
  bm.counters["hash_p50_us"] = tessera::bench::percentile(hash, 0.5) * 1e6;
  bm.counters["encode_p50_us"] = tessera::bench::percentile(encode, 0.5) * 1e6;
  bm.counters["delta_bytes"] = bytes / n;
  bm.counters["regions"] = regions / n;
  bm.counters["rebuilds"] = rebuilds;
  setWorkThreads(0);
}

void fullTessellateAndEncode(benchmark::State& bm) {
  const auto threads = static_cast<unsigned>(bm.range(0));
  setWorkThreads(threads);
  State& s = state(static_cast<int>(bm.range(1)));
  size_t bytes = 0;
  for (auto _ : bm) {
    auto fresh = Tessellation::build(*s.doc, kProfile);
    std::vector<uint64_t> ids;
    for (const auto& [id, mesh] : fresh->regions()) ids.push_back(id);
    s.tessellation.emplace(std::move(*fresh));
    bytes = encodeRegions(s, ids, threads);
  }
  bm.counters["bytes"] = static_cast<double>(bytes);
  bm.counters["triangles"] = static_cast<double>(s.tessellation->numTriangles());
  bm.counters["regions"] = static_cast<double>(s.tessellation->regions().size());
  setWorkThreads(0);
}

// The second argument is the threads that re-tessellate and encode: one,
// the reference, against what a server uses (workThreads), in the same run.
BENCHMARK(editToDelta)
    ->Name("EditToDelta")
    ->ArgsProduct({{0, 1}, {1, static_cast<int64_t>(workThreads())}, {0, 1}})
    ->Iterations(100)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(editToDelta)
    ->Name("EditToDelta")
    ->ArgsProduct({{2, 3, 4}, {1, static_cast<int64_t>(workThreads())}, {0, 1}})
    ->Iterations(1000)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(fullTessellateAndEncode)
    ->Name("FullTessellateAndEncode")
    ->ArgsProduct({{1, static_cast<int64_t>(workThreads())}, {0, 1}})
    ->Iterations(2)
    ->Unit(benchmark::kMillisecond);

}  // namespace

// The document of `scheme`, tessellated; false (said on stderr) if it
// cannot be made.
bool prepare(int scheme, const BaseMesh& mesh, const QuantizationGrid& grid) {
  State& s = state(scheme);
  const DocumentOptions options{
      .maxLevel = 6,
      .uniformLevel = 4,
      .scheme = scheme == 0 ? DocumentScheme::kLoop : DocumentScheme::kCatmullClark};
  auto doc = scheme == 0 ? Document::create(mesh, options)
                         : Document::create(PolyTopology::fromBaseMesh(mesh), mesh.positions(), options);
  if (!doc.isOk()) {
    std::fprintf(stderr, "tessera_bench_delta: %s\n", doc.status().toString().c_str());
    return false;
  }
  s.doc.emplace(std::move(*doc));
  s.grid = grid;
  auto t = Tessellation::build(*s.doc, kProfile);
  if (!t.isOk()) {
    std::fprintf(stderr, "tessera_bench_delta: %s\n", t.status().toString().c_str());
    return false;
  }
  s.tessellation.emplace(std::move(*t));
  std::printf("%s document, displayed (%s): %lld triangles in %zu regions; grid %d position bits\n",
              documentSchemeName(s.doc->scheme()), kProfile.key().c_str(),
              static_cast<long long>(s.tessellation->numTriangles()), s.tessellation->regions().size(),
              s.grid.positionBits);
  return true;
}

int main(int argc, char** argv) {
  auto mesh = tessera::bench::benchMesh(argc, argv, "tessera_bench_delta");
  if (!mesh.isOk()) return 1;
  auto grid = tessera::bench::gridAround(*mesh);
  if (!grid.isOk()) return 1;
  for (int scheme = 0; scheme < kSchemes; ++scheme) {
    if (!prepare(scheme, *mesh, *grid)) return 1;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
