// buildBaseMesh(): order preservation and each rejection rule, on soups built
// in code (the file-based cases live in mesh_import_test.cc).
#include "core/mesh/mesh_validation.h"

#include <limits>

#include <gtest/gtest.h>

namespace tessera {
namespace {

PolygonSoup tetra() {
  PolygonSoup soup;
  soup.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  for (const auto& f : std::vector<std::vector<int>>{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}})
    soup.addFace(f);
  return soup;
}

PolygonSoup withFaces(std::vector<Vec3> points, const std::vector<std::vector<int>>& faces) {
  PolygonSoup soup;
  soup.points = std::move(points);
  for (const auto& f : faces) soup.addFace(f);
  return soup;
}

std::string errorOf(const PolygonSoup& soup, BuildOptions options = {}) {
  auto mesh = buildBaseMesh(soup, options, "soup.obj");
  EXPECT_FALSE(mesh.isOk());
  return mesh.isOk() ? std::string() : mesh.status().message();
}

TEST(MeshValidation, PreservesVertexFaceAndCornerOrder) {
  // Rotated corner orders on purpose: each face must come back exactly as given.
  PolygonSoup soup = withFaces({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                               {{2, 1, 0}, {1, 3, 0}, {3, 1, 2}, {0, 3, 2}});
  auto mesh = buildBaseMesh(soup, {}, "soup");
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  const std::vector<std::array<int, 3>> expected = {{2, 1, 0}, {1, 3, 0}, {3, 1, 2}, {0, 3, 2}};
  EXPECT_EQ(mesh->faceVertexIndices(), expected);
  EXPECT_EQ(mesh->positions(), soup.points);
  for (auto e : mesh->mesh().edges()) EXPECT_EQ(mesh->edgeSharpness(e), 0.0f);
  for (auto v : mesh->mesh().vertices()) EXPECT_EQ(mesh->vertexSharpness(v), 0.0f);
}

TEST(MeshValidation, AcceptsOpenMeshWithBoundary) {
  auto mesh = buildBaseMesh(withFaces({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}}), {}, "tri");
  EXPECT_TRUE(mesh.isOk()) << mesh.status().toString();
}

TEST(MeshValidation, RejectsEmpty) {
  EXPECT_EQ(errorOf(PolygonSoup{}), "soup.obj: mesh: empty, no vertices");
  EXPECT_EQ(errorOf(withFaces({Vec3(0, 0, 0)}, {})), "soup.obj: mesh: empty, no faces");
}

TEST(MeshValidation, RejectsNonFiniteCoordinates) {
  PolygonSoup soup = tetra();
  soup.points[2][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(errorOf(soup).find("soup.obj: vertex 2 (0, nan, 0): coordinate is NaN"), std::string::npos)
      << errorOf(soup);
  soup.points[2][1] = -std::numeric_limits<double>::infinity();
  EXPECT_NE(errorOf(soup).find("vertex 2 (0, -inf, 0): coordinate is infinite"), std::string::npos);
}

TEST(MeshValidation, RejectsBadIndices) {
  PolygonSoup soup = withFaces(tetra().points, {{0, 2, 1}, {0, 1, 4}});
  EXPECT_EQ(errorOf(soup),
            "soup.obj: face 1 (vertices 0, 1, 4): vertex index 4 is out of range (the mesh has 4 vertices)");
  soup = withFaces(tetra().points, {{0, -2, 1}});
  EXPECT_NE(errorOf(soup).find("face 0 (vertices 0, -2, 1): vertex index -2 is out of range"),
            std::string::npos);
  soup = withFaces(tetra().points, {{0, 1}});
  EXPECT_NE(errorOf(soup).find("face 0 (vertices 0, 1): has 2 vertices"), std::string::npos);
}

TEST(MeshValidation, PolygonsNeedTriangulate) {
  PolygonSoup soup = withFaces({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(2, 0, 0)},
                               {{0, 1, 2, 3}, {1, 4, 2}});
  const std::string message = errorOf(soup);
  EXPECT_NE(message.find("face 0 (vertices 0, 1, 2, 3): has 4 vertices"), std::string::npos) << message;
  EXPECT_NE(message.find("use --triangulate"), std::string::npos);
  auto mesh = buildBaseMesh(soup, BuildOptions{.triangulate = true}, "soup");
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  // The square's two triangulations are both Delaunay (its corners are
  // cocircular): either diagonal, the triangles keep the square's orientation.
  const std::vector<std::array<int, 3>> diagonal02 = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
  const std::vector<std::array<int, 3>> diagonal13 = {{0, 1, 3}, {1, 2, 3}, {1, 4, 2}};
  const auto faces = mesh->faceVertexIndices();
  EXPECT_TRUE(faces == diagonal02 || faces == diagonal13) << ::testing::PrintToString(faces);
}

TEST(MeshValidation, RejectsDegenerateFaces) {
  EXPECT_EQ(errorOf(withFaces(tetra().points, {{0, 2, 1}, {1, 3, 1}})),
            "soup.obj: face 1 (vertices 1, 3, 1): degenerate, repeats vertex 1");
  // Collinear corners: zero area relative to the bounding box.
  PolygonSoup line =
      withFaces({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(0, 1, 0)}, {{0, 1, 3}, {0, 2, 1}});
  EXPECT_NE(errorOf(line).find("face 1 (vertices 0, 2, 1): degenerate, zero area"), std::string::npos)
      << errorOf(line);
  // A quad with a corner on a straight side is a triangle with an extra
  // corner: its triangulation never uses the three collinear corners (a fan
  // from corner 0 did, and was refused for it).
  PolygonSoup flatQuad =
      withFaces({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0)}, {{0, 1, 2, 3}});
  auto split = buildBaseMesh(flatQuad, BuildOptions{.triangulate = true}, "soup.obj");
  ASSERT_TRUE(split.isOk()) << split.status().toString();
  const std::vector<std::array<int, 3>> expected = {{0, 1, 3}, {1, 2, 3}};
  EXPECT_EQ(split->faceVertexIndices(), expected);
  // A polygon of collinear corners has no triangulation: refused, named.
  PolygonSoup line4 = withFaces({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)}, {{0, 1, 2, 3}});
  EXPECT_EQ(
      errorOf(line4, BuildOptions{.triangulate = true}),
      "soup.obj: face 0 (vertices 0, 1, 2, 3): cannot be triangulated: degenerate, no area (its corners are "
      "collinear)");
}

