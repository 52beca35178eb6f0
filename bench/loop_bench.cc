// Uniform refinement (topology + positions) and limit evaluation on a real
// mesh of >= 10k triangles, Tessera against OpenSubdiv Far in the same run.
//
//   build/release/bench/tessera_bench_loop [--mesh PATH] [benchmark flags]
//
// Both start from the same triangle list and the same double-precision
// points; OpenSubdiv uses TopologyRefinerFactory + RefineUniform +
// PrimvarRefiner::Interpolate (and ::Limit for the limit case).
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/ratio_reporter.h"
#include "bench/bench_mesh.h"
#include "core/loop/limit.h"
#include "core/loop/loop_refiner.h"
#include "oracle/osd_adapter.h"

namespace {

using namespace tessera;
namespace Far = OpenSubdiv::Far;

using oracle::OsdPoint;

struct Input {
  BaseTopology topology;
  std::vector<Vec3> points;
  std::vector<OsdPoint> osdPoints;
  std::unique_ptr<oracle::OsdInput> osd;
};

Input& input() {
  static Input in;
  return in;
}

std::unique_ptr<Far::TopologyRefiner> osdRefiner(int level, bool fullTopology) {
  return oracle::createOsdRefiner(*input().osd, LoopOptions{}, level, fullTopology);
}

// Refine: the finest level gets faces only (OpenSubdiv's default).
// RefineFull: every relation at the finest level too, as limits need.
template <bool kFullTopology>
void refineTessera(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto refiner = LoopRefiner::create(input().topology, LoopOptions{},
                                       {.levels = level, .fullTopologyInLastLevel = kFullTopology});
    auto points = refiner->refinePoints(input().points);
    benchmark::DoNotOptimize(points.data());
  }
}

template <bool kFullTopology>
void refineOpenSubdiv(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto refiner = osdRefiner(level, kFullTopology);
    auto points = oracle::interpolateOsd(*refiner, input().osdPoints, level);
    benchmark::DoNotOptimize(points.data());
  }
}

void limitTessera(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  auto refiner = LoopRefiner::create(input().topology, LoopOptions{}, {.levels = level});
  auto points = refiner->refinePoints(input().points);
  std::vector<Vec3> positions(points.size()), normals(points.size());
  for (auto _ : state) {
    computeLimit(refiner->finestLevel(), points, positions, normals);
    benchmark::DoNotOptimize(positions.data());
  }
}

void limitOpenSubdiv(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  auto refiner = osdRefiner(level, true);
  auto points = oracle::interpolateOsd(*refiner, input().osdPoints, level);
  Far::PrimvarRefiner primvar(*refiner);
  std::vector<OsdPoint> positions(points.size()), t1(points.size()), t2(points.size());
  for (auto _ : state) {
    OsdPoint *p = positions.data(), *a = t1.data(), *b = t2.data();
    primvar.Limit(points.data(), p, a, b);
    benchmark::DoNotOptimize(positions.data());
  }
}

BENCHMARK(refineTessera<false>)->Name("Refine/Tessera")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(refineOpenSubdiv<false>)->Name("Refine/OpenSubdiv")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(refineTessera<true>)->Name("RefineFull/Tessera")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(refineOpenSubdiv<true>)->Name("RefineFull/OpenSubdiv")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(limitTessera)->Name("Limit/Tessera")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(limitOpenSubdiv)->Name("Limit/OpenSubdiv")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  auto mesh = tessera::bench::benchMesh(argc, argv, "tessera_bench_loop");
  if (!mesh.isOk()) return 1;
  Input& in = input();
  in.topology = BaseTopology::fromBaseMesh(*mesh);
  in.points = mesh->positions();
  for (const auto& p : in.points) in.osdPoints.push_back(OsdPoint::from(p));
  in.osd = std::make_unique<oracle::OsdInput>(in.topology);

  benchmark::Initialize(&argc, argv);
  tessera::bench::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.printRatios();
  benchmark::Shutdown();
  return 0;
}
