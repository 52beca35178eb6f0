#include "core/render/split_table.h"

namespace tessera {

namespace {

using Point = std::array<double, 2>;

// The reference triangle is equilateral so that the table favours no edge:
// it is a fixed table, the same whatever shape the refined triangle has.
constexpr Point kCorners[3] = {{0.0, 0.0}, {1.0, 0.0}, {0.5, 0.8660254037844386}};

constexpr Point position(int slot) {
  if (slot < 3) return kCorners[slot];
  const int edge = (slot - 3) / 3, quarter = (slot - 3) % 3 + 1;
  const Point a = kCorners[edge], b = kCorners[(edge + 1) % 3];
  const double t = quarter / 4.0;
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
}

constexpr double twiceArea(int a, int b, int c) {
  const Point p = position(a), q = position(b), r = position(c);
  return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
}

constexpr double squaredLength(int a, int b) {
  const Point p = position(a), q = position(b);
  return (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]);
}

struct Polygon {
  std::array<int, kSplitSlots> slots{};
  int size = 0;
};

// The corners and split points in counter-clockwise order round the triangle.
constexpr Polygon boundary(int s0, int s1, int s2) {
  const int splits[3] = {s0, s1, s2};
  Polygon p;
  for (int k = 0; k < 3; ++k) {
    p.slots[p.size++] = cornerSlot(k);
    if (splits[k] == 1) p.slots[p.size++] = edgeSlot(k, 2);
    if (splits[k] == 2)
      for (int q = 1; q <= 3; ++q) p.slots[p.size++] = edgeSlot(k, q);
  }
  return p;
}

constexpr double kNoTriangulation = 1e300;

// Which triangulation of the boundary polygon: the paper (split_table.h)
// leaves it open. No
// point lies inside, so the surface between the edges is spanned by
// diagonals, and a short diagonal strays less from a curved surface than a
// long one; so each entry is the triangulation with the least sum of
// squared edge lengths (on the equilateral reference triangle, so the
// table favours no edge), among those without a zero-area triangle (three
// points of one edge). With every edge split once that is the four
// triangles of a Loop step. Found by the classic dynamic programme over
// the convex polygon's sub-chains: best[i][j] triangulates points i..j.
struct Chains {
  double best[kSplitSlots][kSplitSlots]{};
  int apex[kSplitSlots][kSplitSlots]{};
};

constexpr double triangleCost(int a, int b, int c) {
  if (twiceArea(a, b, c) <= 1e-9) return kNoTriangulation;
  return squaredLength(a, b) + squaredLength(b, c) + squaredLength(c, a);
}

constexpr void collect(const Polygon& poly, const Chains& ch, int i, int j, SplitPattern& out) {
  if (j - i < 2) return;
  const int k = ch.apex[i][j];
  collect(poly, ch, i, k, out);
  out.triangles[out.count++] = {static_cast<uint8_t>(poly.slots[i]), static_cast<uint8_t>(poly.slots[k]),
                                static_cast<uint8_t>(poly.slots[j])};
  collect(poly, ch, k, j, out);
}

constexpr SplitPattern triangulate(int s0, int s1, int s2) {
  const Polygon poly = boundary(s0, s1, s2);
  Chains ch;
  for (int span = 2; span < poly.size; ++span) {
    for (int i = 0; i + span < poly.size; ++i) {
      const int j = i + span;
      ch.best[i][j] = kNoTriangulation;
      for (int k = i + 1; k < j; ++k) {
        const double cost =
            ch.best[i][k] + ch.best[k][j] + triangleCost(poly.slots[i], poly.slots[k], poly.slots[j]);
        if (cost < ch.best[i][j]) ch.best[i][j] = cost, ch.apex[i][j] = k;
      }
    }
  }
  SplitPattern out;
  if (ch.best[0][poly.size - 1] >= kNoTriangulation) return out;  // the static_assert below would fail
  collect(poly, ch, 0, poly.size - 1, out);
  return out;
}

constexpr std::array<SplitPattern, kSplitTableSize> buildTable() {
  std::array<SplitPattern, kSplitTableSize> table{};
  for (int s2 = 0; s2 < 3; ++s2)
    for (int s1 = 0; s1 < 3; ++s1)
      for (int s0 = 0; s0 < 3; ++s0) table[splitTableIndex(s0, s1, s2)] = triangulate(s0, s1, s2);
  return table;
}

// Built by the compiler: the table is data in the binary, as in the paper.
constexpr std::array<SplitPattern, kSplitTableSize> kTable = buildTable();

constexpr bool countsAreRight() {
  for (int i = 0; i < kSplitTableSize; ++i) {
    const int n = pointsForSplits(i % 3) + pointsForSplits(i / 3 % 3) + pointsForSplits(i / 9);
    if (kTable[i].count != n + 1) return false;
  }
  return true;
}
static_assert(countsAreRight(), "every split pattern has n + 1 triangles");
static_assert(kTable[26].count == kMaxSplitTriangles,
              "at most ten sub-triangles (Kähler, Haber & Seidel §4)");

}  // namespace

const SplitPattern& splitPattern(int index) {
  return kTable[index];
}

std::array<double, 2> slotPosition(int slot) {
  return position(slot);
}

}  // namespace tessera
