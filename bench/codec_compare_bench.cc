// Draco against meshopt regions (docs/REGION_ENCODING.md, "meshopt
// regions"; docs/PERFORMANCE.md, "Region codecs"), both in the same run, on
// the same document, edits and regions:
//   - EditToDelta/L/C: a single-vertex edit at level L until every changed
//     region is re-tessellated and encoded in codec C (0 Draco at the
//     default level, 1 meshopt), regions that kept their layout without
//     ids as a server sends them; counters: delta bytes, the encode's
//     median, and the median time a C++ client takes to decode the delta's
//     regions (decodeRegion, as client/lib/document_view.cc does);
//   - Snapshot/C: every region with ids: bytes, encode and decode time,
//     and the bytes after zlib's deflate (level 6) of the regions one after
//     another, for a link that compresses (the server's frames are not).
// One thread throughout, so the codecs are compared on equal terms.
//
//   build/release/bench/tessera_bench_codecs [--mesh PATH] [benchmark flags]
#include <benchmark/benchmark.h>
#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "bench/bench_edit.h"
#include "bench/bench_mesh.h"
#include "bench/percentile.h"
#include "core/document/document.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/tessellation.h"

namespace {

using namespace tessera;
using Clock = std::chrono::steady_clock;

// Regions per base face and below it (max level above 3: no groups), as
// a viewer of a detailed document subscribes.
const LodProfile kProfile{.baseLevel = 2, .maxLevel = 4, .angleThresholdDegrees = 10};

struct State {
  std::optional<Document> doc;
  std::optional<Tessellation> tessellation;
  QuantizationGrid grid;
  uint64_t version = 1;
  std::map<uint64_t, uint64_t> layout;  // region -> layout version
};

State& state() {
  static State s;
  return s;
}

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

RegionCodec codecOf(int64_t arg) {
  return arg == 1 ? RegionCodec::kMeshopt : RegionCodec::kDraco;
}

std::string encodeOrDie(const RegionHeader& header, const RegionMesh& mesh) {
  auto bytes = encodeRegion(header, mesh);
  if (!bytes.isOk()) {
    std::fprintf(stderr, "encode: %s\n", bytes.status().toString().c_str());
    std::exit(1);
  }
  return std::move(*bytes);
}

void decodeOrDie(const std::string& bytes) {
  auto decoded = decodeRegion(bytes);
  if (!decoded.isOk()) {
    std::fprintf(stderr, "decode: %s\n", decoded.status().toString().c_str());
    std::exit(1);
  }
  benchmark::DoNotOptimize(decoded->second.positions.data());
}

void editToDelta(benchmark::State& bm) {
  const int level = static_cast<int>(bm.range(0));
  const RegionCodec codec = codecOf(bm.range(1));
  State& s = state();
  Document& doc = *s.doc;
  std::mt19937 rng(7 + level);  // the same edits for both codecs
  std::vector<double> total, encode, decode;
  double bytes = 0, regions = 0;
  for (auto _ : bm) {
    const tessera::bench::LimitEdit edit = tessera::bench::randomLimitEdit(doc, level, rng);
    const auto start = Clock::now();
    auto id = doc.moveToLimit(std::span(&edit.vertex, 1), edit.target);
    auto changes = s.tessellation->update(doc);
    ++s.version;
    const auto encoding = Clock::now();
    std::vector<std::string> payloads;
    for (uint64_t region : changes->changed) {
      const bool relaid = std::binary_search(changes->relaid.begin(), changes->relaid.end(), region);
      if (relaid || !s.layout.count(region)) s.layout[region] = s.version;
      RegionHeader header{.regionId = region,
                          .documentVersion = s.version,
                          .layoutVersion = s.layout[region],
                          .profile = kProfile,
                          .grid = s.grid,
                          .idsInline = relaid};
      header.codec = codec;
      payloads.push_back(encodeOrDie(header, s.tessellation->regions().at(region)));
    }
    const double encodeSeconds = secondsSince(encoding);
    total.push_back(secondsSince(start));
    bm.SetIterationTime(total.back());
    encode.push_back(encodeSeconds);
    const auto decoding = Clock::now();
    for (const std::string& p : payloads) decodeOrDie(p);
    decode.push_back(secondsSince(decoding));
    for (const std::string& p : payloads) bytes += static_cast<double>(p.size());
    regions += static_cast<double>(payloads.size());
    (void)doc.remove(*id);  // restored outside the timing
    auto restored = s.tessellation->update(doc);
    ++s.version;
    for (uint64_t region : restored->relaid) s.layout[region] = s.version;
  }
  const double n = static_cast<double>(total.size());
  bm.counters["p50_us"] = tessera::bench::percentile(total, 0.5) * 1e6;
  bm.counters["encode_p50_us"] = tessera::bench::percentile(encode, 0.5) * 1e6;
  bm.counters["decode_p50_us"] = tessera::bench::percentile(decode, 0.5) * 1e6;
  bm.counters["delta_bytes"] = bytes / n;
  bm.counters["regions"] = regions / n;
}

void snapshot(benchmark::State& bm) {
  const RegionCodec codec = codecOf(bm.range(0));
  State& s = state();
  std::vector<double> encode, decode;
  size_t bytes = 0, deflated = 0;
  for (auto _ : bm) {
    std::vector<std::string> payloads;
    const auto start = Clock::now();
    for (const auto& [region, mesh] : s.tessellation->regions()) {
      RegionHeader header{
          .regionId = region, .documentVersion = s.version, .profile = kProfile, .grid = s.grid};
      header.codec = codec;
      payloads.push_back(encodeOrDie(header, mesh));
    }
    encode.push_back(secondsSince(start));
    bm.SetIterationTime(encode.back());
    const auto decoding = Clock::now();
    for (const std::string& p : payloads) decodeOrDie(p);
    decode.push_back(secondsSince(decoding));
    bytes = 0;
    for (const std::string& p : payloads) bytes += p.size();
    if (deflated == 0) {
      std::string all;
      for (const std::string& p : payloads) all += p;
      uLongf size = compressBound(all.size());
      std::string out(size, '\0');
      if (compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(all.data()),
                    all.size(), 6) == Z_OK)
        deflated = size;
    }
  }
  bm.counters["bytes"] = static_cast<double>(bytes);
  bm.counters["bytes_deflated"] = static_cast<double>(deflated);
  bm.counters["encode_ms"] = tessera::bench::percentile(encode, 0.5) * 1e3;
  bm.counters["decode_ms"] = tessera::bench::percentile(decode, 0.5) * 1e3;
  bm.counters["triangles"] = static_cast<double>(s.tessellation->numTriangles());
  bm.counters["regions"] = static_cast<double>(s.tessellation->regions().size());
}

