// The polygon schemes by their properties and closed forms: Catmull-Clark's
// rules on a cube, its limit against where refinement converges, the
// polygon topology's errors; Doo-Sabin on a regular grid against the
// biquadratic B-spline (Chaikin's 3/4, 1/4 in each direction) and its face
// limits; bilinear; the polygon OBJ/OFF reader and tag files.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "core/catmark/limit.h"
#include "core/catmark/masks.h"
#include "core/io/mesh_import.h"
#include "core/schemes/bilinear_masks.h"
#include "core/schemes/doo_sabin.h"
#include "core/schemes/doo_sabin_masks.h"
#include "core/schemes/polygon_reader.h"
#include "core/schemes/quad_refiner.h"
#include "core/schemes/scheme.h"
#include "support/polygon_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using namespace schemes;
using testing::PolyTestMesh;

void expectNear(const Vec3& a, const Vec3& b, double tolerance) {
  EXPECT_LE((a - b).norm(), tolerance) << "(" << a[0] << ", " << a[1] << ", " << a[2] << ") vs (" << b[0]
                                       << ", " << b[1] << ", " << b[2] << ")";
}

TEST(SchemeCatmark, GoldenMasks) {
  EXPECT_DOUBLE_EQ(catmark::smoothVertexWeight(4), 0.5);
  EXPECT_DOUBLE_EQ(catmark::smoothNeighbourWeight(4), 1.0 / 16.0);
  EXPECT_DOUBLE_EQ(catmark::smoothLimitVertexWeight(4), 4.0 / 9.0);
  EXPECT_DOUBLE_EQ(catmark::smoothLimitNeighbourWeight(4), 1.0 / 9.0);
  EXPECT_DOUBLE_EQ(catmark::smoothLimitFaceWeight(4), 1.0 / 36.0);
  // Masks sum to one at every valence.
  for (int n = 3; n <= 12; ++n) {
    EXPECT_NEAR(catmark::smoothVertexWeight(n) + 2 * n * catmark::smoothNeighbourWeight(n), 1.0, 1e-15) << n;
    EXPECT_NEAR(catmark::smoothLimitVertexWeight(n) +
                    n * (catmark::smoothLimitNeighbourWeight(n) + catmark::smoothLimitFaceWeight(n)),
                1.0, 1e-15)
        << n;
  }
  // Valence 4's tangent is the bicubic B-spline's: (4, 0, -4, 0) and (1, -1, -1, 1).
  EXPECT_NEAR(catmark::smoothTangentNeighbourWeight(4, 2), -4.0, 1e-15);
  EXPECT_NEAR(catmark::smoothTangentFaceWeight(4, 1), -1.0, 1e-15);
  EXPECT_NEAR(catmark::smoothTangentLambda(4), 0.5, 1e-15);
}

TEST(SchemeCatmark, CubeRefinesToItsClosedForm) {
  const PolyTestMesh cube = testing::quadCube();
  auto refiner = QuadRefiner::create(cube.topology, QuadScheme::kCatmullClark, {}, {.levels = 1});
  ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
  const auto points = refiner->refinePoints(cube.points);
  ASSERT_EQ(points.size(), 8u + 6u + 12u);
  // A corner (valence 3): (Q + 2R)/3 with Q = 1/3 of it (the mean of its
  // face centres) and R = 2/3 of it (the mean of its edge midpoints): 5/9.
  // A face point: the centre of the face. An edge point: the mean of its
  // ends and face points.
  expectNear(points[6], Vec3(5.0 / 9, 5.0 / 9, 5.0 / 9), 1e-15);
  expectNear(points[8 + 1], Vec3(0, 0, 1), 1e-15);  // face 1 is z = +1
  for (Index e = 0; e < refiner->level(0).numEdges(); ++e) {
    const auto& ev = refiner->level(0).edgeVertices[e];
    const Vec3 mid = 0.5 * (cube.points[ev[0]] + cube.points[ev[1]]);
    // Each edge midpoint of the unit cube moves to 3/4 of it.
    expectNear(points[8 + 6 + e], 0.75 * mid, 1e-15);
  }
  EXPECT_EQ(refiner->level(1).numFaces(), 24);
  EXPECT_TRUE(refiner->level(1).allQuads());
}

