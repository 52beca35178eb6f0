// The 27-entry split table of dynamic refinement (core/render/split_table.h): every
// entry is a valid, counter-clockwise triangulation of the triangle with
// its split points, with the right number of triangles and none of zero
// area, checked on the table's reference triangle and on a scalene 3D one.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <vector>

#include "core/render/split_table.h"
#include "core/util/vec3.h"

namespace tessera {
namespace {

// The boundary points of entry (s0, s1, s2) in counter-clockwise order,
// written out from the slot naming of split_table.h.
std::vector<int> boundaryOf(const int s[3]) {
  std::vector<int> out;
  for (int k = 0; k < 3; ++k) {
    out.push_back(k);
    if (s[k] == 1) out.push_back(3 + 3 * k + 1);
    if (s[k] == 2)
      for (int q = 0; q < 3; ++q) out.push_back(3 + 3 * k + q);
  }
  return out;
}

// A slot on a scalene triangle in space, by its barycentric coordinates.
Vec3 placeOn(int slot, const Vec3 corners[3]) {
  if (slot < 3) return corners[slot];
  const int edge = (slot - 3) / 3;
  const double t = ((slot - 3) % 3 + 1) / 4.0;
  return (1 - t) * corners[edge] + t * corners[(edge + 1) % 3];
}

TEST(SplitTable, EveryEntryIsAValidOrientedTriangulation) {
  const Vec3 corners[3] = {Vec3(0.3, -0.2, 0.1), Vec3(2.1, 0.4, -0.3), Vec3(0.7, 1.6, 0.9)};
  const Vec3 normal = (corners[1] - corners[0]) % (corners[2] - corners[0]);
  const int newPoints[3] = {0, 1, 3};  // an edge split once gains 1 point, twice 3 (into four parts)
  int seen = 0;
  for (int s2 = 0; s2 < 3; ++s2) {
    for (int s1 = 0; s1 < 3; ++s1) {
      for (int s0 = 0; s0 < 3; ++s0) {
        const int s[3] = {s0, s1, s2};
        const std::string where = "entry " + std::to_string(s0) + std::to_string(s1) + std::to_string(s2);
        const SplitPattern& p = splitPattern(s0 + 3 * s1 + 9 * s2);
        ++seen;
        EXPECT_EQ(p.count, 1 + newPoints[s0] + newPoints[s1] + newPoints[s2]) << where;
        const std::vector<int> boundary = boundaryOf(s);
        const std::set<int> allowed(boundary.begin(), boundary.end());
        std::map<std::pair<int, int>, int> directed;
        std::set<int> used;
        double area = 0;
        for (int i = 0; i < p.count; ++i) {
          const auto& t = p.triangles[i];
          for (int k = 0; k < 3; ++k) {
            ASSERT_TRUE(allowed.count(t[k]))
                << where << ": slot " << int(t[k]) << " is not a point of this entry";
            used.insert(t[k]);
            ++directed[{t[k], t[(k + 1) % 3]}];
          }
          const auto a = slotPosition(t[0]), b = slotPosition(t[1]), c = slotPosition(t[2]);
          const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
          EXPECT_GT(twice, 1e-3) << where << ": triangle " << i << " is clockwise or degenerate";
          area += twice / 2;
          const Vec3 n = (placeOn(t[1], corners) - placeOn(t[0], corners)) %
                         (placeOn(t[2], corners) - placeOn(t[0], corners));
          EXPECT_GT(n | normal, 1e-3 * normal.sqrnorm())
              << where << ": triangle " << i << " flips or has no area in 3D";
        }
        EXPECT_EQ(used, allowed) << where << ": every point is used";
        EXPECT_NEAR(area, 0.4330127018922193, 1e-12) << where << ": the triangles cover the triangle once";
        // Boundary segments once, counter-clockwise; inner edges once each way.
        for (size_t i = 0; i < boundary.size(); ++i) {
          const int a = boundary[i], b = boundary[(i + 1) % boundary.size()];
          EXPECT_EQ(directed[std::make_pair(a, b)], 1) << where << ": boundary " << a << "->" << b;
          EXPECT_EQ(directed[std::make_pair(b, a)], 0)
              << where << ": boundary " << b << "->" << a << " reversed";
          directed.erase({a, b});
          directed.erase({b, a});
        }
        for (const auto& [e, n] : directed) {
          if (n == 0) continue;
          EXPECT_EQ(n, 1) << where << ": inner edge " << e.first << "->" << e.second;
          EXPECT_EQ(directed.count({e.second, e.first}) ? directed.at({e.second, e.first}) : 0, 1)
              << where << ": inner edge " << e.first << "->" << e.second << " has no twin";
        }
      }
    }
  }
  EXPECT_EQ(seen, kSplitTableSize);
}

// Every edge split once: the four triangles of a Loop step, the middle one
// on the three midpoints (slots 4, 7 and 10).
TEST(SplitTable, EveryEdgeSplitOnceIsALoopStep) {
  const SplitPattern& p = splitPattern(1 + 3 + 9);
  ASSERT_EQ(p.count, 4);
  bool middle = false;
  for (int i = 0; i < p.count; ++i) {
    const auto& t = p.triangles[i];
    for (int r = 0; r < 3; ++r) middle = middle || (t[r] == 4 && t[(r + 1) % 3] == 7 && t[(r + 2) % 3] == 10);
  }
  EXPECT_TRUE(middle);
}

}  // namespace
}  // namespace tessera