BENCHMARK(editToDelta)
    ->Name("EditToDelta")
    ->ArgsProduct({{0, 2, 3}, {0, 1}})
    ->Iterations(200)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(snapshot)
    ->Name("Snapshot")
    ->Arg(0)
    ->Arg(1)
    ->Iterations(3)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  auto mesh = tessera::bench::benchMesh(argc, argv, "tessera_bench_codecs");
  if (!mesh.isOk()) return 1;
  auto grid = tessera::bench::gridAround(*mesh);
  if (!grid.isOk()) return 1;
  State& s = state();
  auto doc = Document::create(*mesh, {.maxLevel = 5, .uniformLevel = 4});
  if (!doc.isOk()) {
    std::fprintf(stderr, "tessera_bench_codecs: %s\n", doc.status().toString().c_str());
    return 1;
  }
  s.doc.emplace(std::move(*doc));
  s.grid = *grid;
  auto t = Tessellation::build(*s.doc, kProfile);
  if (!t.isOk()) {
    std::fprintf(stderr, "tessera_bench_codecs: %s\n", t.status().toString().c_str());
    return 1;
  }
  s.tessellation.emplace(std::move(*t));
  for (const auto& [region, mesh] : s.tessellation->regions()) s.layout[region] = s.version;
  std::printf("displayed (%s): %lld triangles in %zu regions; grid %d position bits\n",
              kProfile.key().c_str(), static_cast<long long>(s.tessellation->numTriangles()),
              s.tessellation->regions().size(), s.grid.positionBits);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