TEST(SchemeCatmark, LimitIsWhereRefinementConverges) {
  // The cube's corner: the limit mask gives 1/2 (3/8 v + 1/6 sum of
  // neighbours + 1/24 sum of opposite corners). Eight levels bring the
  // corner's descendant within the subdominant eigenvalue^8 of it.
  const PolyTestMesh mesh = testing::withPolyJitter(testing::mixedPrism(5, false), 0.05, 4);
  const PolyTestMesh cube = testing::quadCube();
  auto coarse = QuadRefiner::create(cube.topology, QuadScheme::kCatmullClark, {}, {.levels = 0});
  ASSERT_TRUE(coarse.isOk());
  std::vector<Vec3> pos(8), nrm(8);
  ASSERT_TRUE(computeCatmarkLimit(coarse->level(0), {}, cube.points, pos, nrm).isOk());
  expectNear(pos[6], Vec3(0.5, 0.5, 0.5), 1e-15);
  expectNear(nrm[6], (1.0 / std::sqrt(3.0)) * Vec3(1, 1, 1), 1e-15);

  // On a mixed mesh: the limit at level 1 (all quads) against level 9.
  auto one = QuadRefiner::create(mesh.topology, QuadScheme::kCatmullClark, {}, {.levels = 1});
  auto fine = QuadRefiner::create(mesh.topology, QuadScheme::kCatmullClark, {},
                                  {.levels = 8, .fullTopologyInLastLevel = false});
  ASSERT_TRUE(one.isOk() && fine.isOk());
  const auto p1 = one->refinePoints(mesh.points);
  const auto p8 = fine->refinePoints(mesh.points);
  std::vector<Vec3> limit(p1.size()), normals(p1.size());
  ASSERT_TRUE(computeCatmarkLimit(one->finestLevel(), {}, p1, limit, normals).isOk());
  double worst = 0;
  // Vertices of level 1 keep their numbers at every finer level.
  for (size_t v = 0; v < p1.size(); ++v) worst = std::max(worst, (p8[v] - limit[v]).norm());
  EXPECT_LT(worst, 2e-3) << "largest distance of a level-8 vertex from its level-1 limit";
  // Level 0 of a mesh with pentagons and triangles has no limit masks.
  auto zero = QuadRefiner::create(mesh.topology, QuadScheme::kCatmullClark, {}, {.levels = 0});
  std::vector<Vec3> p0(mesh.points.size()), n0(mesh.points.size());
  const Status refused = computeCatmarkLimit(zero->level(0), {}, mesh.points, p0, n0);
  EXPECT_FALSE(refused.isOk());
  EXPECT_NE(refused.message().find("refine once"), std::string::npos) << refused.toString();
}

TEST(SchemeCatmark, TopologyErrorsNameTheElement) {
  auto build = [](std::vector<std::vector<int>> faces, int vertices) {
    PolyTopology t;
    t.numVertices = vertices;
    for (const auto& f : faces) t.addFace(f);
    return buildPolyLevel(t, {});
  };
  auto message = [](const Expected<Level>& r) { return r.isOk() ? std::string("ok") : r.status().message(); };
  EXPECT_NE(message(build({{0, 1, 2, 3}, {1, 0, 4}, {0, 1, 5}}, 6)).find("non-manifold"), std::string::npos);
  EXPECT_NE(message(build({{0, 1, 2, 3}, {0, 1, 4}}, 5)).find("inconsistently oriented"), std::string::npos);
  EXPECT_NE(message(build({{0, 1, 2, 3}}, 5)).find("vertex 4 is used by no face"), std::string::npos);
  EXPECT_NE(message(build({{0, 1, 1, 3}}, 4)).find("face 0 uses vertex 1 twice"), std::string::npos);
  EXPECT_NE(message(build({{0, 1, 7}}, 3)).find("face 0 names vertex 7"), std::string::npos);
  EXPECT_NE(message(build({{0, 1}}, 2)).find("face 0 has 2 corners"), std::string::npos);
  // Two fans meeting at vertex 0 (a bow tie).
  EXPECT_NE(message(build({{0, 1, 2}, {0, 3, 4}}, 5)).find("vertex 0 is non-manifold"), std::string::npos);
  PolyTopology t = testing::quadCube().topology;
  t.creases.push_back({0, 6, 1.0f});
  auto r = buildPolyLevel(t, {});
  EXPECT_NE(message(r).find("edge 0-6 does not exist"), std::string::npos) << message(r);
}

