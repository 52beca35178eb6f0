// Triangulation of one polygon of a mesh file (a quad, an n-gon, concave or
// not planar) into triangles with the polygon's orientation, using CGAL's
// constrained Delaunay triangulation with exact predicates.
//
// The polygon is projected onto the plane normal to its Newell normal (the
// area-weighted mean normal, exact for planar polygons); in that plane its
// outline is a simple polygon, counter-clockwise, whenever the polygon does
// not fold over itself. The constrained Delaunay triangulation of the outline
// covers exactly its interior with n - 2 triangles on the polygon's own
// corners (no Steiner points), so a concave polygon gets no flipped or
// overlapping triangle, and among the triangulations of a non-planar polygon
// it picks the best-shaped one (largest smallest angle) as seen along the
// normal. A fan from one corner, Tessera's earlier method, does
// neither.
//
// Refused, with the reason naming the polygon's vertices: a polygon with no
// area (collinear corners) and one whose outline crosses itself in that
// plane (a self-intersecting polygon, or a non-planar one folded so far that
// it has no projection without a crossing).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera {

// `corners`: the polygon's vertex indices into `points`, in order (at least
// 3, no repeats). Appends the triangles, as vertex-index triples, to `out`.
// On error, `out` is unchanged and the message is the reason alone (the
// caller names the file and face): "self-intersecting: its edges 3-4 and
// 7-8 cross (seen along its mean normal)".
// The polygon's Newell normal: twice its area along its mean normal (the
// plain cross product for a triangle), computed relative to the first corner
// so that a polygon far from the origin keeps its digits.
Vec3 polygonNormal(std::span<const Vec3> points, std::span<const int> corners);

Status triangulatePolygon(std::span<const Vec3> points, std::span<const int> corners,
                          std::vector<std::array<int, 3>>& out);

}  // namespace tessera
