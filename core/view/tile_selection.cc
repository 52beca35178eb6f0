#include "core/view/tile_selection.h"

#include <algorithm>
#include <functional>
#include <set>

namespace tessera {

namespace {

constexpr double kBudgetStep = 1.25;
constexpr int kBudgetSteps = 60;

// Sending order: visible before hidden, coarse before fine, near before far.
void sortForSending(TileSelection& s) {
  std::stable_sort(s.tiles.begin(), s.tiles.end(), [](const SelectedTile& a, const SelectedTile& b) {
    if (a.visible != b.visible) return a.visible;
    if (a.key.level != b.key.level) return a.key.level < b.key.level;
    return a.depth < b.depth;
  });
}

// A walk's allowance of tiles to build (tile_selection.h).
class Allowance {
 public:
  Allowance(int64_t tiles, const std::function<bool()>& stop) : left_(tiles), stop_(stop) {}
  // Whether the walk may refine into `children`; counts those not built yet
  // (each once) against the allowance if so. The first refinement that
  // builds anything is always admitted, so that every walk makes progress.
  bool admits(const TileCatalogue& tiles, std::span<const TileKey> children) {
    if (left_ < 0 && !stop_) return true;
    std::vector<TileKey> fresh;
    for (const TileKey& c : children)
      if (!tiles.isBuilt(c) && !counted_.count(c)) fresh.push_back(c);
    if (fresh.empty()) return true;
    const auto cost = static_cast<int64_t>(fresh.size());
    if (!counted_.empty() && ((left_ >= 0 && cost > left_) || (stop_ && stop_()))) return false;
    if (left_ >= 0) left_ = std::max<int64_t>(0, left_ - cost);
    counted_.insert(fresh.begin(), fresh.end());
    return true;
  }

 private:
  int64_t left_;  // negative: no limit
  const std::function<bool()>& stop_;
  std::set<TileKey> counted_;
};

Expected<std::vector<TileKey>> expand(const View& view, TileCatalogue& tiles, double tolerance,
                                      const std::vector<TileKey>& frontier, Allowance& allowance,
                                      TileSelection& out);

// Several views at once, level by level, so that the hierarchy grows once
// per level for every tile any of them needs there (TileCatalogue::prepare):
// each growth selects again at every level below it.
Expected<std::vector<TileSelection>> selectAt(std::span<const View> views, TileCatalogue& tiles,
                                              std::span<const double> tolerances, Allowance& allowance) {
  std::vector<TileSelection> out(views.size());
  std::vector<std::vector<TileKey>> frontiers(views.size(), tiles.tree().roots());
  for (size_t v = 0; v < views.size(); ++v) out[v].tolerancePixels = tolerances[v];
  for (;;) {
    std::vector<TileKey> level;
    for (const auto& f : frontiers) level.insert(level.end(), f.begin(), f.end());
    if (level.empty()) break;
    std::sort(level.begin(), level.end());
    level.erase(std::unique(level.begin(), level.end()), level.end());
    tiles.prepare(level);
    for (size_t v = 0; v < views.size(); ++v) {
      TESSERA_ASSIGN_OR_RETURN(frontiers[v],
                               expand(views[v], tiles, tolerances[v], frontiers[v], allowance, out[v]));
    }
  }
  for (TileSelection& s : out) sortForSending(s);
  return out;
}

// One level of one view's walk: the tiles of `frontier` it keeps go into
// `out`, the children of those it refines are returned.
Expected<std::vector<TileKey>> expand(const View& view, TileCatalogue& tiles, double tolerance,
                                      const std::vector<TileKey>& frontier, Allowance& allowance,
                                      TileSelection& out) {
  std::vector<TileKey> next;
  for (const TileKey& key : frontier) {
    TESSERA_ASSIGN_OR_RETURN(const Tile* tile, tiles.get(key));
    const SelectedTile s = judgeTile(view, key, tile->bounds);
    if (refinesTile(s, tile->bounds, tolerance)) {
      auto children = tiles.tree().children(key);
      if (!children.empty() && allowance.admits(tiles, children)) {
        next.insert(next.end(), children.begin(), children.end());
        continue;
      }
      if (!children.empty()) out.complete = false;
    }
    out.triangles += tile->triangles;
    out.tiles.push_back(s);
  }
  return next;
}

}  // namespace

SelectedTile judgeTile(const View& view, const TileKey& key, const TileBounds& bounds) {
  return {key, !view.outside(bounds.sphere), view.projectedError(bounds.error, bounds.sphere),
          dot(bounds.sphere.centre - view.eye, view.forward.normalized())};
}

bool refinesTile(const SelectedTile& judged, const TileBounds& bounds, double tolerancePixels) {
  // A tag deep under a visible tile has no error bound (tile_error.h).
  return judged.visible && (bounds.deepTags || judged.projectedError > tolerancePixels);
}

Expected<TileSelection> selectTiles(const View& view, TileCatalogue& tiles, int64_t budget) {
  const int64_t budgets[] = {budget};
  TESSERA_ASSIGN_OR_RETURN(std::vector<TileSelection> s, selectTilesForEach({&view, 1}, tiles, budgets));
  return std::move(s.front());
}

Expected<std::vector<TileSelection>> selectTilesForEach(std::span<const View> views, TileCatalogue& tiles,
                                                        std::span<const int64_t> budgets, int64_t newTiles,
                                                        const std::function<bool()>& stopBuilding) {
  for (const View& view : views) TESSERA_RETURN_IF_ERROR(view.check());
  std::vector<double> tolerances;
  for (const View& view : views) tolerances.push_back(view.tolerancePixels);
  Allowance allowance(newTiles, stopBuilding);
  TESSERA_ASSIGN_OR_RETURN(std::vector<TileSelection> out, selectAt(views, tiles, tolerances, allowance));
  // Those over their budget again, with the tolerance raised, one by one.
  for (size_t v = 0; v < views.size(); ++v) {
    for (int step = 1; budgets[v] > 0 && out[v].triangles > budgets[v] && step <= kBudgetSteps; ++step) {
      const double raised[] = {out[v].tolerancePixels * kBudgetStep};
      TESSERA_ASSIGN_OR_RETURN(std::vector<TileSelection> again,
                               selectAt({&views[v], 1}, tiles, raised, allowance));
      out[v] = std::move(again.front());
    }
  }
  return out;
}

}  // namespace tessera
