// How far a tile (tile_tree.h) may lie from the limit surface, and where it
// is: what a view needs to decide a tile's level by screen-space error
// (docs/VIEWS.md "The error of a tile").
//
// A tile shows its faces flat between the limits of their corners. Its
// error is measured at the next level: for every edge of every face, the
// distance from the limit of the vertex the next level puts on that edge to
// the edge's midpoint, the largest over the tile, times 4/3. For a surface
// that is locally quadratic the largest departure of a flat triangle lies
// at most 4/3 times as far as its edge midpoints' (at the circumcentre of an
// acute triangle; on an edge otherwise), so this bounds the error up to
// the higher-order terms; tile_error_test measures how close it comes
// against exact limits three levels finer. At the document's deepest level
// there is no next level: the error is that of the tile's parent over 4, the
// quadratic rate, an estimate (and no view can refine it anyway).
//
// The sphere holds the tile's vertices, grown by its error.
#pragma once

#include "core/document/document.h"
#include "core/tessellation/region_codec.h"
#include "core/view/tile_tree.h"
#include "core/view/view.h"

namespace tessera {

struct TileBounds {
  BoundingSphere sphere;
  double error = 0;      // world units, as stated above
  double midpoints = 0;  // the largest midpoint departure itself
};

// `mesh` is the tile's (buildTile). Grows the hierarchy to the next level
// under the tile. `parentError` serves the deepest level only.
Expected<TileBounds> tileBounds(Document& doc, const TileTree& tree, const TileKey& tile,
                                const RegionMesh& mesh, double parentError = 0);

}  // namespace tessera
