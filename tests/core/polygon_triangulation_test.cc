// triangulatePolygon() and --triangulate on import: concave and non-planar
// polygons become triangles that cover the polygon exactly once, with its
// orientation; polygons that cannot be triangulated are refused, named.
//
// The definitions used here are independent of CGAL: the polygon's area by
// the shoelace formula, orientation by the sign of each triangle's normal
// along the polygon's, and coverage by counting, at sample points, how many
// triangles contain each (one inside the polygon, none outside).
#include "core/mesh/polygon_triangulation.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/io/mesh_import.h"

namespace tessera {
namespace {

using Triangles = std::vector<std::array<int, 3>>;

// Signed area of a planar polygon in the z = 0 plane (shoelace).
double shoelace(const std::vector<Vec3>& p) {
  double twice = 0;
  for (size_t k = 0; k < p.size(); ++k) {
    const Vec3& a = p[k];
    const Vec3& b = p[(k + 1) % p.size()];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return twice / 2;
}

double signedAreaXY(const Vec3& a, const Vec3& b, const Vec3& c) {
  return ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2;
}

// Strictly inside the triangle (x, y), counter-clockwise or not.
bool strictlyInside(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double d1 = signedAreaXY(a, b, q), d2 = signedAreaXY(b, c, q), d3 = signedAreaXY(c, a, q);
  return (d1 > 0 && d2 > 0 && d3 > 0) || (d1 < 0 && d2 < 0 && d3 < 0);
}

// Even-odd point-in-polygon test (x, y).
bool insidePolygon(const Vec3& q, const std::vector<Vec3>& p) {
  bool inside = false;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i][1] > q[1]) != (p[j][1] > q[1]) &&
        q[0] < (p[j][0] - p[i][0]) * (q[1] - p[i][1]) / (p[j][1] - p[i][1]) + p[i][0]) {
      inside = !inside;
    }
  }
  return inside;
}

Triangles triangulated(const std::vector<Vec3>& points) {
  std::vector<int> corners(points.size());
  for (size_t k = 0; k < points.size(); ++k) corners[k] = static_cast<int>(k);
  Triangles out;
  const Status status = triangulatePolygon(points, corners, out);
  EXPECT_TRUE(status.isOk()) << status.toString();
  return out;
}

// The checks of a planar, counter-clockwise polygon in z = 0.
void expectExactCover(const std::vector<Vec3>& polygon) {
  const Triangles triangles = triangulated(polygon);
  ASSERT_EQ(triangles.size(), polygon.size() - 2);
  double sum = 0;
  for (const auto& t : triangles) {
    const double area = signedAreaXY(polygon[t[0]], polygon[t[1]], polygon[t[2]]);
    EXPECT_GT(area, 0) << "flipped or degenerate triangle " << ::testing::PrintToString(t);
    sum += area;
  }
  EXPECT_NEAR(sum, shoelace(polygon), 1e-12 * std::abs(shoelace(polygon)));
  // Sample points on a grid offset from every corner and edge: each point
  // inside the polygon lies in exactly one triangle, outside in none.
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (const Vec3& p : polygon) {
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  int insideSamples = 0;
  for (int i = 0; i < 97; ++i) {
    for (int j = 0; j < 89; ++j) {
      const Vec3 q(lo[0] + (hi[0] - lo[0]) * (i + 0.5123) / 97, lo[1] + (hi[1] - lo[1]) * (j + 0.4871) / 89,
                   0);
      int covering = 0;
      for (const auto& t : triangles)
        covering += strictlyInside(q, polygon[t[0]], polygon[t[1]], polygon[t[2]]);
      const bool inside = insidePolygon(q, polygon);
      insideSamples += inside;
      EXPECT_EQ(covering, inside ? 1 : 0) << "sample (" << q[0] << ", " << q[1] << ")";
    }
  }
  EXPECT_GT(insideSamples, 1000);  // the comparison is not vacuous
}

TEST(PolygonTriangulation, ConcavePentagonIsCoveredOnceWithNoFlippedTriangle) {
  // An arrow head: corner 3 points inwards. The fan from corner 0 (Tessera's
  // method before) gives (0,1,2), (0,2,3), (0,3,4), of which (0,2,3) is
  // flipped and overlaps (0,3,4): checked here so the case is the right one.
  const std::vector<Vec3> arrow = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(4, 4, 0), Vec3(2, 1, 0), Vec3(0, 4, 0)};
  ASSERT_LT(signedAreaXY(arrow[0], arrow[2], arrow[3]), 0);
  expectExactCover(arrow);
}

TEST(PolygonTriangulation, LShapedHexagonIsCoveredOnce) {
  const std::vector<Vec3> ell = {Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(3, 1, 0),
                                 Vec3(1, 1, 0), Vec3(1, 3, 0), Vec3(0, 3, 0)};
  expectExactCover(ell);
  // The same L with its reflex corner first: a fan from it would work, one
  // from corner 1 would not; the result must not depend on where it starts.
  for (size_t start = 1; start < ell.size(); ++start) {
    std::vector<Vec3> rotated(ell.begin() + start, ell.end());
    rotated.insert(rotated.end(), ell.begin(), ell.begin() + start);
    SCOPED_TRACE("starting at corner " + std::to_string(start));
    expectExactCover(rotated);
  }
}