TEST(MeshValidation, RejectsDuplicateFacesInAnyRotationOrOrientation) {
  PolygonSoup soup = tetra();
  soup.addFace({2, 0, 1});  // same as face 0, reversed and rotated
  EXPECT_EQ(errorOf(soup), "soup.obj: face 4 (vertices 2, 0, 1): duplicates face 0 (vertices 0, 2, 1)");
  soup = tetra();
  soup.addFace({1, 0, 2});  // rotation of face 0, same orientation
  EXPECT_NE(errorOf(soup).find("duplicates face 0"), std::string::npos);
}

TEST(MeshValidation, RejectsNonManifoldEdges) {
  PolygonSoup book = withFaces({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)},
                               {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const std::string message = errorOf(book);
  EXPECT_NE(message.find("soup.obj: edge 0-1: non-manifold, used by 3 faces: face 0 (vertices 0, 1, 2); "
                         "face 1 (vertices 1, 0, 3); face 2 (vertices 0, 1, 4)"),
            std::string::npos)
      << message;
}

TEST(MeshValidation, RejectsInconsistentOrientationNamingBothFaces) {
  PolygonSoup soup =
      withFaces({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}, {{0, 1, 2}, {1, 2, 3}});
  EXPECT_EQ(
      errorOf(soup),
      "soup.obj: edge 1-2: inconsistent orientation, face 0 (vertices 0, 1, 2) and face 1 (vertices 1, 2, 3) "
      "both run from vertex 1 (flip one of them)");
}

TEST(MeshValidation, RejectsNonManifoldVertex) {
  // Two triangles sharing only vertex 0 (a bow tie).
  PolygonSoup bowTie = withFaces(
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(errorOf(bowTie),
            "soup.obj: vertex 0: non-manifold, its faces form more than one fan (e.g. face 0 (vertices 0, 1, "
            "2) and "
            "face 1 (vertices 0, 3, 4) touch only at this vertex)");
}

TEST(MeshValidation, RejectsIsolatedVertex) {
  PolygonSoup soup = tetra();
  soup.points.push_back(Vec3(5, 5, 5));
  EXPECT_EQ(
      errorOf(soup),
      "soup.obj: vertex 4 (5, 5, 5): not used by any face (isolated vertices are not accepted; --drop-unused "
      "drops them)");
}

}  // namespace
}  // namespace tessera
