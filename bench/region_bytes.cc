// What a profile's regions cost on the wire against one Draco mesh of the
// same surface, and what an edit's delta costs at each level
// (docs/PERFORMANCE.md "Region groups").
//
//   build/release/bench/tessera_bench_region_bytes [--mesh PATH] BASE MAX ANGLE [EDITS]
//
// The document is the mesh untagged, held to MAX. Its regions are encoded as
// a server encodes them (the document's grid; ids inline, as lattice points
// where a region is one root face; without ids for a display-only profile),
// each counted with the 12 bytes of its Region message and frame share. The
// reference is `tessera doc export --adaptive --draco` of the same
// tessellation: one GLB, 16-bit positions, no ids. Then EDITS moves per
// level (1 % of the bounding diagonal, random vertices, seed 7) each update
// the tessellation; the regions they change are encoded as a delta encodes
// them (ids left out where the layout held).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "bench/bench_mesh.h"
#include "core/document/document.h"
#include "core/io/mesh_export.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/region_lattice.h"
#include "core/tessellation/tessellation.h"
#include "core/util/file_io.h"

namespace {

using namespace tessera;

constexpr size_t kMessageBytes = 12;  // region_id, the bytes' tag and length, the frame's share

size_t encodedBytes(const Document& doc, const Tessellation& t, const QuantizationGrid& grid,
                    const LodProfile& profile, uint64_t region, bool idsInline) {
  RegionHeader header{region, 2, 1, profile, grid, idsInline};
  if (profile.vertexIds && idsInline) {
    auto frame = regionFrame(doc.hierarchy(), doc.counts(), FaceId::fromPacked(region));
    if (frame.isOk()) header.frame = *frame;
  }
  auto bytes = encodeRegion(header, t.regions().at(region));
  if (!bytes.isOk() && header.frame) {
    header.frame.reset();  // a group of faces: ids as labels
    bytes = encodeRegion(header, t.regions().at(region));
  }
  if (!bytes.isOk()) {
    std::fprintf(stderr, "region %llu: %s\n", static_cast<unsigned long long>(region),
                 bytes.status().toString().c_str());
    std::exit(1);
  }
  return bytes->size() + kMessageBytes;
}

}  // namespace

int main(int argc, char** argv) {
  auto mesh = bench::benchMesh(argc, argv, "tessera_bench_region_bytes");
  if (!mesh.isOk()) return 1;
  if (argc < 4) {
    std::fprintf(stderr, "usage: tessera_bench_region_bytes [--mesh PATH] BASE MAX ANGLE [EDITS]\n");
    return 2;
  }
  LodProfile profile;
  profile.baseLevel = std::atoi(argv[1]);
  profile.maxLevel = std::atoi(argv[2]);
  profile.angleThresholdDegrees = std::atof(argv[3]);
  profile.triangleBudget = 100'000'000;
  const int edits = argc > 4 ? std::atoi(argv[4]) : 20;
  auto doc = Document::create(*mesh, {.maxLevel = profile.maxLevel});
  if (!doc.isOk()) return std::fprintf(stderr, "%s\n", doc.status().toString().c_str()), 1;
  auto grid = documentGrid(*doc);
  if (!grid.isOk()) return 1;
  auto t = Tessellation::build(*doc, profile);
  if (!t.isOk()) return std::fprintf(stderr, "%s\n", t.status().toString().c_str()), 1;

  const std::string glb = (std::filesystem::temp_directory_path() / "tessera-region-bytes.glb").string();
  ExportOptions options;
  options.draco = true;
  if (!exportMesh(t->surface(), glb, options).isOk()) return 1;
  const size_t reference = readFile(glb)->size();
  std::filesystem::remove(glb);

  size_t withIds = 0, withoutIds = 0;
  LodProfile displayOnly = profile;
  displayOnly.vertexIds = false;
  for (const auto& [region, m] : t->regions()) {
    withIds += encodedBytes(*doc, *t, *grid, profile, region, true);
    withoutIds += encodedBytes(*doc, *t, *grid, displayOnly, region, true);
  }
  std::printf("profile %s\n", profile.describe().c_str());
  std::printf("regions %zu, triangles %lld (%.1f per region)\n", t->regions().size(),
              static_cast<long long>(t->numTriangles()),
              static_cast<double>(t->numTriangles()) / t->regions().size());
  std::printf("one Draco GLB of the surface   %10zu bytes\n", reference);
  std::printf("regions, display-only          %10zu bytes  %.2fx\n", withoutIds,
              static_cast<double>(withoutIds) / reference);
  std::printf("regions, with vertex ids       %10zu bytes  %.2fx\n", withIds,
              static_cast<double>(withIds) / reference);

  // Deltas: per edit level, the regions an edit changes and their bytes.
  std::mt19937 rng(7);
  Vec3 lo = doc->basePoints()[0], hi = lo;
  for (const Vec3& p : doc->basePoints())
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  const double step = 0.01 * (hi - lo).norm();
  std::printf("edit level | regions per edit | delta bytes per edit (ids where relaid)\n");
  for (int level = 0; level < profile.maxLevel; ++level) {
    size_t regions = 0, bytes = 0;
    for (int e = 0; e < edits; ++e) {
      const VertexId v(level, rng() % doc->counts().vertices(level));
      const Vec3 d(step * (rng() % 3 - 1.0), step, -step);
      if (!doc->moveBy(std::span<const VertexId>(&v, 1), d).isOk()) continue;
      auto changes = t->update(*doc);
      if (!changes.isOk()) return std::fprintf(stderr, "%s\n", changes.status().toString().c_str()), 1;
      for (uint64_t region : changes->changed) {
        const bool relaid = std::binary_search(changes->relaid.begin(), changes->relaid.end(), region);
        bytes += encodedBytes(*doc, *t, *grid, profile, region, relaid);
        ++regions;
      }
    }
    std::printf("%10d | %16.1f | %10.0f\n", level, static_cast<double>(regions) / edits,
                static_cast<double>(bytes) / edits);
  }
  return 0;
}
