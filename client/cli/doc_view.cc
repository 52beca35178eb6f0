// tessera doc view: the tiles a view of a local document selects
// (docs/VIEWS.md), with what each level costs, encoded as a server encodes
// regions: on the document's grid, with vertex ids (lattice points for a
// one-face tile, 8-byte labels for a cluster) and without. Then the
// whole-document uniform level that would reach the same on-screen error.
#include "client/cli/doc_view.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "client/cli/command_line.h"
#include "client/cli/human_format.h"
#include "core/document/document_file.h"
#include "core/tessellation/document_grid.h"
#include "core/view/tile_encoding.h"
#include "core/view/tile_preview.h"
#include "core/view/tile_selection.h"

namespace tessera::cli {

namespace {

Expected<std::pair<int, int>> parseSize(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x')
    return invalidArgument("--size: expects WIDTHxHEIGHT in pixels, got '" + text + "'");
  return std::pair{w, h};
}

size_t encodedBytes(const Document& doc, const TileKey& key, const RegionMesh& mesh,
                    const QuantizationGrid& grid, bool ids) {
  auto encoded = encodeTile(doc, key, mesh, grid, 1, ids);
  return encoded.isOk() ? encoded->bytes->size() : 0;
}

}  // namespace

int runDocView(const DocViewArgs& args) {
  auto size = parseSize(args.size);
  if (!size.isOk()) return usage("doc view", size.status().message());
  View view;
  view.eye = Vec3(args.eye[0], args.eye[1], args.eye[2]);
  view.forward = Vec3(args.target[0], args.target[1], args.target[2]) - view.eye;
  view.up = Vec3(args.up[0], args.up[1], args.up[2]);
  view.width = size->first;
  view.height = size->second;
  view.tolerancePixels = args.tolerance;
  if (args.orthoHeight > 0) {
    view.projection = Projection::kOrthographic;
    view.orthoHeight = args.orthoHeight;
  } else {
    view.fovYRadians = args.fovDegrees * std::numbers::pi / 180;
  }
  auto doc = loadDocument(args.document);
  if (!doc.isOk()) return fail("doc view", doc.status());
  Vec3 lo = doc->basePoints()[0], hi = lo;
  for (const Vec3& p : doc->basePoints())
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  view.nearDistance = std::max(1e-6, 1e-4 * (hi - lo).norm());
  if (Status valid = view.check(); !valid.isOk()) return usage("doc view", valid.message());
  auto grid = documentGrid(*doc);
  if (!grid.isOk()) return fail("doc view", grid.status());

  TileCatalogue catalogue(*doc);
  auto selection = selectTiles(view, catalogue, args.budget);
  if (!selection.isOk()) return fail("doc view", selection.status());

  struct PerLevel {
    int tiles = 0, hidden = 0;
    int64_t triangles = 0;
    size_t withIds = 0, withoutIds = 0;
    double worstPixels = 0, worstError = 0;
  };
  std::map<int, PerLevel> levels;
  int finestVisible = 0;
  for (const SelectedTile& t : selection->tiles) {
    auto tile = catalogue.get(t.key);
    if (!tile.isOk()) return fail("doc view", tile.status());
    PerLevel& l = levels[t.key.level];
    ++l.tiles;
    if (!t.visible) ++l.hidden;
    l.triangles += (*tile)->triangles;
    l.withIds += encodedBytes(*doc, t.key, (*tile)->mesh, *grid, true);
    l.withoutIds += encodedBytes(*doc, t.key, (*tile)->mesh, *grid, false);
    if (t.visible) {
      l.worstPixels = std::max(l.worstPixels, t.projectedError);
      finestVisible = std::max(finestVisible, t.key.level);
    }
    l.worstError = std::max(l.worstError, (*tile)->bounds.error);
  }
  std::printf(
      "view %dx%d px, tolerance %g px%s; %s tiles, %s triangles\n", view.width, view.height,
      view.tolerancePixels,
      selection->tolerancePixels > view.tolerancePixels
          ? (" (raised to " + std::to_string(selection->tolerancePixels) + " px by the budget)").c_str()
          : "",
      formatCount(selection->tiles.size()).c_str(), formatCount(selection->triangles).c_str());
  std::printf(
      "level  tiles (hidden)   triangles   bytes, ids   bytes, no ids   error bound   worst visible px\n");
  size_t withIds = 0, withoutIds = 0;
  for (const auto& [level, l] : levels) {
    std::printf("%5d  %6d (%5d)  %10s  %11s  %14s  %12.4g  %17.3f\n", level, l.tiles, l.hidden,
                formatCount(l.triangles).c_str(), formatBytes(l.withIds).c_str(),
                formatBytes(l.withoutIds).c_str(), l.worstError, l.worstPixels);
    withIds += l.withIds, withoutIds += l.withoutIds;
  }
  std::printf("total  %s with ids, %s without\n", formatBytes(withIds).c_str(),
              formatBytes(withoutIds).c_str());
  const uint64_t uniform = doc->counts().faces(0) << (2 * finestVisible);
  std::printf("the whole document at level %d, the finest this view shows: %s triangles (%.1f times these)\n",
              finestVisible, formatCount(uniform).c_str(),
              static_cast<double>(uniform) / std::max<int64_t>(selection->triangles, 1));
  // The first picture a server sends before these (docs/VIEWS.md "The
  // first picture"): the surface's preview where it pays, else the roots.
  int64_t rootTriangles = 0;
  size_t rootBytes = 0;
  for (const TileKey& root : catalogue.tree().roots()) {
    auto tile = catalogue.get(root);
    if (!tile.isOk()) return fail("doc view", tile.status());
    rootTriangles += (*tile)->triangles;
    rootBytes += encodedBytes(*doc, root, (*tile)->mesh, *grid, true);
  }
  if (previewPays(rootTriangles)) {
    auto preview = surfacePreview(*doc);
    if (!preview.isOk()) return fail("doc view", preview.status());
    std::printf(
        "first picture: the surface's preview, %s triangles, %s with ids (the level-0 tiles: %s, %s)\n",
        formatCount(preview->mesh.triangles.size()).c_str(),
        formatBytes(encodedBytes(*doc, TileKey::preview(), preview->mesh, *grid, true)).c_str(),
        formatCount(rootTriangles).c_str(), formatBytes(rootBytes).c_str());
  } else {
    std::printf("first picture: the level-0 tiles, %s triangles, %s with ids\n",
                formatCount(rootTriangles).c_str(), formatBytes(rootBytes).c_str());
  }
  std::printf("tiles built: %s\n", formatCount(catalogue.built()).c_str());
  return 0;
}

}  // namespace tessera::cli
