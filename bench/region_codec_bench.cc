// Region codec: encode time, encoded size and decode time of
// typical regions at every compression level, to choose the default for
// latency (docs/REGION_ENCODING.md), and of the same regions as meshopt
// regions (EncodeMeshopt, DecodeMeshopt; docs/PERFORMANCE.md "Region
// codecs").
//
//   build/release/bench/tessera_bench_region [--mesh PATH] [benchmark flags]
//
// Regions are compact patches of ~512, ~2k and ~8k triangles grown
// breadth-first from one triangle of the smooth Loop limit surface of the
// mesh (fandisk by default) at level 2, like the quadtree regions of the
// displayed surface; every region is quantized on the grid of the whole
// surface, as a document's regions are.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_mesh.h"
#include "core/hierarchy/ids.h"
#include "core/loop/loop_refiner.h"
#include "core/tessellation/region_codec.h"

namespace {

using namespace tessera;

constexpr int kLevel = 2;
constexpr int kRegionSizes[] = {512, 2048, 8192};

struct Input {
  RegionMesh surface;
  RegionHeader header;
  std::map<int, RegionMesh> regions;  // by target triangle count
};

Input& input() {
  static Input in;
  return in;
}

// Grows a patch of `count` triangles breadth-first over shared edges.
RegionMesh patch(const RegionMesh& s, size_t seed, size_t count) {
  std::map<std::pair<int, int>, std::vector<size_t>> byEdge;
  for (size_t f = 0; f < s.triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = s.triangles[f][k], b = s.triangles[f][(k + 1) % 3];
      byEdge[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  }
  std::vector<char> taken(s.triangles.size(), 0);
  std::vector<int> local(s.positions.size(), -1);
  std::deque<size_t> queue{seed};
  taken[seed] = 1;
  RegionMesh out;
  while (!queue.empty() && out.triangles.size() < count) {
    const size_t f = queue.front();
    queue.pop_front();
    std::array<int, 3> mapped{};
    for (int k = 0; k < 3; ++k) {
      const int v = s.triangles[f][k];
      if (local[v] < 0) {
        local[v] = static_cast<int>(out.positions.size());
        out.positions.push_back(s.positions[v]);
        out.normals.push_back(s.normals[v]);
        out.vertexIds.push_back(s.vertexIds[v]);
      }
      mapped[k] = local[v];
      const int w = s.triangles[f][(k + 1) % 3];
      for (size_t g : byEdge[{std::min(v, w), std::max(v, w)}]) {
        if (!taken[g]) taken[g] = 1, queue.push_back(g);
      }
    }
    out.triangles.push_back(mapped);
  }
  return out;
}

// The timing loops of every codec: encoding `region` under `header` at
// `level` (the meshopt codec checks and ignores it), with its size per
// triangle, and decoding that encoding.
void timeEncode(benchmark::State& state, const RegionHeader& header, const RegionMesh& region, int level) {
  size_t bytes = 0;
  for (auto _ : state) {
    auto encoded = encodeRegion(header, region, level);
    if (!encoded.isOk()) {
      state.SkipWithError(encoded.status().toString().c_str());
      break;
    }
    bytes = encoded->size();
    benchmark::DoNotOptimize(encoded->data());
  }
  state.counters["triangles"] = static_cast<double>(region.triangles.size());
  state.counters["bytes"] = static_cast<double>(bytes);
  state.counters["bytes_per_tri"] = static_cast<double>(bytes) / static_cast<double>(region.triangles.size());
}

void timeDecode(benchmark::State& state, const RegionHeader& header, const RegionMesh& region, int level) {
  const auto encoded = encodeRegion(header, region, level);
  if (!encoded.isOk()) {
    state.SkipWithError(encoded.status().toString().c_str());
    return;
  }
  for (auto _ : state) {
    auto decoded = decodeRegion(*encoded);
    benchmark::DoNotOptimize(decoded);
  }
  state.counters["bytes"] = static_cast<double>(encoded->size());
}

const RegionMesh& regionOf(const benchmark::State& state) {
  return input().regions.at(static_cast<int>(state.range(0)));
}

void encode(benchmark::State& state) {
  timeEncode(state, input().header, regionOf(state), static_cast<int>(state.range(1)));
}

void decode(benchmark::State& state) {
  timeDecode(state, input().header, regionOf(state), static_cast<int>(state.range(1)));
}

// The same regions in the meshopt codec, which has no levels.
RegionHeader meshoptHeader() {
  RegionHeader header = input().header;
  header.codec = RegionCodec::kMeshopt;
  return header;
}

void encodeMeshopt(benchmark::State& state) {
  timeEncode(state, meshoptHeader(), regionOf(state), kDefaultRegionCompressionLevel);
}

void decodeMeshopt(benchmark::State& state) {
  timeDecode(state, meshoptHeader(), regionOf(state), kDefaultRegionCompressionLevel);
}

// With --benchmark_repetitions, the minimum is the figure least disturbed by
// other work on a shared machine; the median is reported beside it.
double minimum(const std::vector<double>& v) {
  return *std::min_element(v.begin(), v.end());
}

BENCHMARK(encode)
    ->Name("Encode")
    ->ArgsProduct({{512, 2048, 8192}, benchmark::CreateDenseRange(0, 10, 1)})
    ->ArgNames({"tris", "level"})
    ->ComputeStatistics("min", minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(decode)
    ->Name("Decode")
    ->ArgsProduct({{512, 2048, 8192}, benchmark::CreateDenseRange(0, 10, 1)})
    ->ArgNames({"tris", "level"})
    ->ComputeStatistics("min", minimum)
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(encodeMeshopt)
    ->Name("EncodeMeshopt")
    ->ArgsProduct({{512, 2048, 8192}})
    ->ArgNames({"tris"})
    ->ComputeStatistics("min", minimum)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(decodeMeshopt)
    ->Name("DecodeMeshopt")
    ->ArgsProduct({{512, 2048, 8192}})
    ->ArgNames({"tris"})
    ->ComputeStatistics("min", minimum)
    ->Unit(benchmark::kMicrosecond);

// The decoded error over the whole surface at the default level, against
// the grid's bound and the target of 1e-4 of the diagonal
// (kDefaultMaxErrorFraction).
void reportQuantizationError(const Vec3& lo, const Vec3& hi) {
  const Input& in = input();
  auto encoded = encodeRegion(in.header, in.surface);
  auto decoded = encoded.isOk() ? decodeRegion(*encoded) : encoded.status();
  if (!decoded.isOk()) {
    std::fprintf(stderr, "tessera_bench_region: %s\n", decoded.status().toString().c_str());
    return;
  }
  std::map<uint64_t, size_t> byId;
  for (size_t i = 0; i < in.surface.vertexIds.size(); ++i) byId[in.surface.vertexIds[i]] = i;
  double position = 0.0, normal = 0.0;
  const RegionMesh& out = decoded->second;
  for (size_t i = 0; i < out.positions.size(); ++i) {
    const size_t j = byId.at(out.vertexIds[i]);
    position = std::max(position, (out.positions[i] - in.surface.positions[j]).norm());
    normal = std::max(normal, std::atan2(cross(out.normals[i], in.surface.normals[j]).norm(),
                                         dot(out.normals[i], in.surface.normals[j])));
  }
  const double diagonal = (hi - lo).norm();
  std::printf(
      "whole surface, %zu triangles, level %d: %zu bytes; %d position bits, max position error %.3g = %.3g "
      "of the diagonal (bound %.3g), max normal error %.3f degrees (%d bits)\n",
      in.surface.triangles.size(), kDefaultRegionCompressionLevel, encoded->size(),
      in.header.grid.positionBits, position, position / diagonal,
      in.header.grid.maxPositionError() / diagonal, normal * 180.0 / M_PI, in.header.grid.normalBits);
}

}  // namespace

int main(int argc, char** argv) {
  auto mesh = tessera::bench::benchMesh(argc, argv, "tessera_bench_region");
  if (!mesh.isOk()) return 1;
  auto refiner = LoopRefiner::create(BaseTopology::fromBaseMesh(*mesh), LoopOptions{}, {.levels = kLevel});
  auto limit = refiner.isOk() ? refiner->limitSurface(refiner->refinePoints(mesh->positions()))
                              : Expected<SurfaceMesh>(refiner.status());
  if (!limit.isOk()) {
    std::fprintf(stderr, "tessera_bench_region: %s\n", limit.status().toString().c_str());
    return 1;
  }
  Input& in = input();
  in.surface.positions = limit->positions;
  in.surface.normals = limit->normals;
  in.surface.triangles = limit->triangles;
  // Crease copies (appended after the level's vertices) pick the id of
  // nothing in particular; fandisk without tags has none.
  for (size_t i = 0; i < limit->positions.size(); ++i)
    in.surface.vertexIds.push_back(VertexId(kLevel, i).packed());
  Vec3 lo = limit->positions[0], hi = lo;
  for (const Vec3& p : limit->positions) lo.minimize(p), hi.maximize(p);
  auto grid = gridFor(lo, hi);
  if (!grid.isOk()) {
    std::fprintf(stderr, "tessera_bench_region: %s\n", grid.status().toString().c_str());
    return 1;
  }
  in.header.grid = *grid;
  in.header.regionId = 1;
  in.header.documentVersion = 1;
  for (int size : kRegionSizes) in.regions[size] = patch(in.surface, in.surface.triangles.size() / 3, size);
  std::printf("limit surface at level %d, %zu triangles\n", kLevel, in.surface.triangles.size());
  reportQuantizationError(lo, hi);

  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
