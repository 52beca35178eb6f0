// The control cage (core/document/control_cage.h) against OpenSubdiv 3.5:
// at every level, the cage's polygons are Far's faces of that level, corner
// for corner and in the same turning order. Far numbers its vertices its own
// way, so each of Far's vertices is matched to Tessera's by position (every
// level's points equal Far's within 1e-12 of the diagonal:
// catmark_document_oracle_test.cc), and faces are compared as cyclic
// sequences of the matched indices.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/document/control_cage.h"
#include "oracle/catmark_cases.h"
#include "oracle/osd_catmark_reference.h"
#include "support/polygon_meshes.h"

namespace tessera {
namespace {

constexpr int kLevels = 3;
using Face = std::vector<uint64_t>;

// The rotation that starts at the smallest index: one name per cyclic
// sequence, which keeps the turning order.
Face canonical(Face f) {
  std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
  return f;
}

double diagonalOf(const std::vector<Vec3>& points) {
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) lo.minimize(p), hi.maximize(p);
  return (hi - lo).norm();
}

// Our index of each of Far's points: the one point within `tolerance`.
std::vector<uint64_t> matchByPosition(const std::vector<oracle::OsdDoublePoint>& far,
                                      const std::vector<Vec3>& ours, double tolerance) {
  std::vector<size_t> byX(ours.size());
  for (size_t i = 0; i < ours.size(); ++i) byX[i] = i;
  std::sort(byX.begin(), byX.end(), [&](size_t a, size_t b) { return ours[a][0] < ours[b][0]; });
  std::vector<uint64_t> match(far.size(), ~uint64_t{0});
  for (size_t v = 0; v < far.size(); ++v) {
    const Vec3 p(far[v].x, far[v].y, far[v].z);
    auto it = std::lower_bound(byX.begin(), byX.end(), p[0] - tolerance,
                               [&](size_t i, double x) { return ours[i][0] < x; });
    for (; it != byX.end() && ours[*it][0] <= p[0] + tolerance; ++it) {
      if ((ours[*it] - p).norm() > tolerance) continue;
      EXPECT_EQ(match[v], ~uint64_t{0}) << "two points of ours at Far's vertex " << v;
      match[v] = *it;
    }
    EXPECT_NE(match[v], ~uint64_t{0}) << "no point of ours at Far's vertex " << v;
  }
  return match;
}

std::vector<Face> facesOf(const ControlCage& cage) {
  std::vector<Face> faces;
  size_t at = 0;
  for (uint32_t n : cage.faceSizes) {
    faces.emplace_back(cage.vertices.begin() + static_cast<std::ptrdiff_t>(at),
                       cage.vertices.begin() + static_cast<std::ptrdiff_t>(at + n));
    at += n;
  }
  EXPECT_EQ(at, cage.vertices.size());
  return faces;
}

void checkCage(const testing::PolyTestMesh& mesh, const CreaseOptions& options) {
  SCOPED_TRACE(mesh.name);
  auto doc =
      Document::create(mesh.topology, mesh.points,
                       {.loop = options, .maxLevel = kLevels, .scheme = DocumentScheme::kCatmullClark});
  ASSERT_TRUE(doc.isOk()) << doc.status().toString();
  const oracle::OsdPolyInput input(mesh.topology);
  auto refiner =
      oracle::createOsdQuadRefiner(input, schemes::QuadScheme::kCatmullClark, options, kLevels, true);
  std::vector<oracle::OsdDoublePoint> base;
  for (const Vec3& p : mesh.points) base.push_back({p[0], p[1], p[2]});
  const double diag = diagonalOf(mesh.points);
  for (int level = 0; level <= kLevels; ++level) {
    SCOPED_TRACE("level " + std::to_string(level));
    auto cage = controlCage(*doc, level);
    ASSERT_TRUE(cage.isOk()) << cage.status().toString();
    EXPECT_EQ(cage->level, level);
    const std::vector<Face> ours = facesOf(*cage);
    const auto& farLevel = refiner->GetLevel(level);
    ASSERT_EQ(ours.size(), static_cast<size_t>(farLevel.GetNumFaces()));
    if (level == 0) {
      // The base polygons as the mesh gave them, n-gons kept.
      for (int f = 0; f < mesh.topology.numFaces(); ++f) {
        const Face given(mesh.topology.indices.begin() + mesh.topology.faceOffsets[f],
                         mesh.topology.indices.begin() + mesh.topology.faceOffsets[f + 1]);
        EXPECT_EQ(ours[f], given) << "base face " << f;
      }
    } else {
      for (const Face& f : ours) EXPECT_EQ(f.size(), 4u) << "a face below the base is a quad";
    }
    auto eval = doc->evaluate(level);
    ASSERT_TRUE(eval.isOk());
    const auto farPoints = oracle::interpolateOsdDouble(*refiner, base, level);
    const auto match = matchByPosition(farPoints, (*eval)->points[level], 1e-9 * diag);
    if (::testing::Test::HasFailure()) return;
    std::multiset<Face> expected, got;
    for (int f = 0; f < farLevel.GetNumFaces(); ++f) {
      Face mapped;
      for (int v : farLevel.GetFaceVertices(f)) mapped.push_back(match[v]);
      expected.insert(canonical(mapped));
    }
    for (const Face& f : ours) got.insert(canonical(f));
    EXPECT_TRUE(got == expected) << "the cage's polygons are not Far's faces";
  }
  auto beyond = controlCage(*doc, kLevels + 1);
  ASSERT_FALSE(beyond.isOk());
  EXPECT_NE(beyond.status().message().find("level 4"), std::string::npos) << beyond.status().message();
}

TEST(ControlCageOracle, EveryLevelsPolygonsAreFarsFaces) {
  for (const testing::PolyTestMesh& shape : testing::catmarkShapes()) {
    checkCage(shape, {});
    if (HasFailure()) return;
  }
  checkCage(testing::withPolyJitter(testing::mixedPrism(6, true), 0.05, 5),
            {CreaseMethod::kChaikin, BoundaryInterpolation::kEdgeAndCorner});
}

}  // namespace
}  // namespace tessera
