// Catmull-Clark (and bilinear) against OpenSubdiv 3.5: Far::TopologyRefiner
// with SCHEME_CATMARK, PrimvarRefinerReal<double> for refined points and
// Limit(). Refined points at levels 1..3 within 1e-12 of the bounding-box
// diagonal, limit positions within 1e-9 of it and limit normals within
// 1e-6 rad, on quads, triangles and any polygons, closed and open, with
// random semi-sharp and infinitely sharp tags from fixed seeds, under both
// crease methods and both boundary rules.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "core/catmark/limit.h"
#include "core/io/mesh_export.h"
#include "core/io/mesh_import.h"
#include "core/schemes/polygon_reader.h"
#include "core/schemes/quad_refiner.h"
#include "oracle/catmark_cases.h"
#include "oracle/osd_catmark_reference.h"
#include "support/polygon_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using schemes::QuadRefiner;
using schemes::QuadScheme;
using testing::PolyTestMesh;

using oracle::kNormalTolerance;
using oracle::kPointTolerance;
using oracle::kPositionTolerance;

double angleBetween(const Vec3& a, const Vec3& b) {
  return std::atan2((a % b).norm(), a | b);
}

struct Totals {
  long long points = 0, limits = 0, normals = 0, degenerateNormals = 0, notLimits = 0;
};

void printTotals(const Totals& totals) {
  std::printf(
      "points %lld, limits %lld, normals %lld (parallel OpenSubdiv tangents skipped: %lld; darts and crease "
      "spans of 3+ faces left to the Bfr test: %lld)\n",
      totals.points, totals.limits, totals.normals, totals.degenerateNormals, totals.notLimits);
}

// Compares every level's points (and limits where the level is all quads).
void checkAgainstOsd(const PolyTestMesh& mesh, QuadScheme scheme, const CreaseOptions& options, int levels,
                     Totals& totals) {
  SCOPED_TRACE(mesh.name + (options.creaseMethod == CreaseMethod::kChaikin ? " chaikin" : " uniform") +
               (options.boundary == BoundaryInterpolation::kEdgeOnly ? " edge-only" : " edge-and-corner"));
  auto refiner = QuadRefiner::create(mesh.topology, scheme, options, {.levels = levels});
  ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
  const auto ours = refiner->refinePointsPerLevel(mesh.points);
  const bool limit = scheme == QuadScheme::kCatmullClark;
  const int firstLimitLevel = refiner->level(0).allQuads() ? 0 : 1;
  const auto osd = oracle::refineQuadsWithOpenSubdiv(mesh.topology, mesh.points, options, *refiner, limit,
                                                     firstLimitLevel);
  const double diag = oracle::boundingDiagonal(mesh.points);
  for (int l = 0; l <= levels; ++l) {
    const int n = refiner->level(l).numVertices;
    ASSERT_EQ(static_cast<int>(ours[l].size()), n);
    for (int v = 0; v < n; ++v) {
      ASSERT_LE((ours[l][v] - osd[l].points[v]).norm(), kPointTolerance * diag)
          << "level " << l << " vertex " << v;
    }
    totals.points += n;
    if (!limit || l < firstLimitLevel) continue;
    std::vector<Vec3> positions(n), normals(n);
    ASSERT_TRUE(computeCatmarkLimit(refiner->level(l), options, ours[l], positions, normals).isOk());
    for (int v = 0; v < n; ++v) {
      if (oracle::limitNormalDiffersFromFar(refiner->level(l), v, options)) {
        ++totals.notLimits;  // Limit() is not the surface here
        continue;
      }
      ASSERT_LE((positions[v] - osd[l].limitPositions[v]).norm(), kPositionTolerance * diag)
          << "limit at level " << l << " vertex " << v;
      const Vec3 osdNormal = osd[l].limitTangent1[v] % osd[l].limitTangent2[v];
      const double scale = osd[l].limitTangent1[v].norm() * osd[l].limitTangent2[v].norm();
      if (!(osdNormal.norm() > 1e-12 * scale)) {
        ++totals.degenerateNormals;  // parallel tangents: Limit() gives no normal
        continue;
      }
      ASSERT_LE(angleBetween(normals[v], osdNormal), kNormalTolerance)
          << "normal at level " << l << " vertex " << v;
      ++totals.normals;
    }
    totals.limits += n;
  }
}