// A regular grid of generic points: heights from a fixed seed.
PolyTestMesh generalGrid(int nu, int nv, uint32_t seed) {
  PolyTestMesh grid = testing::quadGrid(nu, nv);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-0.3, 0.3);
  for (auto& p : grid.points) p += Vec3(0.2 * d(rng), 0.2 * d(rng), d(rng));
  return grid;
}

TEST(SchemeDooSabin, RegularGridRefinesToTheBiquadraticSplinesControlPoints) {
  // Knot insertion of the biquadratic tensor B-spline: Chaikin's rule in u,
  // then in v. The new point of cell (i, j) near its corner (i + a, j + b)
  // weighs the cell's corners by (3/4 if near else 1/4) in each direction.
  constexpr int nu = 6, nv = 5;
  const PolyTestMesh grid = generalGrid(nu, nv, 17);
  auto P = [&](int i, int j) { return grid.points[j * (nu + 1) + i]; };
  auto level = buildPolyLevel(grid.topology, {});
  ASSERT_TRUE(level.isOk());
  const PolygonRefinement step = dooSabinStep(*level, grid.points);
  // Corners of cell (i, j) in face order: (i,j), (i+1,j), (i+1,j+1), (i,j+1).
  const int da[4] = {0, 1, 1, 0}, db[4] = {0, 0, 1, 1};
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int f = j * nu + i;
      for (int k = 0; k < 4; ++k) {
        Vec3 expected(0, 0, 0);
        for (int s = 0; s < 2; ++s) {
          for (int t = 0; t < 2; ++t) {
            const double wu = s == da[k] ? 0.75 : 0.25, wv = t == db[k] ? 0.75 : 0.25;
            expected += (wu * wv) * P(i + s, j + t);
          }
        }
        expectNear(step.points[4 * f + k], expected, 1e-14);
      }
    }
  }
  // One face per face, interior edge and interior vertex, all quads inside.
  const int interiorEdges = (nu - 1) * nv + nu * (nv - 1), interiorVertices = (nu - 1) * (nv - 1);
  EXPECT_EQ(step.topology.numFaces(), nu * nv + interiorEdges + interiorVertices);
  EXPECT_EQ(static_cast<int>(step.topology.indices.size()), 4 * step.topology.numFaces());
  EXPECT_TRUE(buildPolyLevel(step.topology, {}).isOk());  // a valid, consistently oriented mesh
}

TEST(SchemeDooSabin, FaceLimitsAreTheSplinesKnotPointsAndAreWhereFacesShrink) {
  // The biquadratic B-spline at the knot of cell (i, j): the mean of its four
  // corners; its tangents there: the averaged differences across the cell,
  // whose cross product is that of the cell's diagonals.
  constexpr int nu = 5, nv = 4;
  const PolyTestMesh grid = generalGrid(nu, nv, 23);
  auto P = [&](int i, int j) { return grid.points[j * (nu + 1) + i]; };
  std::vector<Vec3> positions, normals;
  dooSabinFaceLimits(grid.topology, grid.points, positions, normals);
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int f = j * nu + i;
      expectNear(positions[f], 0.25 * (P(i, j) + P(i + 1, j) + P(i + 1, j + 1) + P(i, j + 1)), 1e-15);
      const Vec3 du = 0.5 * ((P(i + 1, j) - P(i, j)) + (P(i + 1, j + 1) - P(i, j + 1)));
      const Vec3 dv = 0.5 * ((P(i, j + 1) - P(i, j)) + (P(i + 1, j + 1) - P(i + 1, j)));
      const Vec3 n = du % dv;
      expectNear(normals[f], (1.0 / n.norm()) * n, 1e-12);
    }
  }
  // On a mesh with triangles, pentagons and heptagons: six steps shrink each
  // face's descendant (face f stays face f) onto its limit point, and its
  // own plane turns to the limit normal.
  const PolyTestMesh mixed = testing::withPolyJitter(testing::mixedPrism(7, false), 0.05, 2);
  dooSabinFaceLimits(mixed.topology, mixed.points, positions, normals);
  auto fine = refineDooSabin(mixed.topology, mixed.points, 6);
  ASSERT_TRUE(fine.isOk()) << fine.status().toString();
  std::vector<Vec3> finePositions, fineNormals;
  dooSabinFaceLimits(fine->topology, fine->points, finePositions, fineNormals);
  for (int f = 0; f < mixed.topology.numFaces(); ++f) {
    expectNear(finePositions[f], positions[f], 1e-12);  // the centroid never moves
    const int from = fine->topology.faceOffsets[f], to = fine->topology.faceOffsets[f + 1];
    for (int k = from; k < to; ++k)
      EXPECT_LT((fine->points[fine->topology.indices[k]] - positions[f]).norm(), 0.05);
    EXPECT_LT(std::acos(std::min(1.0, fineNormals[f] | normals[f])), 1e-3) << "face " << f;
  }
}

