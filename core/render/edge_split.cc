#include "core/render/edge_split.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <utility>

namespace tessera {

namespace {

// Below this squared sine the two sides' normals are taken as one (a crease
// flatter than about one degree): their cross product has no direction.
constexpr double kParallelSine2 = 3e-4;

bool sideLess(const EdgeSide& a, const EdgeSide& b) {
  if (!bitsEqual(a.n0, b.n0)) return bitsLess(a.n0, b.n0);
  return bitsLess(a.n1, b.n1);
}

// The curve's tangent at one end, scaled to the chord e (Kähler, Haber &
// Seidel, "Dynamic Refinement of Deformable Triangle Meshes for Rendering"
// §4.2 adapted, see splitEdge). One normal: the chord projected into the tangent plane.
// Two normals (a crease): the crease runs along both sectors' tangent
// planes, so along their intersection a x b; the chord projected onto it.
Vec3 endTangent(const Vec3& e, const Vec3& a, const Vec3& b) {
  if (!bitsEqual(a, b)) {
    const Vec3 c = a % b;
    const double len2 = c.sqrnorm();
    if (len2 >= kParallelSine2) {
      const Vec3 t = c / std::sqrt(len2);
      return (e | t) * t;
    }
    const Vec3 n = (a + b).normalized();
    return e - (e | n) * n;
  }
  return e - (e | a) * a;
}

// The paper's §4.4: a new point's normal is interpolated along the edge from its
// neighbours there (original vertices or earlier split points), normalised.
Vec3 between(const Vec3& a, const Vec3& b) {
  const Vec3 s = a + b;
  const double n = s.norm();
  return n > 1e-12 ? s / n : a;
}

std::array<Vec3, 3> interpolatedNormals(const EdgeSide& s) {
  const Vec3 mid = between(s.n0, s.n1);
  return {between(s.n0, mid), mid, between(mid, s.n1)};
}

}  // namespace

bool bitsLess(const Vec3& a, const Vec3& b) {
  for (int k = 0; k < 3; ++k) {
    const auto x = std::bit_cast<uint64_t>(a[k]), y = std::bit_cast<uint64_t>(b[k]);
    if (x != y) return x < y;
  }
  return false;
}

bool bitsEqual(const Vec3& a, const Vec3& b) {
  return !bitsLess(a, b) && !bitsLess(b, a);
}

// The paper's §4.2 computes a first-level point with Loop's edge mask, 3/8 of each
// end plus 1/8 of each opposite vertex, and a second-level point with the
// same mask on the half edge, reading the first-level points of the other
// edges (or their midpoints). Across a region border each side holds only
// its own opposite vertex, so that mask would put the point in two places
// and open a crack. The mask is the chord midpoint moved by a curvature
// term, (c + d)/8 - (a + b)/8; here the curvature comes from what both
// sides hold instead, the limit normals at the ends: the cubic through the
// ends whose tangents are the chord projected into each end's tangent plane
// (the paper's §4.4 "new degrees of freedom", placed as Vlachos' PN triangles
// place their edge control points). Its midpoint is the chord midpoint plus
// (T0 - T1) / 8, a Loop-like correction that is exact to second order on a
// circle. The second-level points are the same rule on the half curves,
// that is the cubic at 1/4 and 3/4. The original vertices are not moved
// (the paper smooths them for the first level only): here they are limit
// points already, and their rings straddle regions.
EdgeSplit splitEdge(const Vec3& p0In, const Vec3& p1In, const EdgeSide& sideIn,
                    const std::optional<EdgeSide>& otherIn, const SplitCriterion& criterion) {
  // Canonical order: ends by position bits, then sides by normal bits.
  const bool flip = bitsLess(p1In, p0In);
  Vec3 p0 = p0In, p1 = p1In;
  EdgeSide a = sideIn, b = otherIn.value_or(sideIn);
  if (flip) {
    std::swap(p0, p1);
    std::swap(a.n0, a.n1);
    std::swap(b.n0, b.n1);
  }
  const bool swapSides = sideLess(b, a);
  if (swapSides) std::swap(a, b);

  EdgeSplit out;
  // The paper's §4.1 on both sides; the smaller dot product decides for both.
  const double dotProduct = std::min(a.n0 | a.n1, b.n0 | b.n1);
  out.splits = dotProduct < criterion.splitTwiceBelow ? 2 : dotProduct < criterion.splitOnceBelow ? 1 : 0;
  out.splits = std::clamp(out.splits, 0, std::max(criterion.maxSplits, 0));
  if (out.splits == 0) return out;  // no points needed (most edges of a fine LOD)

  const Vec3 e = p1 - p0;
  const Vec3 t0 = endTangent(e, a.n0, b.n0), t1 = endTangent(e, a.n1, b.n1);
  // Cubic Hermite weights at u = 1/4, 1/2, 3/4 for (p0, t0, p1, t1).
  out.points[0] = (27.0 / 32.0) * p0 + (5.0 / 32.0) * p1 + (9.0 / 64.0) * t0 - (3.0 / 64.0) * t1;
  out.points[1] = 0.5 * (p0 + p1) + 0.125 * (t0 - t1);
  out.points[2] = (5.0 / 32.0) * p0 + (27.0 / 32.0) * p1 + (3.0 / 64.0) * t0 - (9.0 / 64.0) * t1;
  out.normals = interpolatedNormals(a);
  out.otherNormals = interpolatedNormals(b);

  if (swapSides) std::swap(out.normals, out.otherNormals);
  if (flip) {
    std::swap(out.points[0], out.points[2]);
    std::swap(out.normals[0], out.normals[2]);
    std::swap(out.otherNormals[0], out.otherNormals[2]);
  }
  return out;
}

}  // namespace tessera
