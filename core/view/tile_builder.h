// A tile's mesh (tile_tree.h): the faces it covers, shown uniformly at its
// level, each vertex at its displayed limit (core/tessellation/
// displayed_vertices.h), so that a vertex two tiles share has bit-identical
// positions and normals in both, whatever their levels. The hierarchy is
// grown only where the tile lies: a view needs deep levels only where it
// looks.
#pragma once

#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/tessellation/region_codec.h"
#include "core/util/status.h"
#include "core/view/tile_tree.h"

namespace tessera {

// Errors: a tile the tree does not have, or a level beyond the document's.
Expected<RegionMesh> buildTile(Document& doc, const TileTree& tree, const TileKey& tile);

// The same for any faces of one level (`level`, which must be within the
// document's): what a tile shows, without a tile tree. `what` names them in
// errors.
Expected<RegionMesh> buildFacesAt(Document& doc, int level, const std::vector<FaceId>& faces,
                                  const std::string& what);

}  // namespace tessera
