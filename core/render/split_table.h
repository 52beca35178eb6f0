// The split table of dynamic refinement (Kähler, Haber & Seidel, "Dynamic
// Refinement of Deformable Triangle Meshes for Rendering" §4.3, Figures 5
// and 6):
// one triangulation of a triangle for each of the 27 ways its three edges
// can be split 0, 1 or 2 times, indexed s0 + 3 s1 + 9 s2.
//
// An edge split once gains its midpoint; split twice ("into four parts",
// the paper's §4) it gains the points at 1/4, 1/2 and 3/4. No point is added inside
// the triangle (§4), so an entry triangulates the polygon of the corners
// and the split points: 3 + n points, n + 1 triangles, at most ten.
//
// Points are named by slot, the paper's Figure 6 numbering made fixed-size so
// that every entry uses the same names:
//   0, 1, 2            the corners;
//   3 + 3k + (q - 1)   the point q/4 of the way along edge k (q = 1, 2, 3),
//                      edge k running from corner k to corner (k + 1) % 3.
// Every triangle of an entry is counter-clockwise like the input triangle,
// so refinement keeps the orientation.
#pragma once

#include <array>
#include <cstdint>

namespace tessera {

inline constexpr int kSplitTableSize = 27;
inline constexpr int kMaxSplitTriangles = 10;
inline constexpr int kSplitSlots = 12;

struct SplitPattern {
  int count = 0;  // triangles used
  std::array<std::array<uint8_t, 3>, kMaxSplitTriangles> triangles{};
};

constexpr int splitTableIndex(int s0, int s1, int s2) {
  return s0 + 3 * s1 + 9 * s2;
}
constexpr int cornerSlot(int corner) {
  return corner;
}
constexpr int edgeSlot(int edge, int quarter) {
  return 3 + 3 * edge + (quarter - 1);
}
// Points an edge gains when split `splits` times: 0, 1 or 3.
constexpr int pointsForSplits(int splits) {
  return splits == 0 ? 0 : splits == 1 ? 1 : 3;
}

// The entry for index splitTableIndex(s0, s1, s2), 0 <= index < 27.
const SplitPattern& splitPattern(int index);

// Where slot `slot` lies on the reference triangle the table was built on
// (corners (0, 0), (1, 0), (1/2, sqrt(3)/2)): for checks of the table.
std::array<double, 2> slotPosition(int slot);

}  // namespace tessera
