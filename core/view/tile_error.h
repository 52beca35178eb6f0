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
// On the quad split (Catmull-Clark) a quad is shown as two triangles on its
// first diagonal, whose midpoint stands for the face's centre: the vertex
// the next level puts in the face is measured against it, so each triangle
// has its three edge midpoints measured and the same 4/3 holds. A base
// n-gon of other than four corners, shown as a fan, has no such place: its
// face vertex is measured against the nearest point of the fan, which
// bounds nothing under the argument above; tile_error_test measures the
// true error of such faces against the fan's nearest points too.
//
// Edits more than one level below the tile shape detail that the next level
// does not show. Let S be the limit surface, S' the one without those moves
// and D the sum of their offsets' sizes (L1 norms of local offsets, whose
// frames are orthonormal). Loop's basis functions are non-negative and sum
// to one, so |S - S'| <= D; the flat tile and its midpoints move by at most
// D too (Catmull-Clark's are non-negative and sum to one as well, creases
// included). So the error is 4/3 (m + 2D) + 2D = 4/3 m + 14/3 D, with m the
// midpoint departure measured on S. Tags that deep change the rules, not
// the points: no such bound, and a view refines the tile instead
// (docs/VIEWS.md "The error of a tile").
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
  // Edits more than one level below the tile, near it: the summed size of
  // their offsets, in the error as stated above; and whether a tag is among
  // them, whose effect has no such bound (a view refines the tile while it
  // is visible).
  double deepOffsets = 0;
  bool deepTags = false;
};

// `mesh` is the tile's (buildTile). The next level's vertices are read from
// the tile's level where Loop's stencils predict them (no edit, tag or
// ghost ring reaches them, no semi-sharp edge: core/loop/edge_child_limit.h);
// elsewhere, and on every Catmull-Clark document, the hierarchy grows to the
// next level under the tile.
// `parentError` serves the deepest level only.
Expected<TileBounds> tileBounds(Document& doc, const TileTree& tree, const TileKey& tile,
                                const RegionMesh& mesh, double parentError = 0);

}  // namespace tessera
