// Client-side refinement (docs/VIEWER.md): the bytes a thin client saves by
// subscribing to a coarser LOD, against how far what it draws is from the
// fine surface -- coarse as received, and coarse refined with 1 and 2
// splits per edge (core/render/dynamic_refinement.h) -- and the refinement's time per frame.
//
//   build/release/bench/tessera_bench_refine [--mesh PATH] [benchmark flags]
//
// Documents: the creased cube (tests/data/cube.obj + cube.tags) and fandisk
// (or --mesh). Each is tessellated at a fine profile and at coarser ones;
// every region is encoded with the region codec on the document's grid
// (bytes), the coarse regions are decoded (what a client holds) and
// refined region by region with BorderEdges, as tessera-view does. The
// difference is core/render/surface_distance.h (RMS over the drawn
// surface, two-sided max) against the fine tessellation, divided by its
// bounding-box diagonal. One benchmark per (document, coarse profile,
// splits) times one frame's refinement of all regions.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_mesh.h"
#include "core/document/document.h"
#include "core/io/tag_file.h"
#include "core/render/dynamic_refinement.h"
#include "core/render/surface_distance.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/tessellation.h"
#include "core/util/file_io.h"

namespace {

using namespace tessera;

struct Soup {
  std::vector<Vec3> positions;
  std::vector<std::array<int, 3>> triangles;
  void add(const std::vector<Vec3>& p, const std::vector<std::array<int, 3>>& t) {
    const int base = static_cast<int>(positions.size());
    positions.insert(positions.end(), p.begin(), p.end());
    for (const auto& tri : t) triangles.push_back({tri[0] + base, tri[1] + base, tri[2] + base});
  }
  MeshView view() const { return {positions, triangles}; }
};

struct Row {
  std::string document, profile;
  int splits = 0;
  int64_t triangles = 0;
  uint64_t bytes = 0, fineBytes = 0;
  double rms = 0, max = 0;  // over the fine surface's diagonal
  double frameMs = 0;       // median CPU time to refine all regions (one frame)
};

struct Coarse {
  std::string document, profile;
  std::map<uint64_t, RegionMesh> regions;  // decoded
  Soup fine;
  double diagonal = 1;
  uint64_t bytes = 0, fineBytes = 0;
};

std::vector<Coarse>& coarseCases() {
  static std::vector<Coarse> cases;
  return cases;
}

std::vector<Row>& rows() {
  static std::vector<Row> r;
  return r;
}

// One frame of tessera-view with --refine: every region refined on its
// own, with the border normals of all.
std::vector<RefinedMesh> refineFrame(const std::map<uint64_t, RegionMesh>& regions, int splits) {
  std::vector<RefineInput> inputs;
  inputs.reserve(regions.size());
  for (const auto& [id, m] : regions) inputs.push_back({m.positions, m.normals, m.triangles});
  auto refined = refineMeshes(inputs, {.maxSplits = splits});
  return refined.isOk() ? std::move(*refined) : std::vector<RefinedMesh>{};
}

// Encodes every region on the document's grid; the sum of their sizes,
// and optionally the decoded regions.
Expected<uint64_t> encodeAll(const Document& doc, const Tessellation& t,
                             std::map<uint64_t, RegionMesh>* decoded) {
  TESSERA_ASSIGN_OR_RETURN(const QuantizationGrid grid, documentGrid(doc));
  uint64_t bytes = 0;
  for (const auto& [id, mesh] : t.regions()) {
    const RegionHeader header{.regionId = id, .documentVersion = 1, .profile = t.profile(), .grid = grid};
    TESSERA_ASSIGN_OR_RETURN(const std::string encoded, encodeRegion(header, mesh));
    bytes += encoded.size();
    if (!decoded) continue;
    TESSERA_ASSIGN_OR_RETURN(auto back, decodeRegion(encoded));
    (*decoded)[id] = std::move(back.second);
  }
  return bytes;
}

// CPU time (single-threaded), not wall time: the machines this runs on are
// shared, and waiting for a core is not refinement's cost.
double medianFrameMs(const Coarse& c, int splits) {
  std::vector<double> ms;
  for (int i = 0; i < 15; ++i) {
    const std::clock_t start = std::clock();
    benchmark::DoNotOptimize(refineFrame(c.regions, splits));
    ms.push_back(1000.0 * static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC);
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

Status measure(const std::string& name, Document& doc, const LodProfile& fineProfile,
               const std::vector<LodProfile>& coarseProfiles) {
  TESSERA_ASSIGN_OR_RETURN(Tessellation fine, Tessellation::build(doc, fineProfile));
  TESSERA_ASSIGN_OR_RETURN(const uint64_t fineBytes, encodeAll(doc, fine, nullptr));
  Soup fineSoup;
  for (const auto& [id, m] : fine.regions()) fineSoup.add(m.positions, m.triangles);
  Vec3 lo = fineSoup.positions[0], hi = lo;
  for (const Vec3& p : fineSoup.positions) lo.minimize(p), hi.maximize(p);
  rows().push_back(
      {name, fineProfile.key() + " (fine)", 0, fine.numTriangles(), fineBytes, fineBytes, 0, 0, 0});
  for (const LodProfile& profile : coarseProfiles) {
    TESSERA_ASSIGN_OR_RETURN(Tessellation t, Tessellation::build(doc, profile));
    Coarse c{name, profile.key(), {}, fineSoup, (hi - lo).norm(), 0, fineBytes};
    TESSERA_ASSIGN_OR_RETURN(c.bytes, encodeAll(doc, t, &c.regions));
    for (int splits = 0; splits <= 2; ++splits) {
      Soup drawn;
      if (splits == 0) {
        for (const auto& [id, m] : c.regions) drawn.add(m.positions, m.triangles);
      } else {
        for (const RefinedMesh& r : refineFrame(c.regions, splits)) drawn.add(r.positions, r.triangles);
      }
      const SurfaceDistance d = surfaceDistance(drawn.view(), fineSoup.view());
      rows().push_back({name, c.profile, splits, static_cast<int64_t>(drawn.triangles.size()), c.bytes,
                        fineBytes, d.rms / c.diagonal, d.max / c.diagonal,
                        splits ? medianFrameMs(c, splits) : 0});
    }
    coarseCases().push_back(std::move(c));
  }
  return Status::ok();
}

void BM_RefineFrame(benchmark::State& state, const Coarse* c, int splits) {
  int64_t triangles = 0;
  for (auto _ : state) {
    triangles = 0;
    for (const RefinedMesh& r : refineFrame(c->regions, splits))
      triangles += static_cast<int64_t>(r.triangles.size());
  }
  for (const Row& r : rows()) {
    if (r.document != c->document || r.profile != c->profile || r.splits != splits) continue;
    state.counters["rms_per_diag"] = r.rms;
    state.counters["max_per_diag"] = r.max;
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["bytes_coarse"] = static_cast<double>(c->bytes);
  state.counters["bytes_fine"] = static_cast<double>(c->fineBytes);
  state.counters["saved_pct"] =
      100.0 * (1.0 - static_cast<double>(c->bytes) / static_cast<double>(c->fineBytes));
}

void printTable() {
  std::printf("\n%-8s %-40s %6s %9s %10s %7s %11s %11s %9s\n", "document", "profile", "splits", "triangles",
              "bytes", "saved", "rms/diag", "max/diag", "ms/frame");
  for (const Row& r : rows()) {
    std::printf("%-8s %-40s %6d %9lld %10llu %6.1f%% %11.3e %11.3e %9.2f\n", r.document.c_str(),
                r.profile.c_str(), r.splits, static_cast<long long>(r.triangles),
                static_cast<unsigned long long>(r.bytes),
                100.0 * (1.0 - static_cast<double>(r.bytes) / static_cast<double>(r.fineBytes)), r.rms, r.max,
                r.frameMs);
  }
}

Expected<Document> cubeDocument() {
  const std::string dir = TESSERA_SOURCE_TESTDATA_DIR;
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, importMesh(dir + "/cube.obj"));
  TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(dir + "/cube.tags"));
  TESSERA_ASSIGN_OR_RETURN(const auto tags, parseTags(text, "cube.tags"));
  TESSERA_RETURN_IF_ERROR(applyTags(tags, "cube.tags", mesh));
  return Document::create(mesh, {.maxLevel = 6});
}

Status run(int& argc, char** argv) {
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, bench::benchMesh(argc, argv, "tessera_bench_refine"));
  TESSERA_ASSIGN_OR_RETURN(Document cube, cubeDocument());
  TESSERA_ASSIGN_OR_RETURN(Document fandisk, Document::create(mesh, {.maxLevel = 4}));
  TESSERA_RETURN_IF_ERROR(measure("cube", cube, {.baseLevel = 5, .maxLevel = 6, .angleThresholdDegrees = 3},
                                  {{.baseLevel = 1, .maxLevel = 3, .angleThresholdDegrees = 15},
                                   {.baseLevel = 1, .maxLevel = 2, .angleThresholdDegrees = 20}}));
  TESSERA_RETURN_IF_ERROR(measure("fandisk", fandisk,
                                  {.baseLevel = 2, .maxLevel = 3, .angleThresholdDegrees = 3},
                                  {{.baseLevel = 1, .maxLevel = 2, .angleThresholdDegrees = 15},
                                   {.baseLevel = 0, .maxLevel = 1, .angleThresholdDegrees = 20}}));
  return Status::ok();
}

}  // namespace

int main(int argc, char** argv) {
  const Status status = run(argc, argv);
  if (!status.isOk()) {
    std::fprintf(stderr, "tessera_bench_refine: %s\n", status.toString().c_str());
    return 1;
  }
  for (const Coarse& c : coarseCases()) {
    for (int splits = 1; splits <= 2; ++splits) {
      const std::string name =
          "BM_RefineFrame/" + c.document + "/" + c.profile + "/splits:" + std::to_string(splits);
      benchmark::RegisterBenchmark(name.c_str(), BM_RefineFrame, &c, splits)->Unit(benchmark::kMillisecond);
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  printTable();
  return 0;
}
