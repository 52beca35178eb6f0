#include "core/view/tile_encoding.h"

#include "core/tessellation/document_bounds.h"
#include "core/tessellation/region_lattice.h"
#include "core/tessellation/surface_hash.h"

namespace tessera {

Expected<EncodedTile> encodeTile(const Document& doc, const TileKey& key, const RegionMesh& mesh,
                                 const QuantizationGrid& grid, uint64_t version, bool withIds) {
  RegionHeader header;
  header.regionId = key.regionId();
  header.documentVersion = header.layoutVersion = version;
  // A preview (tile_preview.h) shows level-0 vertices, as its root does.
  const int level = key.isPreview() ? 0 : key.level;
  header.profile = {.baseLevel = level, .maxLevel = level, .vertexIds = withIds};
  header.grid = grid;
  if (withIds && key.level >= kTileDepth) {
    // One face's tile: its ids travel as points of that face's lattice.
    auto frame = regionFrame(doc.hierarchy(), doc.counts(), FaceId::fromPacked(key.face));
    if (frame.isOk()) header.frame = *frame;
  }
  const std::optional<RegionMesh> clamped = clampedToGrid(mesh, grid);
  const RegionMesh& shown = clamped ? *clamped : mesh;
  TESSERA_ASSIGN_OR_RETURN(std::string bytes, encodeRegion(header, shown));
  EncodedTile out;
  out.bytes = std::make_shared<const std::string>(std::move(bytes));
  out.hash = regionSurfaceHashOnGrid(shown, grid, withIds);
  out.triangles = static_cast<int64_t>(mesh.triangles.size());
  return out;
}

}  // namespace tessera