TEST(SchemeDooSabin, OpenMeshesLoseTheirBorderFacesOnly) {
  const PolyTestMesh open = testing::mixedPrism(5, true);
  auto level = buildPolyLevel(open.topology, {});
  ASSERT_TRUE(level.isOk());
  int interiorEdges = 0, interiorVertices = 0;
  for (Index e = 0; e < level->numEdges(); ++e) interiorEdges += level->isBoundaryEdge(e) ? 0 : 1;
  for (Index v = 0; v < level->numVertices; ++v) interiorVertices += level->isBoundaryVertex(v) ? 0 : 1;
  const PolygonRefinement step = dooSabinStep(*level, open.points);
  EXPECT_EQ(step.topology.numFaces(), level->numFaces() + interiorEdges + interiorVertices);
  EXPECT_TRUE(buildPolyLevel(step.topology, {}).isOk());
}

TEST(SchemeBilinear, MidpointsCentroidsAndUnmovedVertices) {
  const PolyTestMesh mesh = testing::withPolyJitter(testing::mixedPrism(5, false), 0.1, 9);
  auto refiner = QuadRefiner::create(mesh.topology, QuadScheme::kBilinear, {}, {.levels = 2});
  ASSERT_TRUE(refiner.isOk());
  const auto levels = refiner->refinePointsPerLevel(mesh.points);
  const Level& base = refiner->level(0);
  for (size_t v = 0; v < mesh.points.size(); ++v) EXPECT_EQ((levels[2][v] - mesh.points[v]).norm(), 0.0);
  for (Index f = 0; f < base.numFaces(); ++f) {
    Vec3 c(0, 0, 0);
    for (Index v : base.faceVerticesOf(f)) c += mesh.points[v];
    expectNear(levels[1][base.numVertices + f], (1.0 / base.faceSize(f)) * c, 1e-15);
  }
  for (Index e = 0; e < base.numEdges(); ++e) {
    const auto& ev = base.edgeVertices[e];
    expectNear(levels[1][base.numVertices + base.numFaces() + e],
               0.5 * (mesh.points[ev[0]] + mesh.points[ev[1]]), 1e-15);
  }
  EXPECT_EQ(bilinear::kEdgeEndWeight, 0.5);
  auto limit = refiner->limitSurface(levels[2]);
  EXPECT_FALSE(limit.isOk());
}

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = testing::makeTempDir("scheme-reader") + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

