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

#include "bench/bench_mesh.h"
#include "bench/ratio_reporter.h"
#include "core/loop/limit.h"
#include "core/loop/loop_refiner.h"
#include "core/mesh/sharpness.h"
#include "oracle/osd_adapter.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/tessellation.h>

namespace {

using namespace tessera;
namespace Far = OpenSubdiv::Far;
namespace Bfr = OpenSubdiv::Bfr;

using oracle::OsdPoint;

struct Input {
  BaseTopology topology;
  BaseTopology tagged;  // the same mesh with infinitely sharp and semi-sharp edges
  std::vector<Vec3> points;
  std::vector<OsdPoint> osdPoints;
  std::unique_ptr<oracle::OsdInput> osd, osdTagged;
};

Input& input() {
  static Input in;
  return in;
}

std::unique_ptr<Far::TopologyRefiner> osdRefiner(int level, bool fullTopology, bool tagged = false) {
  return oracle::createOsdRefiner(tagged ? *input().osdTagged : *input().osd, LoopOptions{}, level,
                                  fullTopology);
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

// Limit: every vertex of the level, positions and normals. Tessera's are
// the exact limit (darts, wide crease sectors, corners and semi-sharp
// features included, docs/LIMITS.md); OpenSubdiv's Limit() applies the masks of
// the level's rules. Tagged: 1 edge in 13 infinitely sharp, 1 in 17 with
// sharpness 2.5, so creases, darts, corners and decaying features occur.
template <bool kTagged>
void limitTessera(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  auto refiner =
      LoopRefiner::create(kTagged ? input().tagged : input().topology, LoopOptions{}, {.levels = level});
  auto points = refiner->refinePoints(input().points);
  std::vector<Vec3> positions(points.size()), normals(points.size());
  for (auto _ : state) {
    computeLimit(refiner->finestLevel(), points, positions, normals);
    benchmark::DoNotOptimize(positions.data());
  }
}

template <bool kTagged>
void limitOpenSubdiv(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  auto refiner = osdRefiner(level, true, kTagged);
  auto points = oracle::interpolateOsd(*refiner, input().osdPoints, level);
  Far::PrimvarRefiner primvar(*refiner);
  std::vector<OsdPoint> positions(points.size()), t1(points.size()), t2(points.size());
  for (auto _ : state) {
    OsdPoint *p = positions.data(), *a = t1.data(), *b = t2.data();
    primvar.Limit(points.data(), p, a, b);
    benchmark::DoNotOptimize(positions.data());
  }
}

// Bfr: the limit surface of every base face evaluated (position and both
// derivatives) at the points of a uniform tessellation of rate 2^level, the
// points of the level's vertices (shared ones once per face). Surfaces are
// set up inside the loop: that is what a Bfr evaluation of new points costs.
template <bool kTagged>
void limitBfr(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  auto refiner = osdRefiner(0, true, kTagged);
  const std::vector<double> meshPoints = [] {
    std::vector<double> out;
    for (const auto& p : input().points) out.insert(out.end(), {p[0], p[1], p[2]});
    return out;
  }();
  Bfr::RefinerSurfaceFactory<> factory(*refiner);
  Bfr::Surface<double> surface;
  std::vector<double> patch, coords, out(9);
  for (auto _ : state) {
    size_t evaluated = 0;
    for (int f = 0; f < refiner->GetLevel(0).GetNumFaces(); ++f) {
      if (!factory.InitVertexSurface(f, &surface)) continue;
      patch.resize(3 * surface.GetNumPatchPoints());
      surface.PreparePatchPoints(meshPoints.data(), 3, patch.data(), 3);
      Bfr::Tessellation tess(surface.GetParameterization(), 1 << level);
      coords.resize(2 * tess.GetNumCoords());
      tess.GetCoords(coords.data());
      for (int i = 0; i < tess.GetNumCoords(); ++i) {
        surface.Evaluate(&coords[2 * i], patch.data(), 3, &out[0], &out[3], &out[6]);
        ++evaluated;
      }
    }
    benchmark::DoNotOptimize(out.data());
    state.counters["points"] = static_cast<double>(evaluated);
  }
}

BENCHMARK(refineTessera<false>)->Name("Refine/Tessera")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(refineOpenSubdiv<false>)
    ->Name("Refine/OpenSubdiv")
    ->DenseRange(1, 4)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(refineTessera<true>)->Name("RefineFull/Tessera")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(refineOpenSubdiv<true>)
    ->Name("RefineFull/OpenSubdiv")
    ->DenseRange(1, 4)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(limitTessera<false>)->Name("Limit/Tessera")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(limitOpenSubdiv<false>)->Name("Limit/OpenSubdiv")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(limitBfr<false>)->Name("Limit/Bfr")->DenseRange(1, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(limitTessera<true>)->Name("LimitTagged/Tessera")->DenseRange(1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(limitOpenSubdiv<true>)
    ->Name("LimitTagged/OpenSubdiv")
    ->DenseRange(1, 4)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(limitBfr<true>)->Name("LimitTagged/Bfr")->DenseRange(1, 3)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  auto mesh = tessera::bench::benchMesh(argc, argv, "tessera_bench_loop");
  if (!mesh.isOk()) return 1;
  Input& in = input();
  in.topology = BaseTopology::fromBaseMesh(*mesh);
  in.points = mesh->positions();
  for (const auto& p : in.points) in.osdPoints.push_back(OsdPoint::from(p));
  in.osd = std::make_unique<oracle::OsdInput>(in.topology);
  in.tagged = in.topology;
  {
    auto base = LoopRefiner::create(in.topology, LoopOptions{}, {.levels = 0});
    const Level& level0 = base->level(0);
    for (Index e = 0; e < level0.numEdges(); ++e) {
      const auto& ev = level0.edgeVertices[e];
      if (e % 13 == 0)
        in.tagged.creases.push_back({ev[0], ev[1], kSharpnessInfinite});
      else if (e % 17 == 0)
        in.tagged.creases.push_back({ev[0], ev[1], 2.5f});
    }
  }
  in.osdTagged = std::make_unique<oracle::OsdInput>(in.tagged);

  return tessera::bench::runWithRatios(argc, argv);
}