TEST(PolygonTriangulation, CombWithManyReflexCornersIsCoveredOnce) {
  // A comb: 6 teeth, 12 reflex corners.
  std::vector<Vec3> comb = {Vec3(0, 0, 0), Vec3(13, 0, 0)};
  for (int t = 6; t >= 1; --t) {
    comb.push_back(Vec3(2 * t + 1, 5, 0));
    comb.push_back(Vec3(2 * t, 5, 0));
    comb.push_back(Vec3(2 * t, 1, 0));
    comb.push_back(Vec3(2 * t - 1, 1, 0));
  }
  comb.push_back(Vec3(1, 5, 0));
  comb.push_back(Vec3(0, 5, 0));
  expectExactCover(comb);
}

TEST(PolygonTriangulation, NonPlanarPolygonKeepsItsOrientation) {
  // A saddle hexagon: corners alternately up and down, far from the origin.
  std::vector<Vec3> saddle;
  for (int k = 0; k < 6; ++k) {
    const double a = 2 * M_PI * k / 6;
    saddle.push_back(Vec3(1000 + std::cos(a), -2000 + std::sin(a), 500 + (k % 2 ? 0.3 : -0.3)));
  }
  const Triangles triangles = triangulated(saddle);
  ASSERT_EQ(triangles.size(), 4u);
  std::vector<int> uses(6, 0);
  for (const auto& t : triangles) {
    const Vec3 n = (saddle[t[1]] - saddle[t[0]]) % (saddle[t[2]] - saddle[t[0]]);
    EXPECT_GT(n[2], 0) << "a triangle faces away from the polygon's normal (+z)";
    for (int c : t) ++uses[c];
  }
  for (int k = 0; k < 6; ++k) EXPECT_GE(uses[k], 1) << "corner " << k << " unused";
}

TEST(PolygonTriangulation, ClockwisePolygonGivesClockwiseTriangles) {
  // Orientation is the polygon's own, whichever way it turns.
  const std::vector<Vec3> ccw = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(4, 4, 0), Vec3(2, 1, 0), Vec3(0, 4, 0)};
  const std::vector<Vec3> cw(ccw.rbegin(), ccw.rend());
  for (const auto& t : triangulated(cw)) EXPECT_LT(signedAreaXY(cw[t[0]], cw[t[1]], cw[t[2]]), 0);
}

TEST(PolygonTriangulation, RefusesSelfIntersectingAndDegeneratePolygonsNamingThem) {
  // A bow tie: edges 0-1 and 2-3 cross.
  const std::vector<Vec3> bowTie = {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  Triangles out;
  const Status crossed = triangulatePolygon(bowTie, std::vector<int>{0, 1, 2, 3}, out);
  EXPECT_EQ(crossed.code(), ErrorCode::kInvalidMesh);
  EXPECT_NE(crossed.message().find("self-intersecting"), std::string::npos) << crossed.message();
  EXPECT_NE(crossed.message().find("0-1 and 2-3 cross"), std::string::npos) << crossed.message();
  EXPECT_TRUE(out.empty());
  // A pentagram, through import: the file and face are named.
  std::string star = "";
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * M_PI * k / 5;
    star += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  star += "f 1 3 5 2 4\n";
  auto refused = importMeshFromBytes(star, ".obj", "star.obj", {.triangulate = true});
  ASSERT_FALSE(refused.isOk());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidMesh);
  EXPECT_NE(
      refused.status().message().find("star.obj: face 0 (vertices 0, 2, 4, 1, 3): cannot be triangulated: "
                                      "self-intersecting"),
      std::string::npos)
      << refused.status().message();
  // Collinear corners: no area.
  const std::vector<Vec3> line = {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 3, 3)};
  const Status flat = triangulatePolygon(line, std::vector<int>{0, 1, 2, 3}, out);
  EXPECT_NE(flat.message().find("degenerate, no area"), std::string::npos) << flat.message();
  // A corner that doubles back along its edge (a zero-width spike).
  const std::vector<Vec3> spike = {Vec3(0, 0, 0), Vec3(2, 0, 0),   Vec3(2, 2, 0), Vec3(1, 2, 0),
                                   Vec3(1, 3, 0), Vec3(1, 2.5, 0), Vec3(0, 2, 0)};
  const Status folded = triangulatePolygon(spike, std::vector<int>{0, 1, 2, 3, 4, 5, 6}, out);
  EXPECT_EQ(folded.code(), ErrorCode::kInvalidMesh) << folded.toString();
  EXPECT_TRUE(out.empty());
}

TEST(PolygonTriangulation, ImportedConcavePolygonMeshIsValid) {
  // The arrow head of above as a one-face OBJ: three triangles, none
  // flipped, covering its area.
  const std::string arrow = "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 1 0\nv 0 4 0\nf 1 2 3 4 5\n";
  auto mesh = importMeshFromBytes(arrow, ".obj", "arrow.obj", {.triangulate = true});
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  ASSERT_EQ(mesh->numFaces(), 3);
  const std::vector<Vec3> p = mesh->positions();
  double sum = 0;
  for (const auto& t : mesh->faceVertexIndices()) {
    const double area = signedAreaXY(p[t[0]], p[t[1]], p[t[2]]);
    EXPECT_GT(area, 0);
    sum += area;
  }
  EXPECT_DOUBLE_EQ(sum, 10.0);  // by the shoelace formula
}

}  // namespace
}  // namespace tessera
