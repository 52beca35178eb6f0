// mergeRegions (export, DocumentView::surface): copies of one vertex join
// by id and normal, and a joined vertex whose triangles form two fans that
// touch only at it (a crease's sides across a flat area: equal normals,
// while the crease's next vertices keep their sides apart) is split again,
// one copy per fan, so the merged mesh stays a manifold.
#include <gtest/gtest.h>

#include <numeric>

#include "core/tessellation/region_merge.h"

namespace tessera {
namespace {

// The number of edge-connected fans around each vertex.
std::vector<int> fansPerVertex(const SurfaceMesh& mesh) {
  std::vector<int> fans(mesh.positions.size(), 0);
  for (int v = 0; v < static_cast<int>(mesh.positions.size()); ++v) {
    std::vector<std::array<int, 2>> corners;  // (prev, next) around v
    for (const auto& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        if (t[k] == v) corners.push_back({t[(k + 2) % 3], t[(k + 1) % 3]});
      }
    }
    std::vector<int> parent(corners.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int i) {
      while (parent[i] != i) i = parent[i];
      return i;
    };
    for (size_t i = 0; i < corners.size(); ++i)
      for (size_t j = 0; j < corners.size(); ++j)
        if (corners[i][1] == corners[j][0]) parent[find(static_cast<int>(i))] = find(static_cast<int>(j));
    for (size_t i = 0; i < corners.size(); ++i)
      fans[v] += find(static_cast<int>(i)) == static_cast<int>(i) ? 1 : 0;
  }
  return fans;
}

RegionMesh regionOf(std::vector<uint64_t> ids, std::vector<Vec3> positions, std::vector<Vec3> normals,
                    std::vector<std::array<int, 3>> triangles) {
  return {std::move(positions), std::move(normals), std::move(ids), std::move(triangles)};
}

TEST(RegionMerge, AFlatCreaseVertexWithTwoFansIsSplitPerFan) {
  // P on a crease Q-P-R across a flat area: both sides' copies of P have
  // the flat normal, the copies of Q and R have their sides' normals.
  const Vec3 up(0, 0, 1), left(-0.6, 0, 0.8), right(0.6, 0, 0.8);
  const Vec3 p(0, 0, 0), q(0, 1, 0), r(0, -1, 0), x(-1, 0, 0), y(1, 0, 0);
  std::map<uint64_t, RegionMesh> regions;
  regions[1] = regionOf({10, 11, 12, 13}, {p, q, x, r}, {up, left, up, left}, {{0, 1, 2}, {0, 2, 3}});
  regions[2] = regionOf({10, 13, 14, 11}, {p, r, y, q}, {up, right, up, right}, {{0, 1, 2}, {0, 2, 3}});
  const SurfaceMesh merged = mergeRegions(regions);
  ASSERT_EQ(merged.triangles.size(), 4u);
  EXPECT_EQ(merged.positions.size(), 8u) << "P's two fans share one vertex";
  for (int fans : fansPerVertex(merged)) EXPECT_EQ(fans, 1);
  for (const auto& t : merged.triangles) {
    EXPECT_EQ(merged.positions[t[0]][0], p[0]);  // every triangle still starts at P
    EXPECT_EQ(merged.positions[t[0]][1], p[1]);
  }
}

TEST(RegionMerge, CopiesOfOneFanAcrossRegionsStayOneVertex) {
  // An octahedron cut into two regions along its equator: every equator
  // vertex is in both, with one normal, and joins into one.
  const std::vector<Vec3> pts = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::map<uint64_t, RegionMesh> regions;
  regions[1] =
      regionOf({0, 1, 2, 3, 4}, {pts[0], pts[1], pts[2], pts[3], pts[4]},
               {pts[0], pts[1], pts[2], pts[3], pts[4]}, {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
  regions[2] =
      regionOf({0, 1, 2, 3, 5}, {pts[0], pts[1], pts[2], pts[3], pts[5]},
               {pts[0], pts[1], pts[2], pts[3], pts[5]}, {{1, 0, 4}, {2, 1, 4}, {3, 2, 4}, {0, 3, 4}});
  const SurfaceMesh merged = mergeRegions(regions);
  EXPECT_EQ(merged.positions.size(), 6u);
  EXPECT_EQ(merged.triangles.size(), 8u);
  for (int fans : fansPerVertex(merged)) EXPECT_EQ(fans, 1);
}

}  // namespace
}  // namespace tessera