std::vector<PolyTestMesh> shapes() {
  return testing::catmarkShapes();
}

TEST(CatmarkOracle, ProceduralShapesWithoutTags) {
  Totals totals;
  for (const auto& mesh : shapes()) {
    for (const auto& options : oracle::allCreaseOptions())
      checkAgainstOsd(mesh, QuadScheme::kCatmullClark, options, 3, totals);
  }
  EXPECT_GT(totals.normals, 0);
  printTotals(totals);
}

TEST(CatmarkOracle, RandomTagsFromFixedSeeds) {
  Totals totals;
  for (const auto& mesh : shapes()) {
    for (uint32_t seed : {1u, 2u, 3u}) {
      const PolyTestMesh tagged = testing::withRandomPolyTags(mesh, 0.3, 0.1, seed);
      for (const auto& options : oracle::allCreaseOptions())
        checkAgainstOsd(tagged, QuadScheme::kCatmullClark, options, 3, totals);
    }
  }
  EXPECT_GT(totals.normals, 0);
  printTotals(totals);
}

TEST(CatmarkOracle, RealPolygonMeshDoubleTorus) {
  const std::string path = testing::cgalMeshPath("double-torus-example.off");
  auto mesh = schemes::importPolygonMesh(path, "");
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  PolyTestMesh real{"double-torus-example", mesh->topology, mesh->points};
  int pentagonsOrMore = 0;
  for (int f = 0; f < real.topology.numFaces(); ++f) {
    pentagonsOrMore += real.topology.faceOffsets[f + 1] - real.topology.faceOffsets[f] >= 5 ? 1 : 0;
  }
  EXPECT_GT(pentagonsOrMore, 0);
  Totals totals;
  checkAgainstOsd(real, QuadScheme::kCatmullClark, {}, 3, totals);
  checkAgainstOsd(testing::withRandomPolyTags(real, 0.2, 0.05, 5), QuadScheme::kCatmullClark,
                  {CreaseMethod::kChaikin, BoundaryInterpolation::kEdgeOnly}, 3, totals);
  EXPECT_GT(totals.normals, 0);
}

TEST(CatmarkOracle, RealTriangleMeshFandiskWithRandomTags) {
  auto base = importMesh(testing::cgalMeshPath("fandisk.off"));
  ASSERT_TRUE(base.isOk()) << base.status().toString();
  PolyTestMesh real{"fandisk", PolyTopology::fromBaseMesh(*base), base->positions()};
  Totals totals;
  checkAgainstOsd(testing::withRandomPolyTags(real, 0.05, 0.01, 9), QuadScheme::kCatmullClark, {}, 2, totals);
  EXPECT_GT(totals.normals, 0);
}

TEST(BilinearOracle, MatchesOpenSubdivOnPolygons) {
  Totals totals;
  for (const auto& mesh : shapes()) checkAgainstOsd(mesh, QuadScheme::kBilinear, {}, 3, totals);
  EXPECT_GT(totals.points, 0);
}

// Written polygons (`tessera refine --scheme catmull-clark|bilinear` to OBJ,
// OFF and PLY, core/io/mesh_export.h) are OpenSubdiv's faces of the finest
// level: as many, each the same cycle of vertices, read back from the file.
// Vertices are matched by position (ours and OpenSubdiv's agree to 1e-12 of
// the diagonal, PLY's float32 to 1e-6 of it; the closest two vertices of
// these meshes are far apart), so neither numbering is assumed.
class NearestVertex {
 public:
  NearestVertex(const std::vector<Vec3>& points, double cell) : points_(points), cell_(cell) {
    for (size_t v = 0; v < points.size(); ++v) cells_[keyOf(points[v])].push_back(static_cast<int>(v));
  }
  // The vertex within `tolerance` of p, or -1.
  int find(const Vec3& p, double tolerance) const {
    const auto k = keyOf(p);
    int best = -1;
    double bestDistance = tolerance;
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          auto it = cells_.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == cells_.end()) continue;
          for (int v : it->second) {
            const double d = (points_[v] - p).norm();
            if (d <= bestDistance) best = v, bestDistance = d;
          }
        }
    return best;
  }

 private:
  std::array<long long, 3> keyOf(const Vec3& p) const {
    return {std::llround(p[0] / cell_), std::llround(p[1] / cell_), std::llround(p[2] / cell_)};
  }
  const std::vector<Vec3>& points_;
  double cell_;
  std::map<std::array<long long, 3>, std::vector<int>> cells_;
};

