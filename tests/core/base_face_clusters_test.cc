// Base faces grouped into regions (core/tessellation/base_face_clusters.h,
// docs/REGION_ENCODING.md "Region groups"): every face in exactly one
// cluster, each cluster edge-connected and at most the size asked, named by
// its lowest face, the same from every build; and a grouped tessellation
// shows exactly the triangles of its faces' regions, over the same vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/base_face_clusters.h"
#include "core/tessellation/tessellation.h"
#include "support/procedural_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

// Whether the faces form one piece over shared edges.
bool edgeConnected(const BaseTopology& base, std::span<const int> faces) {
  std::map<std::pair<int, int>, std::vector<int>> byEdge;
  for (int f : faces) {
    for (int k = 0; k < 3; ++k) {
      const int a = base.triangles[f][k], b = base.triangles[f][(k + 1) % 3];
      byEdge[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  }
  std::map<int, int> parent;
  for (int f : faces) parent[f] = f;
  std::function<int(int)> find = [&](int f) { return parent[f] == f ? f : parent[f] = find(parent[f]); };
  for (const auto& [edge, around] : byEdge)
    for (size_t i = 1; i < around.size(); ++i) parent[find(around[i])] = find(around[0]);
  std::set<int> roots;
  for (int f : faces) roots.insert(find(f));
  return roots.size() == 1;
}

TEST(BaseFaceClusters, EveryFaceIsInOneConnectedClusterNamedByItsLowestFace) {
  auto fandisk = importMesh(testing::cgalMeshPath("fandisk.off"));
  ASSERT_TRUE(fandisk.isOk());
  const BaseTopology base = BaseTopology::fromBaseMesh(*fandisk);
  const int n = static_cast<int>(base.triangles.size());
  for (int size : {1, 4, 16, 64, 256}) {
    const BaseFaceClusters c = BaseFaceClusters::build(base, size);
    std::vector<int> seen(n, 0);
    int full = 0;
    for (uint32_t k = 0; k < static_cast<uint32_t>(c.numClusters()); ++k) {
      const auto faces = c.facesOf(k);
      ASSERT_FALSE(faces.empty());
      EXPECT_LE(static_cast<int>(faces.size()), size);
      EXPECT_TRUE(std::is_sorted(faces.begin(), faces.end()));
      EXPECT_EQ(c.seedOf(k), faces.front()) << "size " << size << " cluster " << k;
      for (int f : faces) {
        ++seen[f];
        EXPECT_EQ(c.clusterOf(f), k);
      }
      EXPECT_TRUE(edgeConnected(base, faces)) << "size " << size << " cluster " << k;
      if (static_cast<int>(faces.size()) == size) full += size;
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; })) << "size " << size;
    // Growth breadth-first leaves few fragments: most faces are in full clusters.
    EXPECT_GE(full, n * 7 / 10) << "size " << size << ": " << c.numClusters() << " clusters";
    const BaseFaceClusters again = BaseFaceClusters::build(base, size);
    ASSERT_EQ(again.numClusters(), c.numClusters());
    for (int f = 0; f < n; ++f) ASSERT_EQ(again.clusterOf(f), c.clusterOf(f));
  }
}

TEST(RegionGroups, AGroupShowsItsFacesTrianglesOverTheSameVertices) {
  const testing::TestMesh mesh = testing::withRandomFlips(testing::torus(24, 16), 20, 5);
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 4});
  ASSERT_TRUE(doc.isOk());
  // Deepest level 3: grouped, 4^(6 - 3) = 64 faces to a region. Deepest
  // level 4: a region per base face, the same triangles.
  const LodProfile grouped{.baseLevel = 1, .maxLevel = 3, .angleThresholdDegrees = 8};
  auto t = Tessellation::build(*doc, grouped);
  ASSERT_TRUE(t.isOk()) << t.status().message();
  ASSERT_TRUE(t->regionsAreGroups());
  const BaseFaceClusters clusters = BaseFaceClusters::build(doc->baseTopology(), 64);
  ASSERT_EQ(static_cast<int>(t->regions().size()), clusters.numClusters());
  int64_t triangles = 0;
  for (const auto& [id, region] : t->regions()) {
    const FaceId seed = FaceId::fromPacked(id);
    ASSERT_EQ(seed.level(), 0);
    EXPECT_EQ(clusters.seedOf(clusters.clusterOf(static_cast<int>(seed.index()))),
              static_cast<int>(seed.index()));
    triangles += static_cast<int64_t>(region.triangles.size());
    // One vertex per (id, normal): no duplicates inside a group.
    std::set<std::tuple<uint64_t, double, double, double>> keys;
    for (size_t v = 0; v < region.positions.size(); ++v)
      keys.insert({region.vertexIds[v], region.normals[v][0], region.normals[v][1], region.normals[v][2]});
    EXPECT_EQ(keys.size(), region.positions.size());
  }
  EXPECT_EQ(triangles, t->numTriangles());
  const LodProfile perFace{.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 8};
  auto deep = Tessellation::build(*doc, perFace);
  ASSERT_TRUE(deep.isOk());
  EXPECT_FALSE(deep->regionsAreGroups());
  EXPECT_EQ(static_cast<int>(deep->regions().size()), static_cast<int>(mesh.topology.triangles.size()));
}

}  // namespace
}  // namespace tessera
