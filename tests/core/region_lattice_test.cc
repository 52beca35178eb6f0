// Region lattices (core/tessellation/region_lattice.h): the id the lattice
// gives each point of a region's root face is the canonical id the sparse
// hierarchy computes for the vertex there, on whole uniform levels of
// several meshes, for root faces at levels 0 and 1 and depths up to 4.
#include <gtest/gtest.h>

#include "core/document/document.h"
#include "core/tessellation/region_lattice.h"
#include "support/procedural_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using Point = std::array<int, 2>;

// The corner points of child k of a face with corners `at` (refinement.h:
// children 0..2 at the corners, 3 in the middle).
std::array<Point, 3> childCorners(const std::array<Point, 3>& at, int k) {
  auto mid = [&](int a, int b) { return Point{(at[a][0] + at[b][0]) / 2, (at[a][1] + at[b][1]) / 2}; };
  const Point m0 = mid(0, 1), m1 = mid(1, 2), m2 = mid(2, 0);
  switch (k) {
    case 0: return {at[0], m0, m2};
    case 1: return {m0, at[1], m1};
    case 2: return {m2, m1, at[2]};
    default: return {m1, m2, m0};
  }
}

void expectLatticeMatchesHierarchy(const testing::TestMesh& mesh, int rootLevel, int depth) {
  const int deepest = rootLevel + depth;
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = deepest, .uniformLevel = deepest});
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  const SparseEvaluator& h = doc->hierarchy();
  const LevelCounts& counts = doc->counts();
  const int n = 1 << depth;
  int checked = 0;
  for (uint64_t root = 0; root < counts.faces(rootLevel); ++root) {
    const FaceId face(rootLevel, root);
    auto frame = regionFrame(h, counts, face);
    ASSERT_TRUE(frame.isOk()) << frame.status().message();
    auto lattice = RegionLattice::build(*frame, depth);
    ASSERT_TRUE(lattice.isOk()) << lattice.status().message();
    // Every descendant face at the deepest level, found by its path of
    // child numbers, with the corner points that path gives.
    for (uint64_t path = 0; path < (uint64_t{1} << (2 * depth)); ++path) {
      std::array<Point, 3> at{Point{0, 0}, Point{n, 0}, Point{0, n}};
      for (int d = depth - 1; d >= 0; --d) at = childCorners(at, static_cast<int>((path >> (2 * d)) & 3));
      const uint64_t canonical = (root << (2 * depth)) | path;
      const Index local = h.level(deepest).findFace(canonical);
      ASSERT_GE(local, 0);
      for (int k = 0; k < 3; ++k) {
        const uint64_t index = h.level(deepest).vertexIds[h.level(deepest).mesh.faceVertices[local][k]];
        const auto id = lattice->idAt(at[k][0], at[k][1]);
        ASSERT_TRUE(id.has_value());
        ASSERT_EQ(id->index(), index) << mesh.name << " root " << face.toString() << " point (" << at[k][0] << ", "
                                      << at[k][1] << ")";
        ASSERT_EQ(id->level(), counts.birthLevel(*id));
        ASSERT_EQ(lattice->pointOf(*id), at[k]);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(RegionLattice, IdsEqualTheHierarchysOnUniformLevels) {
  for (const auto& mesh : {testing::icosahedron(), testing::torus(5, 4), testing::openGrid(3, 2)}) {
    for (int rootLevel : {0, 1}) {
      for (int depth : {0, 1, 2, 4}) {
        expectLatticeMatchesHierarchy(mesh, rootLevel, depth);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
}

TEST(RegionLattice, RefusesBadDepthsAndFrames) {
  const auto mesh = testing::icosahedron();
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 3, .uniformLevel = 1});
  ASSERT_TRUE(doc.isOk());
  auto frame = regionFrame(doc->hierarchy(), doc->counts(), FaceId(1, 7));
  ASSERT_TRUE(frame.isOk());
  EXPECT_EQ(RegionLattice::build(*frame, -1).status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(RegionLattice::build(*frame, kMaxLatticeDepth + 1).status().code(), ErrorCode::kInvalidArgument);
  RegionFrame bad = *frame;
  bad.corners[1] = doc->counts().vertices(1);
  Status status = RegionLattice::build(bad, 2).status();
  EXPECT_NE(status.message().find("corner or edge 1"), std::string::npos) << status.toString();
  bad = *frame;
  bad.face = FaceId(1, doc->counts().faces(1)).packed();
  EXPECT_NE(RegionLattice::build(bad, 2).status().message().find("does not exist"), std::string::npos);
  bad = *frame;
  bad.baseCounts = {uint64_t{1} << 57, uint64_t{1} << 57, uint64_t{1} << 57};
  EXPECT_NE(RegionLattice::build(bad, 3).status().message().find("overflow"), std::string::npos);
  auto lattice = RegionLattice::build(*frame, 2);
  ASSERT_TRUE(lattice.isOk());
  EXPECT_FALSE(lattice->idAt(3, 2).has_value());  // 3 + 2 > 4
  EXPECT_FALSE(lattice->idAt(-1, 0).has_value());
  EXPECT_TRUE(lattice->idAt(4, 0).has_value());
  EXPECT_EQ(RegionLattice::build(*frame, 2)->idAt(0, 0)->index(), frame->corners[0]);
  EXPECT_EQ(regionFrame(doc->hierarchy(), doc->counts(), FaceId(3, 0)).status().code(), ErrorCode::kNotFound);
}

}  // namespace
}  // namespace tessera