// A face as its cycle of vertices from the lowest.
std::vector<int> cycleFromLowest(std::vector<int> corners) {
  std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
  return corners;
}

TEST(CatmarkOracle, WrittenPolygonsAreOpenSubdivsFacesOfTheFinestLevel) {
  const std::string dir = testing::makeTempDir("catmark-polygons");
  auto real = schemes::importPolygonMesh(testing::cgalMeshPath("double-torus-example.off"), "");
  ASSERT_TRUE(real.isOk());
  std::vector<PolyTestMesh> meshes = shapes();
  meshes.push_back({"double-torus-example", real->topology, real->points});
  int compared = 0;
  for (const PolyTestMesh& mesh : meshes) {
    const double diag = oracle::boundingDiagonal(mesh.points);
    for (QuadScheme scheme : {QuadScheme::kCatmullClark, QuadScheme::kBilinear}) {
      for (int levels : {1, 2}) {
        const std::string where = mesh.name +
                                  (scheme == QuadScheme::kBilinear ? " bilinear" : " catmull-clark") +
                                  " level " + std::to_string(levels);
        auto refiner = QuadRefiner::create(mesh.topology, scheme, {}, {.levels = levels});
        ASSERT_TRUE(refiner.isOk()) << where;
        const SurfaceMesh surface = refiner->controlSurface(refiner->refinePoints(mesh.points));
        const NearestVertex ours(surface.positions, 1e-6 * diag);
        // OpenSubdiv's faces of the finest level, in our vertices.
        oracle::OsdPolyInput input(mesh.topology);
        auto osd = oracle::createOsdQuadRefiner(input, scheme, {}, levels, false);
        std::vector<oracle::OsdDoublePoint> base;
        for (const Vec3& p : mesh.points) base.push_back({p[0], p[1], p[2]});
        const auto points = oracle::interpolateOsdDouble(*osd, base, levels);
        const auto& level = osd->GetLevel(levels);
        std::multiset<std::vector<int>> expected;
        for (int f = 0; f < level.GetNumFaces(); ++f) {
          std::vector<int> corners;
          for (int v : level.GetFaceVertices(f)) {
            corners.push_back(ours.find({points[v].x, points[v].y, points[v].z}, 1e-12 * diag));
            ASSERT_GE(corners.back(), 0) << where << ": OpenSubdiv's vertex " << v << " is none of ours";
          }
          expected.insert(cycleFromLowest(corners));
        }
        for (const std::string ext : {".obj", ".off", ".ply"}) {
          const std::string path = dir + "/refined" + ext;
          ASSERT_TRUE(exportMesh(surface, path).isOk()) << where << ext;
          auto back = schemes::importPolygonMesh(path, "");
          ASSERT_TRUE(back.isOk()) << where << ext << ": " << back.status().toString();
          ASSERT_EQ(back->topology.numFaces(), level.GetNumFaces()) << where << ext;
          // OBJ and OFF print each coordinate so that it reads back exactly;
          // PLY stores float32.
          const double tolerance = ext == std::string(".ply") ? 1e-6 * diag : 0;
          std::multiset<std::vector<int>> written;
          for (int f = 0; f < back->topology.numFaces(); ++f) {
            std::vector<int> corners;
            for (int k = back->topology.faceOffsets[f]; k < back->topology.faceOffsets[f + 1]; ++k) {
              corners.push_back(ours.find(back->points[back->topology.indices[k]], tolerance));
              ASSERT_GE(corners.back(), 0) << where << ext << ": face " << f;
            }
            written.insert(cycleFromLowest(corners));
          }
          EXPECT_EQ(written, expected) << where << ext;
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(compared, 6 * 2 * 2 * 3);
}

// A refined cage written to OBJ with its tags (OpenSubdiv's `t` dialect,
// docs/FORMATS.md "Tags in OBJ") is the same subdivision surface: read back,
// its creases and corners are the refined level's (decayed semi-sharp values
// included) and its options the run's; refined once more by OpenSubdiv, it
// gives Tessera's next level of the original to 1e-12 of the diagonal.
TEST(CatmarkOracle, AWrittenCageWithItsTagsRefinesToTheNextLevel) {
  const std::string dir = testing::makeTempDir("catmark-cage");
  PolyTestMesh tagged =
      testing::withRandomPolyTags(testing::withPolyJitter(testing::quadTorus(7, 5), 0.05, 3), 0.3, 0.1, 17);
  int checked = 0;
  for (const CreaseOptions& options : oracle::allCreaseOptions()) {
    SCOPED_TRACE(std::string(options.creaseMethod == CreaseMethod::kChaikin ? "chaikin" : "uniform") +
                 (options.boundary == BoundaryInterpolation::kEdgeOnly ? " edge-only" : " edge-and-corner"));
    for (int level : {1, 2}) {
      auto refiner =
          QuadRefiner::create(tagged.topology, QuadScheme::kCatmullClark, options, {.levels = level + 1});
      ASSERT_TRUE(refiner.isOk());
      const auto ours = refiner->refinePointsPerLevel(tagged.points);
      auto atLevel =
          QuadRefiner::create(tagged.topology, QuadScheme::kCatmullClark, options, {.levels = level});
      ASSERT_TRUE(atLevel.isOk());
      const SurfaceMesh cage = atLevel->controlSurface(ours[level]);
      const std::string path = dir + "/cage.obj";
      ASSERT_TRUE(exportMesh(cage, path).isOk());
      auto back = schemes::importPolygonMesh(path, "");
      ASSERT_TRUE(back.isOk()) << back.status().toString();
      EXPECT_EQ(back->boundary,
                options.boundary == BoundaryInterpolation::kEdgeOnly ? "edge-only" : "edge-and-corner");
      EXPECT_EQ(back->creaseMethod, options.creaseMethod == CreaseMethod::kChaikin ? "chaikin" : "uniform");
      // The tags read back are the level's, value for value.
      const Level& l = refiner->level(level);
      std::map<std::pair<int, int>, float> wanted, read;
      for (Index e = 0; e < static_cast<Index>(l.edgeVertices.size()); ++e)
        if (l.edgeSharpness[e] > 0)
          wanted[std::minmax(l.edgeVertices[e][0], l.edgeVertices[e][1])] = l.edgeSharpness[e];
      for (const auto& c : back->topology.creases) read[std::minmax(c.v0, c.v1)] = c.sharpness;
      EXPECT_EQ(read, wanted);
      EXPECT_FALSE(wanted.empty());
      for (Index v = 0; v < l.numVertices; ++v)
        EXPECT_EQ(back->topology.vertexSharpness.empty() ? 0.0f : back->topology.vertexSharpness[v],
                  l.vertexSharpness[v] > 0 ? l.vertexSharpness[v] : 0.0f)
            << v;
      // OpenSubdiv refines the cage as read back, with the options it states.
      CreaseOptions stated;
      stated.boundary = back->boundary == "edge-only" ? BoundaryInterpolation::kEdgeOnly
                                                      : BoundaryInterpolation::kEdgeAndCorner;
      stated.creaseMethod = back->creaseMethod == "chaikin" ? CreaseMethod::kChaikin : CreaseMethod::kUniform;
      oracle::OsdPolyInput input(back->topology);
      auto osd = oracle::createOsdQuadRefiner(input, QuadScheme::kCatmullClark, stated, 1, false);
      std::vector<oracle::OsdDoublePoint> base;
      for (const Vec3& p : back->points) base.push_back({p[0], p[1], p[2]});
      const auto next = oracle::interpolateOsdDouble(*osd, base, 1);
      // Matched by position (neither numbering assumed): every point of
      // OpenSubdiv's is one of our next level's, each a different one.
      ASSERT_EQ(next.size(), ours[level + 1].size());
      const double diag = oracle::boundingDiagonal(tagged.points);
      const NearestVertex nearest(ours[level + 1], 1e-6 * diag);
      std::set<int> matched;
      for (size_t v = 0; v < next.size(); ++v) {
        const int found = nearest.find(Vec3(next[v].x, next[v].y, next[v].z), 1e-12 * diag);
        ASSERT_GE(found, 0) << "OpenSubdiv's vertex " << v << " is none of ours within 1e-12 of the diagonal";
        matched.insert(found);
      }
      EXPECT_EQ(matched.size(), next.size());
      ++checked;
    }
  }
  EXPECT_EQ(checked, 8);
}

}  // namespace
}  // namespace tessera
