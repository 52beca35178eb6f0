// Which tiles a view needs (docs/VIEWS.md), after 3D Tiles'
// refinement by screen-space error: from the roots down, a tile in the view
// frustum is replaced by its children while its error, projected at its
// sphere's nearest depth, exceeds the view's tolerance. A tile wholly
// outside the frustum is kept as it is: the coarsest the tree offers there,
// enough to turn towards. Under a triangle budget the tolerance is raised
// by steps of 1.25 until the selection fits, so quality falls evenly over
// the screen and no visible part is dropped.
//
// The result comes in the order it should be sent: visible before hidden,
// coarse before fine, near before far.
//
// A walk may be given an allowance of tiles to build (those the catalogue
// does not hold, shared by all its views): a tile it would refine whose
// children the allowance has no room for is kept as it is, a coarser cut of
// the same surface, and its selection is marked incomplete. Selecting again
// goes on where it stopped, since the tiles built meanwhile are held; so a
// camera that reaches new parts of a large document gets its picture in
// steps of bounded work (docs/VIEWS.md "The server"). A walk always refines
// at least one tile that needs it, whatever its allowance.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/util/status.h"
#include "core/view/tile_catalogue.h"
#include "core/view/view.h"

namespace tessera {

struct SelectedTile {
  TileKey key;
  bool visible = true;
  double projectedError = 0;  // pixels, at the sphere's nearest depth
  double depth = 0;           // of the sphere's centre along the view
};

struct TileSelection {
  std::vector<SelectedTile> tiles;
  int64_t triangles = 0;
  double tolerancePixels = 0;  // the view's, or what the budget raised it to
  bool complete = true;        // false: the walk's allowance held some tiles back
};

// What a view sees of one tile: whether it is in the frustum, its error in
// pixels and its depth.
SelectedTile judgeTile(const View& view, const TileKey& key, const TileBounds& bounds);
// The walk's rule for one tile so judged: whether the view replaces it by
// its children (it is in the frustum, and its error projects above the
// tolerance or a tag deep under it has no bound), given that it has children.
bool refinesTile(const SelectedTile& judged, const TileBounds& bounds, double tolerancePixels);

// `budget` <= 0: none. Errors: a bad view, a tile that cannot be built.
Expected<TileSelection> selectTiles(const View& view, TileCatalogue& tiles, int64_t budget = 0);
// The same for several views at once, equal to selecting each alone: the
// hierarchy grows once per level for all of them (a server choosing again
// for every viewer after an edit). `newTiles` >= 0: the walk's allowance of
// tiles to build, as above; negative: none. `stopBuilding`, if given, is
// asked before each further refinement that would build tiles (the first
// is always made): true ends the building as a spent allowance does, for
// a caller whose other work has come to wait.
Expected<std::vector<TileSelection>> selectTilesForEach(std::span<const View> views, TileCatalogue& tiles,
                                                        std::span<const int64_t> budgets,
                                                        int64_t newTiles = -1,
                                                        const std::function<bool()>& stopBuilding = {});

}  // namespace tessera
