// The control vertices of one level, placed at their limit positions, and
// picking among them. Pure functions over the published regions, so they are
// tested without a window.
//
// A region vertex carries the packed id of the control vertex it is the limit
// of, at the vertex's birth level. A vertex born at level b <= L has the same
// index at level L, so the control vertices of level L visible in the
// tessellation are the region vertices with a birth level <= L, renamed to
// level L.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "client/view/camera.h"
#include "client/view/connection.h"

namespace tessera::view {

struct ControlPoint {
  uint64_t id = 0;  // packed VertexId at the chosen level
  V3 position;      // limit position
  V3 normal;        // limit normal
};

// One point per control vertex, in id order.
std::vector<ControlPoint> controlPoints(const RegionMap& regions, int level);

// The point nearest to the pixel within radiusPixels, skipping points whose
// normal faces away from the eye; nothing if none qualifies.
std::optional<size_t> pickPoint(const std::vector<ControlPoint>& points, const OrbitCamera& camera, int width,
                                int height, float px, float py, float radiusPixels);

// Where a dragged point goes: the ray through the pixel meets the plane
// through `anchor` facing the camera.
V3 dragTarget(const OrbitCamera& camera, V3 anchor, float px, float py, int width, int height);

// The control vertices of `level` joined to `vertex` (packed, at `level`)
// by an edge of that level, as far as the displayed triangles show, in id
// order: where the tessellation shows `level`, its triangle edges; where it
// shows level + 1, the far ends of the vertices on those edges. Deeper
// tessellations show none, and crack-closing fans may show a wrong one: the
// server has the last word (Document::edgeBetween).
std::vector<uint64_t> levelNeighbours(const RegionMap& regions, uint64_t vertex, int level);

// `count` >= 2 points evenly spaced from a to b, both included: a picked
// edge drawn as a dotted line.
std::vector<V3> segmentPoints(V3 a, V3 b, int count);

// The bounding box of every region vertex; false when there is none.
bool bounds(const RegionMap& regions, V3* lo, V3* hi);

// The world-space diameter of a control vertex's dot: `count` points spread
// over a model with this bounding box lie about diagonal / sqrt(count)
// apart, and a dot a third of that leaves the surface between them visible.
// Kept between 0.15% and 1.5% of the diagonal, so that eight points on a cube
// are not balls and a million are not dust. The renderer turns it into
// pixels with the perspective (points nearer the eye are larger).
float controlPointDiameter(V3 lo, V3 hi, size_t count);

}  // namespace tessera::view