TEST(SchemePolygonReader, ObjPolygonsWithFullPrecision) {
  const std::string obj =
      "# a square pyramid, far from the origin\n"
      "v 1000.000000000001 1000 1000\nv 1001 1000 1000\nv 1001 1001 1000\nv 1000 1001 1000\n"
      "v 1000.5 1000.5 1001\nvt 0 0\nvn 0 0 1\n"
      "f 4/1/1 3/1/1 2/1/1 1/1/1\nf 1 2 5\nf 2//1 3//1 5//1\nf -2 -1 -5\nf 4 1 5\n";
  auto soup = readObjPolygons(obj, "pyramid.obj");
  ASSERT_TRUE(soup.isOk()) << soup.status().toString();
  EXPECT_EQ(soup->numFaces(), 5);
  EXPECT_EQ(soup->faceOffsets[1], 4);
  EXPECT_EQ(soup->points[0][0], 1000.000000000001);  // not rounded through float
  EXPECT_EQ(std::vector<int>(soup->indices.begin() + 10, soup->indices.begin() + 13),
            (std::vector<int>{3, 4, 0}));
  auto bad = readObjPolygons("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "bad.obj");
  ASSERT_FALSE(bad.isOk());
  EXPECT_NE(bad.status().message().find("bad.obj:4:"), std::string::npos) << bad.status().toString();
  auto outOfRange = readObjPolygons("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "range.obj");
  ASSERT_FALSE(outOfRange.isOk());
  EXPECT_NE(outOfRange.status().message().find("range.obj:4: vertex index 4"), std::string::npos);
  auto badNumber = readObjPolygons("v 0 nan 0\n", "nan.obj");
  ASSERT_FALSE(badNumber.isOk());
  EXPECT_NE(badNumber.status().message().find("nan.obj:1: bad coordinate 'nan'"), std::string::npos);
}

TEST(SchemePolygonReader, OffPolygonsCommentsColoursAndTruncation) {
  auto soup =
      readOffPolygons("OFF # cube-ish\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n", "q.off");
  ASSERT_TRUE(soup.isOk()) << soup.status().toString();
  EXPECT_EQ(soup->numFaces(), 1);
  EXPECT_EQ(soup->indices.size(), 4u);
  auto truncated = readOffPolygons("OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n", "t.off");
  ASSERT_FALSE(truncated.isOk());
  EXPECT_NE(truncated.status().message().find("t.off: truncated: 1 of 2 faces"), std::string::npos);
  auto badIndex = readOffPolygons("OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 3\n", "i.off");
  ASSERT_FALSE(badIndex.isOk());
  EXPECT_NE(badIndex.status().message().find("i.off:6: bad vertex index '3'"), std::string::npos);
}

TEST(SchemePolygonReader, PlyPolygonsAndIndicesCheckedAgainstTheDeclaredVertices) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
  auto quad = importPolygonSoup(header + "4 0 1 2 3\n", ".ply", "q.ply");
  ASSERT_TRUE(quad.isOk()) << quad.status().toString();
  EXPECT_EQ(quad->numFaces(), 1);
  EXPECT_EQ(quad->indices.size(), 4u);
  auto badIndex = importPolygonSoup(header + "4 0 1 2 4\n", ".ply", "i.ply");
  ASSERT_FALSE(badIndex.isOk());
  EXPECT_NE(badIndex.status().message().find("i.ply: face 0: vertex index 4 names no vertex (4 vertices)"),
            std::string::npos)
      << badIndex.status().toString();
}

TEST(SchemePolygonReader, TagFilesApplyToPolygonsWithLineNumbers) {
  const std::string mesh = writeTemp("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const std::string good = writeTemp("good.tags", "# tags\ncrease 0 1 inf\ncorner 2 1.5\n");
  auto tagged = importPolygonMesh(mesh, good);
  ASSERT_TRUE(tagged.isOk()) << tagged.status().toString();
  ASSERT_EQ(tagged->topology.creases.size(), 1u);
  EXPECT_EQ(tagged->topology.vertexSharpness[2], 1.5f);
  const std::string diagonal = writeTemp("diag.tags", "crease 0 2 1\n");
  auto noEdge = importPolygonMesh(mesh, diagonal);
  ASSERT_FALSE(noEdge.isOk());
  EXPECT_NE(noEdge.status().message().find("diag.tags:1: vertices 0 and 2 share no edge"), std::string::npos)
      << noEdge.status().toString();
  const std::string twice = writeTemp("twice.tags", "crease 0 1 1\ncrease 1 0 2\n");
  auto duplicate = importPolygonMesh(mesh, twice);
  ASSERT_FALSE(duplicate.isOk());
  EXPECT_NE(duplicate.status().message().find("already tagged at line 1"), std::string::npos);
}

TEST(SchemeNames, ParseAndDescribe) {
  for (const std::string& name : schemeNames()) {
    auto scheme = parseScheme(name);
    ASSERT_TRUE(scheme.isOk());
    EXPECT_EQ(schemeName(*scheme), name);
  }
  auto unknown = parseScheme("kobbelt");
  ASSERT_FALSE(unknown.isOk());
  EXPECT_NE(unknown.status().message().find("unknown scheme 'kobbelt'"), std::string::npos);
  EXPECT_TRUE(limitUnavailableReason(Scheme::kCatmullClark).empty());
  EXPECT_FALSE(limitUnavailableReason(Scheme::kButterfly).empty());
}

}  // namespace
}  // namespace tessera
