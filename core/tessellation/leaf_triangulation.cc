#include "core/tessellation/leaf_triangulation.h"

#include <algorithm>
#include <array>
#include <vector>

namespace tessera {

namespace {

using Points = std::vector<VertexRef>;

// The vertices strictly inside edge e (level l) from x to y, as the face g
// on its far side refines it: its midpoint where g is split, recursively
// the points of the halves from g's corner children.
void collectEdge(const SparseHierarchy& h, const AdaptiveCut& cut, int l, Index e, Index g, Index x, Index y,
                 Points& out) {
  if (g < 0 || !cut.isSplit(l, g)) return;
  const SparseLevel& level = h.level(l);
  const Index m = level.childOfEdge[e];
  const Index half = level.halvesOfEdge[e];
  const int endX = level.mesh.edgeVertices[e][0] == x ? 0 : 1;
  const Index first = level.firstChildFace[g];
  const Index gx = first + level.mesh.vertexInFace(g, x), gy = first + level.mesh.vertexInFace(g, y);
  collectEdge(h, cut, l + 1, half + endX, gx, level.childOfVertex[x], m, out);
  out.push_back({l + 1, m});
  collectEdge(h, cut, l + 1, half + 1 - endX, gy, m, level.childOfVertex[y], out);
}

// Splits edge points at their midpoint: the coarsest point among them.
struct Split {
  Points before, after;
  VertexRef mid;
};

Split splitAtMidpoint(const Points& points) {
  const auto mid = std::min_element(points.begin(), points.end(),
                                    [](const VertexRef& a, const VertexRef& b) { return a.level < b.level; });
  return {Points(points.begin(), mid), Points(mid + 1, points.end()), *mid};
}

void cover(VertexRef a, VertexRef b, VertexRef c, const Points& ab, const Points& bc, const Points& ca,
           std::vector<RefTriangle>& out) {
  const int withPoints = !ab.empty() + !bc.empty() + !ca.empty();
  if (withPoints == 0) {
    out.push_back({a, b, c});
    return;
  }
  if (withPoints == 1) {
    // One fan from the corner opposite the edge with points.
    if (!bc.empty()) return cover(b, c, a, bc, ca, ab, out);
    if (!ca.empty()) return cover(c, a, b, ca, ab, bc, out);
    VertexRef prev = a;
    for (const VertexRef& p : ab) out.push_back({c, prev, p}), prev = p;
    out.push_back({c, prev, b});
    return;
  }
  if (withPoints == 2) {
    // Rotate so that the edge without points is c-a.
    if (ab.empty()) return cover(b, c, a, bc, ca, ab, out);
    if (bc.empty()) return cover(c, a, b, ca, ab, bc, out);
    const Split s0 = splitAtMidpoint(ab), s1 = splitAtMidpoint(bc);
    cover(a, s0.mid, c, s0.before, {}, {}, out);
    cover(s0.mid, b, s1.mid, s0.after, s1.before, {}, out);
    cover(s0.mid, s1.mid, c, {}, s1.after, {}, out);
    return;
  }
  const Split s0 = splitAtMidpoint(ab), s1 = splitAtMidpoint(bc), s2 = splitAtMidpoint(ca);
  cover(a, s0.mid, s2.mid, s0.before, {}, s2.after, out);
  cover(s0.mid, b, s1.mid, s0.after, s1.before, {}, out);
  cover(s2.mid, s1.mid, c, {}, s1.after, s2.before, out);
  out.push_back({s1.mid, s2.mid, s0.mid});
}

// A quad leaf with the finer points on its sides (side j from corner j to
// corner j + 1). A corner whose two sides hold no points covers the quad
// with one fan over the other sides; otherwise two opposite sides both hold
// points (a corner on no such side would be free), and the quad is split
// at their midpoints into two quads, each with fewer points and a bare
// new side. No triangle has three points on one side of the leaf.
void coverQuad(const std::array<VertexRef, 4>& c, const std::array<Points, 4>& s,
               std::vector<RefTriangle>& out) {
  if (s[0].empty() && s[1].empty() && s[2].empty() && s[3].empty()) {
    // The first diagonal, as the quad split's control polygons are drawn.
    out.push_back({c[0], c[1], c[2]});
    out.push_back({c[0], c[2], c[3]});
    return;
  }
  for (int k = 0; k < 4; ++k) {
    if (!s[k].empty() || !s[(k + 3) % 4].empty()) continue;
    std::vector<VertexRef> chain{c[(k + 1) % 4]};
    for (int step = 1; step <= 2; ++step) {
      const int side = (k + step) % 4;
      chain.insert(chain.end(), s[side].begin(), s[side].end());
      chain.push_back(c[(side + 1) % 4]);
    }
    for (size_t i = 0; i + 1 < chain.size(); ++i) out.push_back({c[k], chain[i], chain[i + 1]});
    return;
  }
  const int j = !s[0].empty() && !s[2].empty() ? 0 : 1;
  const Split near = splitAtMidpoint(s[j]), far = splitAtMidpoint(s[j + 2]);
  coverQuad({c[j], near.mid, far.mid, c[(j + 3) % 4]}, {near.before, Points{}, far.after, s[(j + 3) % 4]},
            out);
  coverQuad({near.mid, c[j + 1], c[j + 2], far.mid}, {near.after, s[j + 1], far.before, Points{}}, out);
}

void triangulateQuadLeaf(const SparseHierarchy& h, const AdaptiveCut& cut, int l, Index f,
                         std::vector<RefTriangle>& out) {
  const Level& m = h.level(l).mesh;
  const auto fv = m.faceVerticesOf(f);
  const auto fe = m.faceEdgesOf(f);
  // A base n-gon is a leaf only where a profile stops at level 0, with no
  // finer neighbour: shown whole.
  if (fv.size() != 4) return triangulateFace(h, l, f, out);
  std::array<VertexRef, 4> corners;
  std::array<Points, 4> sides;
  for (int j = 0; j < 4; ++j) {
    corners[j] = {l, fv[j]};
    const auto& ef = m.edgeFaces[fe[j]];
    const Index far = ef[0] == f ? ef[1] : ef[0];
    collectEdge(h, cut, l, fe[j], far, fv[j], fv[(j + 1) % 4], sides[j]);
  }
  coverQuad(corners, sides, out);
}

}  // namespace

void triangulateFace(const SparseHierarchy& h, int l, Index f, std::vector<RefTriangle>& out) {
  const auto fv = h.level(l).mesh.faceVerticesOf(f);
  // A quad's fan from corner 0 is its first diagonal (coverQuad).
  for (size_t k = 1; k + 1 < fv.size(); ++k) out.push_back({VertexRef{l, fv[0]}, {l, fv[k]}, {l, fv[k + 1]}});
}

void triangulateLeaf(const SparseHierarchy& h, const AdaptiveCut& cut, int l, Index f,
                     std::vector<RefTriangle>& out) {
  const Level& m = h.level(l).mesh;
  if (h.quads()) return triangulateQuadLeaf(h, cut, l, f, out);
  const auto fv = m.triangleVertices(f);
  std::array<Points, 3> edges;
  for (int j = 0; j < 3; ++j) {
    const Index e = m.triangleEdges(f)[j];
    const auto& ef = m.edgeFaces[e];
    const Index far = ef[0] == f ? ef[1] : ef[0];
    collectEdge(h, cut, l, e, far, fv[j], fv[(j + 1) % 3], edges[j]);
  }
  cover({l, fv[0]}, {l, fv[1]}, {l, fv[2]}, edges[0], edges[1], edges[2], out);
}

}  // namespace tessera
