// The first picture of a view (docs/VIEWS.md "The first picture"): the
// whole surface at level 0 (every root tile, joined by vertex id),
// simplified by edge collapses to at most kPreviewTriangles triangles
// (meshoptimizer's meshopt_simplify, after Garland & Heckbert, "Surface
// Simplification Using Quadric Error Metrics"), so that it costs a few
// kilobytes whatever the document's size. A placeholder, not a tile: no
// view selects it and it has no error bound. A viewer shows it alone,
// then the view's tiles in its place once the visible ones have come.
#pragma once

#include <cstdint>
#include <vector>

#include "core/document/document.h"
#include "core/tessellation/region_codec.h"
#include "core/util/status.h"

namespace tessera {

inline constexpr size_t kPreviewTriangles = 2048;

// Whether a surface of this many level-0 triangles gets a preview: only
// where it saves most of the first picture (the roots are the first
// picture otherwise, as small as the preview would be).
inline bool previewPays(int64_t levelZeroTriangles) {
  return levelZeroTriangles > 4 * static_cast<int64_t>(kPreviewTriangles);
}

// `roots`: the meshes of the tile tree's roots (tile_builder.h). Its
// vertices are level-0 limit points, each with a root's position, normal
// and id. Errors: more vertices than 32-bit indices hold.
Expected<RegionMesh> surfacePreview(const std::vector<const RegionMesh*>& roots);

// The same from the document's level-0 faces directly, without a tile
// tree: the level-0 surface the roots show together, so a server can send
// it before it has built the tree (docs/VIEWS.md "The first picture").
// `levelZeroTriangles`: that surface's triangles before simplifying, what
// every root together shows.
struct SurfacePreview {
  RegionMesh mesh;
  int64_t levelZeroTriangles = 0;
};
Expected<SurfacePreview> surfacePreview(Document& doc);

}  // namespace tessera
