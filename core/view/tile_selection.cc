#include "core/view/tile_selection.h"

#include <algorithm>

namespace tessera {

namespace {

constexpr double kBudgetStep = 1.25;
constexpr int kBudgetSteps = 60;

Expected<TileSelection> selectAt(const View& view, TileCatalogue& tiles, double tolerance) {
  TileSelection out;
  out.tolerancePixels = tolerance;
  // Level by level, so that the hierarchy grows once per level for every
  // tile of it (TileCatalogue::prepare).
  std::vector<TileKey> frontier = tiles.tree().roots();
  while (!frontier.empty()) {
    tiles.prepare(frontier);
    std::vector<TileKey> next;
    for (const TileKey& key : frontier) {
      TESSERA_ASSIGN_OR_RETURN(const Tile* tile, tiles.get(key));
      SelectedTile s{key, !view.outside(tile->bounds.sphere), 0,
                     dot(tile->bounds.sphere.centre - view.eye, view.forward.normalized())};
      s.projectedError = view.projectedError(tile->bounds.error, tile->bounds.sphere);
      if (s.visible && s.projectedError > tolerance) {
        auto children = tiles.tree().children(key);
        if (!children.empty()) {
          next.insert(next.end(), children.begin(), children.end());
          continue;
        }
      }
      out.triangles += tile->triangles;
      out.tiles.push_back(s);
    }
    frontier = std::move(next);
  }
  std::stable_sort(out.tiles.begin(), out.tiles.end(), [](const SelectedTile& a, const SelectedTile& b) {
    if (a.visible != b.visible) return a.visible;
    if (a.key.level != b.key.level) return a.key.level < b.key.level;
    return a.depth < b.depth;
  });
  return out;
}

}  // namespace

Expected<TileSelection> selectTiles(const View& view, TileCatalogue& tiles, int64_t budget) {
  TESSERA_RETURN_IF_ERROR(view.check());
  double tolerance = view.tolerancePixels;
  for (int step = 0;; ++step) {
    TESSERA_ASSIGN_OR_RETURN(TileSelection s, selectAt(view, tiles, tolerance));
    if (budget <= 0 || s.triangles <= budget || step == kBudgetSteps) return s;
    tolerance *= kBudgetStep;
  }
}

}  // namespace tessera
