// Editing a document whose displayed surface has more than 1M triangles
// (docs/PERFORMANCE.md "Hierarchical editing"): a single-vertex direct-manipulation edit at levels
// 0-4, from the call to updated limit positions and normals of its dirty
// set, against a full recomputation of the same document and OpenSubdiv's
// uniform refine + limit of the same surface, in the same run.
//
//   build/release/bench/tessera_bench_edit [--mesh PATH] [benchmark flags]
//
// Each edit is timed on its own (manual time) and undone by removal outside
// the timing, so every sample edits the same document; p50/p99 are over the
// samples of one run.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <random>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/bench_mesh.h"
#include "bench/percentile.h"
#include "bench/ratio_reporter.h"
#include "core/document/document.h"
#include "core/loop/limit.h"
#include "oracle/osd_adapter.h"

namespace {

using namespace tessera;
using Clock = std::chrono::steady_clock;

constexpr int kDisplayLevel = 4;

struct Input {
  BaseTopology topology;
  std::vector<Vec3> points;
  std::vector<oracle::OsdPoint> osdPoints;
  std::unique_ptr<oracle::OsdInput> osd;
  std::optional<Document> doc;
};

Input& input() {
  static Input in;
  return in;
}

void editTessera(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  Document& doc = *input().doc;
  std::mt19937 rng(42 + level);
  std::vector<double> samples;
  int64_t points = 0, limits = 0;
  for (auto _ : state) {
    const VertexId v(level,
                     std::uniform_int_distribution<uint64_t>(0, doc.counts().vertices(level) - 1)(rng));
    const Index local = *doc.hierarchy().completeVertex(v);
    const Vec3 limit =
        limitFrame(doc.hierarchy().level(level).mesh, local, doc.hierarchy().points(level)).position;
    const auto start = Clock::now();
    auto id = doc.moveToLimit(std::span(&v, 1), limit + Vec3(0.002, -0.001, 0.003));
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (!id.isOk()) {
      state.SkipWithError(id.status().toString().c_str());
      return;
    }
    state.SetIterationTime(seconds);
    samples.push_back(seconds);
    points += doc.lastUpdate().pointsRecomputed;
    limits += doc.lastUpdate().limitsRecomputed;
    (void)doc.remove(*id);
  }
  const double n = static_cast<double>(samples.size());
  state.counters["p50_us"] = tessera::bench::percentile(samples, 0.50) * 1e6;
  state.counters["p99_us"] = tessera::bench::percentile(samples, 0.99) * 1e6;
  state.counters["points"] = static_cast<double>(points) / n;
  state.counters["limits"] = static_cast<double>(limits) / n;
}

// The same document evaluated from scratch: hierarchy, points and the
// limits of every displayed vertex.
void fullTessera(benchmark::State& state) {
  const Document& doc = *input().doc;
  for (auto _ : state) {
    auto eval = SparseHierarchy::create(doc.baseTopology(), doc.basePoints(), doc.options().loop,
                                        doc.counts(), doc.options().uniformLevel, doc.edits());
    benchmark::DoNotOptimize(eval.isOk());
  }
}

void refineLimitOpenSubdiv(benchmark::State& state) {
  for (auto _ : state) {
    auto refiner = oracle::createOsdRefiner(*input().osd, LoopOptions{}, kDisplayLevel, true);
    auto points = oracle::interpolateOsd(*refiner, input().osdPoints, kDisplayLevel);
    OpenSubdiv::Far::PrimvarRefiner primvar(*refiner);
    std::vector<oracle::OsdPoint> positions(points.size()), t1(points.size()), t2(points.size());
    oracle::OsdPoint *p = positions.data(), *a = t1.data(), *b = t2.data();
    primvar.Limit(points.data(), p, a, b);
    benchmark::DoNotOptimize(positions.data());
  }
}

BENCHMARK(editTessera)
    ->Name("Edit")
    ->DenseRange(0, 1)
    ->Iterations(200)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(editTessera)
    ->Name("Edit")
    ->DenseRange(2, 4)
    ->Iterations(2000)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(fullTessera)->Name("FullRecompute/Tessera")->Iterations(3)->Unit(benchmark::kMillisecond);
BENCHMARK(refineLimitOpenSubdiv)
    ->Name("FullRecompute/OpenSubdiv")
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

void printMemory(const char* what, const HierarchyStats& stats) {
  const double displayed = static_cast<double>(stats.displayedVertices);
  std::printf(
      "%s: %lld points held, %lld displayed (overhead %.1f%%), %.1f MiB, %.1f bytes per displayed vertex\n",
      what, static_cast<long long>(stats.vertices), static_cast<long long>(stats.displayedVertices),
      100.0 * (static_cast<double>(stats.vertices) - displayed) / displayed,
      static_cast<double>(stats.bytes) / (1 << 20), static_cast<double>(stats.bytes) / displayed);
}

// A document displayed at level 2 with 40 edits at levels 3-6 in a few
// spots: the adaptive case the forest is for.
void reportAdaptiveMemory(const Input& in) {
  auto doc = Document::create(in.topology, in.points, {.maxLevel = 6, .uniformLevel = 2});
  std::mt19937 rng(7);
  for (int i = 0; i < 40; ++i) {
    const int level = 3 + i % 4;
    const uint64_t spot = (i % 5) * 997;  // five spots, descendants of base vertices
    const VertexId v(level, std::min<uint64_t>(spot + std::uniform_int_distribution<uint64_t>(0, 3)(rng),
                                               doc->counts().vertices(0) - 1));
    (void)doc->moveBy(std::span(&v, 1), Vec3(0.001, 0.002, 0.001));
  }
  printMemory("adaptive (display level 2, 40 edits at levels 3-6)", doc->hierarchy().stats());
}

}  // namespace

int main(int argc, char** argv) {
  auto mesh = tessera::bench::benchMesh(argc, argv, "tessera_bench_edit");
  if (!mesh.isOk()) return 1;
  Input& in = input();
  in.topology = BaseTopology::fromBaseMesh(*mesh);
  in.points = mesh->positions();
  for (const auto& p : in.points) in.osdPoints.push_back(oracle::OsdPoint::from(p));
  in.osd = std::make_unique<oracle::OsdInput>(in.topology);
  auto doc = Document::create(in.topology, in.points, {.maxLevel = 6, .uniformLevel = kDisplayLevel});
  if (!doc.isOk()) {
    std::fprintf(stderr, "tessera_bench_edit: %s\n", doc.status().toString().c_str());
    return 1;
  }
  in.doc.emplace(std::move(*doc));
  std::printf("document displayed at level %d: %llu triangles\n", kDisplayLevel,
              static_cast<unsigned long long>(in.doc->counts().faces(kDisplayLevel)));
  printMemory("uniform display", in.doc->hierarchy().stats());
  reportAdaptiveMemory(in);

  return tessera::bench::runWithRatios(argc, argv);
}
