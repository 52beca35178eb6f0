// The viewer's control cage (client/view/control_cage.h) as pure functions:
// a Cage reply becomes each edge once over packed ids of its level, a
// malformed reply is refused naming the face, and only edges whose two ends
// are shown and face the eye are drawn. Expected values are counted by hand.
#include <gtest/gtest.h>

#include "client/view/control_cage.h"
#include "core/hierarchy/ids.h"

namespace tessera::view {
namespace {

wire::Cage cageOf(uint32_t level, const std::vector<std::vector<uint64_t>>& faces) {
  wire::Cage c;
  c.set_level(level);
  c.set_version(7);
  for (const auto& f : faces) {
    c.add_face_sizes(static_cast<uint32_t>(f.size()));
    for (uint64_t v : f) c.add_vertices(v);
  }
  return c;
}

uint64_t id(int level, uint64_t index) {
  return VertexId(level, index).packed();
}

TEST(ViewControlCage, ACubesSixQuadsHaveTwelveEdges) {
  const auto cage = controlCageOf(
      cageOf(2, {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}));
  ASSERT_TRUE(cage.isOk()) << cage.status().toString();
  EXPECT_EQ(cage->level, 2);
  EXPECT_EQ(cage->version, 7u);
  EXPECT_EQ(cage->faces(), 6u);
  EXPECT_EQ(cage->facesBySize, (std::map<uint32_t, size_t>{{4, 6}}));
  ASSERT_EQ(cage->edges.size(), 12u);
  EXPECT_EQ(cage->edges.front(), std::make_pair(id(2, 0), id(2, 1)));
  EXPECT_EQ(cage->edges.back(), std::make_pair(id(2, 6), id(2, 7)));
}

TEST(ViewControlCage, AQuadAndATriangleSharingAnEdgeHaveSixAndIndicesKeepTheirHighBits) {
  const uint64_t big = (uint64_t{1} << 40) + 5;
  const auto cage = controlCageOf(cageOf(3, {{0, 1, 2, big}, {2, 1, 9}}));
  ASSERT_TRUE(cage.isOk()) << cage.status().toString();
  EXPECT_EQ(cage->facesBySize, (std::map<uint32_t, size_t>{{3, 1}, {4, 1}}));
  EXPECT_EQ(cage->edges.size(), 6u);
  // Sorted: (0 1) (0 big) (1 2) (1 9) (2 9) (2 big).
  EXPECT_EQ(cage->edges[1], std::make_pair(id(3, 0), id(3, big)));
  EXPECT_EQ(cage->edges.back(), std::make_pair(id(3, 2), id(3, big)));
  EXPECT_EQ(VertexId::fromPacked(cage->edges.back().second).index(), big);
}

TEST(ViewControlCage, MalformedRepliesAreRefusedNamingTheFace) {
  auto two = controlCageOf(cageOf(1, {{0, 1, 2}, {3, 4}}));
  ASSERT_FALSE(two.isOk());
  EXPECT_NE(two.status().message().find("face 1 has 2 corners"), std::string::npos) << two.status().message();
  wire::Cage shortOf = cageOf(1, {{0, 1, 2, 3}});
  shortOf.set_face_sizes(0, 5);
  auto over = controlCageOf(shortOf);
  ASSERT_FALSE(over.isOk());
  EXPECT_NE(over.status().message().find("face 0 has 5 corners, but only 4"), std::string::npos)
      << over.status().message();
  wire::Cage extra = cageOf(1, {{0, 1, 2}});
  extra.add_vertices(9);
  auto left = controlCageOf(extra);
  ASSERT_FALSE(left.isOk());
  EXPECT_NE(left.status().message().find("use 3 of the 4 vertices"), std::string::npos)
      << left.status().message();
  auto huge = controlCageOf(cageOf(1, {{0, 1, uint64_t{1} << 60}}));
  ASSERT_FALSE(huge.isOk());
  EXPECT_NE(huge.status().message().find("face 0 has an index beyond 58 bits"), std::string::npos);
}

TEST(ViewControlCage, OnlyEdgesOfFacesTurnedToTheEyeWithBothEndsShownAreDrawn) {
  // A square in z = 0, counter-clockwise seen from +z, its corner 3 not
  // shown: seen from +z its shown corners still turn their front to the
  // eye, and of its four edges 0-1 and 1-2 have both ends; from -z, none.
  // The normals (one facing away) play no part.
  const auto cage = controlCageOf(cageOf(0, {{0, 1, 2, 3}}));
  ASSERT_TRUE(cage.isOk());
  const std::vector<ControlPoint> points = {
      {id(0, 0), {0, 0, 0}, {0, 0, 1}}, {id(0, 1), {1, 0, 0}, {0, 0, 1}}, {id(0, 2), {1, 1, 0}, {0, 0, -1}}};
  const std::vector<V3> segments = cageSegments(*cage, points, {0.5f, 0.5f, 3});
  ASSERT_EQ(segments.size(), 4u);
  EXPECT_EQ(segments[0].x, 0.0f);  // 0-1
  EXPECT_EQ(segments[1].x, 1.0f);
  EXPECT_EQ(segments[2].y, 0.0f);  // 1-2
  EXPECT_EQ(segments[3].y, 1.0f);
  EXPECT_TRUE(cageSegments(*cage, points, {0.5f, 0.5f, -3}).empty()) << "the square's back";
}

TEST(ViewControlCage, AnEdgeIsDrawnWhenEitherOfItsFacesIsTurnedToTheEye) {
  // Two squares folded along the shared edge 1-4: face 0 in z = 0, its
  // front towards +z; face 1 folded down into x = 1, its front towards +x.
  // An eye up and to the left sees only face 0's front: its four edges are
  // drawn (the shared one too), none of face 1's other three.
  const auto cage = controlCageOf(cageOf(0, {{0, 1, 4, 3}, {1, 2, 5, 4}}));
  ASSERT_TRUE(cage.isOk());
  ASSERT_EQ(cage->edges.size(), 7u);
  const std::vector<ControlPoint> points = {{id(0, 0), {0, 0, 0}, {}},  {id(0, 1), {1, 0, 0}, {}},
                                            {id(0, 2), {1, 0, -1}, {}}, {id(0, 3), {0, 1, 0}, {}},
                                            {id(0, 4), {1, 1, 0}, {}},  {id(0, 5), {1, 1, -1}, {}}};
  EXPECT_EQ(cageSegments(*cage, points, {-5, 0.5f, 5}).size(), 2u * 4);
  EXPECT_EQ(cageSegments(*cage, points, {5, 0.5f, -0.5f}).size(), 2u * 4) << "face 1's front only";
  EXPECT_EQ(cageSegments(*cage, points, {5, 0.5f, 5}).size(), 2u * 7) << "both fronts";
}

}  // namespace
}  // namespace tessera::view
