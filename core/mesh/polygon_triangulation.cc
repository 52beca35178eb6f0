// Polygon triangulation with CGAL 2D constrained Delaunay triangulation (see
// polygon_triangulation.h for the method and its guarantees).
#include "core/mesh/polygon_triangulation.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <string>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

namespace tessera {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;  // corner position
struct FaceInfo {
  bool outside = false;
  bool visited = false;
};
using FaceBase =
    CGAL::Constrained_triangulation_face_base_2<Kernel,
                                                CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

// Corners whose Newell normal is shorter than this times the squared longest
// edge have no area worth the name (collinear up to rounding).
constexpr double kRelativeAreaEpsilon = 1e-12;

std::string edgeName(std::span<const int> corners, size_t k) {
  return std::to_string(corners[k]) + "-" + std::to_string(corners[(k + 1) % corners.size()]);
}

// The first pair of non-adjacent outline edges that meet, for the message.
std::string findCrossing(const std::vector<Point2>& outline, std::span<const int> corners) {
  const size_t n = outline.size();
  for (size_t i = 0; i < n; ++i) {
    const Kernel::Segment_2 a(outline[i], outline[(i + 1) % n]);
    for (size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) {
        // Adjacent edges share a corner; they overlap only when folded back.
        const Point2& shared = j == i + 1 ? outline[j] : outline[0];
        const Point2& p = j == i + 1 ? outline[i] : outline[1];
        const Point2& q = j == i + 1 ? outline[(j + 1) % n] : outline[n - 1];
        if (CGAL::collinear(p, shared, q) && !CGAL::collinear_are_strictly_ordered_along_line(p, shared, q)) {
          return "its edges " + edgeName(corners, i) + " and " + edgeName(corners, j) +
                 " fold back onto each other";
        }
        continue;
      }
      if (CGAL::do_intersect(a, Kernel::Segment_2(outline[j], outline[(j + 1) % n]))) {
        return "its edges " + edgeName(corners, i) + " and " + edgeName(corners, j) + " cross";
      }
    }
  }
  return "its outline is not simple";
}

// The corners in an orthonormal frame (u, v) of the plane normal to
// `normal`, with u x v along it: counter-clockwise in (u, v) is the
// polygon's own orientation about `normal`.
std::vector<Point2> project(std::span<const Vec3> points, std::span<const int> corners, const Vec3& normal) {
  const Vec3 w = normal / normal.norm();
  const Vec3 helper = std::abs(w[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 u = (helper % w).normalized();
  const Vec3 v = w % u;
  const Vec3& origin = points[corners[0]];
  std::vector<Point2> outline;
  outline.reserve(corners.size());
  for (int c : corners) {
    const Vec3 d = points[c] - origin;
    outline.emplace_back(d | u, d | v);
  }
  return outline;
}

// Marks the faces outside the outline: those reachable from the infinite
// face without crossing a constrained (outline) edge.
void markOutside(Cdt& cdt) {
  std::deque<Cdt::Face_handle> queue{cdt.infinite_face()};
  cdt.infinite_face()->info() = {true, true};
  while (!queue.empty()) {
    const Cdt::Face_handle f = queue.front();
    queue.pop_front();
    for (int i = 0; i < 3; ++i) {
      const Cdt::Face_handle g = f->neighbor(i);
      if (g->info().visited || cdt.is_constrained(Cdt::Edge(f, i))) continue;
      g->info() = {true, true};
      queue.push_back(g);
    }
  }
}

}  // namespace

Vec3 polygonNormal(std::span<const Vec3> points, std::span<const int> corners) {
  Vec3 n(0, 0, 0);
  const size_t count = corners.size();
  const Vec3& origin = points[corners[0]];
  for (size_t k = 1; k + 1 < count; ++k)
    n += (points[corners[k]] - origin) % (points[corners[k + 1]] - origin);
  return n;
}

Status triangulatePolygon(std::span<const Vec3> points, std::span<const int> corners,
                          std::vector<std::array<int, 3>>& out) {
  const size_t n = corners.size();
  if (n < 3) return invalidMesh("has " + std::to_string(n) + " vertices, a face needs at least 3");
  if (n == 3) {
    out.push_back({corners[0], corners[1], corners[2]});
    return Status::ok();
  }
  const Vec3 normal = polygonNormal(points, corners);
  double longest = 0;
  for (size_t k = 0; k < n; ++k)
    longest = std::max(longest, (points[corners[(k + 1) % n]] - points[corners[k]]).sqrnorm());
  if (!(normal.norm() > kRelativeAreaEpsilon * longest)) {
    // No area overall: collinear corners, or lobes of opposite orientation
    // that cancel (a bow tie). The largest corner triangle tells which, and
    // gives a plane in which to find the crossing.
    const Vec3& origin = points[corners[0]];
    Vec3 widest(0, 0, 0);
    for (size_t k = 1; k + 1 < n; ++k) {
      const Vec3 c = (points[corners[k]] - origin) % (points[corners[k + 1]] - origin);
      if (c.norm() > widest.norm()) widest = c;
    }
    if (!(widest.norm() > kRelativeAreaEpsilon * longest)) {
      return invalidMesh("cannot be triangulated: degenerate, no area (its corners are collinear)");
    }
    return invalidMesh("cannot be triangulated: self-intersecting, " +
                       findCrossing(project(points, corners, widest), corners) +
                       " (its parts turn opposite ways and their areas cancel)");
  }
  const std::vector<Point2> outline = project(points, corners, normal);
  if (!CGAL::is_simple_2(outline.begin(), outline.end(), Kernel())) {
    return invalidMesh("cannot be triangulated: self-intersecting, " + findCrossing(outline, corners) +
                       " (seen along its mean normal)");
  }
  if (CGAL::orientation_2(outline.begin(), outline.end(), Kernel()) != CGAL::COUNTERCLOCKWISE) {
    // Only a polygon folded over itself projects clockwise on its own normal.
    return invalidMesh("cannot be triangulated: it folds over itself (seen along its mean normal)");
  }

  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  handles.reserve(n);
  for (size_t k = 0; k < n; ++k) {
    handles.push_back(cdt.insert(outline[k]));
    handles.back()->info() = static_cast<int>(k);
  }
  for (size_t k = 0; k < n; ++k) cdt.insert_constraint(handles[k], handles[(k + 1) % n]);
  if (cdt.number_of_vertices() != n) {
    return internalError("triangulation: " + std::to_string(cdt.number_of_vertices()) + " vertices for " +
                         std::to_string(n) + " corners");
  }
  markOutside(cdt);
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(n - 2);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info().outside) continue;
    // In corner positions, rotated to start at the lowest: the order below
    // then depends on the polygon alone, not on CGAL's storage.
    std::array<int, 3> t = {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end());
  for (std::array<int, 3>& t : triangles) t = {corners[t[0]], corners[t[1]], corners[t[2]]};
  // A simple polygon of n corners has exactly n - 2 triangles.
  if (triangles.size() != n - 2) {
    return internalError("triangulation: " + std::to_string(triangles.size()) + " triangles for " +
                         std::to_string(n) + " corners");
  }
  out.insert(out.end(), triangles.begin(), triangles.end());
  return Status::ok();
}

}  // namespace tessera
