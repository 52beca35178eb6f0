// A tile as a region payload on the wire (docs/VIEWS.md "Tiles on the
// wire", docs/REGION_ENCODING.md): the same self-describing Draco region
// as a profile's, named by the tile's region id (TileKey::regionId), with
// its ids inline (lattice points for a one-face tile, labels for a
// cluster), and the surface hash a receiver recomputes from what it decodes
// (docs/PROTOCOL.md 6.5). Positions are clamped to the document's grid as
// every region's are (document_bounds.h).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/document/document.h"
#include "core/tessellation/region_codec.h"
#include "core/util/status.h"
#include "core/view/tile_tree.h"

namespace tessera {

struct EncodedTile {
  std::shared_ptr<const std::string> bytes;
  uint64_t hash = 0;  // regionSurfaceHash of the decoded payload
  int64_t triangles = 0;
};

// `withIds` false: display only, no vertex ids (a third fewer bytes).
Expected<EncodedTile> encodeTile(const Document& doc, const TileKey& key, const RegionMesh& mesh,
                                 const QuantizationGrid& grid, uint64_t version, bool withIds = true);

}  // namespace tessera
