#include "core/tessellation/region_lattice.h"

#include <algorithm>
#include <string>
#include <tuple>

#include "core/hierarchy/incidence.h"
#include "core/hierarchy/sparse_hierarchy.h"

namespace tessera {

void writeFrame(ByteWriter& w, const RegionFrame& frame) {
  const FaceId face = FaceId::fromPacked(frame.face);
  const int n = frame.sides;
  w.put<uint8_t>(static_cast<uint8_t>(face.level()));
  w.putVarint(face.index());
  if (n == 4) w.putVarint(frame.firstChild);
  for (int j = 0; j < n; ++j) w.putVarint(frame.corners[j]);
  for (int j = 0; j < n; ++j) w.putVarint(frame.edges[j]);
  w.put<uint8_t>(frame.forward);
  for (int j = 0; j < (n == 4 ? 4 : 3); ++j) w.putVarint(frame.baseCounts[j]);
}

Expected<RegionFrame> readFrame(ByteReader& r, int sides) {
  RegionFrame frame;
  frame.sides = sides;
  uint8_t level = 0;
  uint64_t index = 0;
  TESSERA_RETURN_IF_ERROR(r.get(level, "the frame's face level"));
  TESSERA_RETURN_IF_ERROR(r.getVarint(index, 64, "the frame's face"));
  const std::string face = "f" + std::to_string(level) + ":" + std::to_string(index);
  if (level > kMaxIdLevel || index > FaceId::kIndexMask)
    return parseError(r.source() + ": the frame's face " + face + " is not a face id");
  frame.face = FaceId(level, index).packed();
  if (sides == 4) {
    TESSERA_RETURN_IF_ERROR(r.getVarint(frame.firstChild, 64, "the frame's first child"));
    if (level > 0 && frame.firstChild != 4 * index) {
      return parseError(r.source() + ": the frame's first child " + std::to_string(frame.firstChild) +
                        " is not 4 x the index of quad " + face);
    }
  }
  for (int j = 0; j < sides; ++j)
    TESSERA_RETURN_IF_ERROR(r.getVarint(frame.corners[j], 64, "the frame's corners"));
  for (int j = 0; j < sides; ++j)
    TESSERA_RETURN_IF_ERROR(r.getVarint(frame.edges[j], 64, "the frame's edges"));
  TESSERA_RETURN_IF_ERROR(r.get(frame.forward, "the frame's edge directions"));
  if (frame.forward >> sides != 0) {
    return parseError(r.source() + ": the frame's edge directions " + std::to_string(frame.forward) +
                      " name more than " + std::to_string(sides) + " edges");
  }
  for (int j = 0; j < (sides == 4 ? 4 : 3); ++j)
    TESSERA_RETURN_IF_ERROR(r.getVarint(frame.baseCounts[j], 64, "the frame's base counts"));
  return frame;
}

Expected<RegionFrame> regionFrame(const SparseHierarchy& h, const LevelCounts& counts, FaceId region) {
  const int r = region.level();
  if (r >= h.numLevels())
    return notFound("region " + region.toString() + ": the hierarchy holds no level " + std::to_string(r));
  RegionFrame frame;
  frame.face = region.packed();
  frame.sides = counts.quads() ? 4 : 3;
  // A base n-gon's children are numbered by corner, n of them: no square
  // lattice; its region carries its ids as labels (docs/PROTOCOL.md 6.2).
  if (counts.quads() && counts.faceSize(region) != 4) {
    return unsupported("region " + region.toString() + ": a face of " +
                       std::to_string(counts.faceSize(region)) + " corners has no lattice");
  }
  const SparseLevel& level = h.level(r);
  const Index f = level.findFace(region.index());
  if (f < 0) return notFound("region " + region.toString() + ": the hierarchy does not hold its face");
  const auto vertices = level.mesh.faceVerticesOf(f);
  const auto edges = level.mesh.faceEdgesOf(f);
  const int n = frame.sides;
  for (int j = 0; j < n; ++j) {
    frame.corners[j] = level.vertexIds[vertices[j]];
    frame.edges[j] = level.edgeIds[edges[j]];
  }
  const Level& base = h.level(0).mesh;
  for (int j = 0; j < n; ++j) {
    // The canonical direction, from the ids alone (not the sparse level's
    // local orientation).
    const auto ends = edgeEnds(base, counts, EdgeId(r, frame.edges[j]));
    const uint64_t from = frame.corners[j], to = frame.corners[(j + 1) % n];
    if (ends[0].index() == from && ends[1].index() == to) {
      frame.forward |= static_cast<uint8_t>(1u << j);
    } else if (ends[1].index() != from || ends[0].index() != to) {
      return internalError("region " + region.toString() + ": edge " + EdgeId(r, frame.edges[j]).toString() +
                           " does not join corners " + std::to_string(j) + " and " +
                           std::to_string((j + 1) % n));
    }
  }
  frame.baseCounts = {counts.vertices(0), counts.edges(0), counts.faces(0),
                      counts.quads() ? counts.corners(0) : 0};
  if (counts.quads()) frame.firstChild = counts.firstChildFace(region);
  return frame;
}

namespace {

using Point = std::array<int, 2>;

// A face of the recursion: its canonical index, corner lattice points and
// vertex indices, and its edges' canonical indices and directions (the
// first three of each for a triangle).
struct Node {
  uint64_t face;
  uint64_t firstChild;  // quads
  std::array<Point, 4> at;
  std::array<uint64_t, 4> vertex;
  std::array<uint64_t, 4> edge;
  std::array<bool, 4> forward;  // edge j runs from corner j to corner j+1
};

Point mid(const Point& a, const Point& b) {
  return {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2};
}

// Per-level counts of the frame's base, checked for ids that would wrap
// (a frame may come off the wire) before they are computed: below 2^58 a
// level's counts cannot wrap 64 bits on the way to the next.
struct Counts {
  std::vector<uint64_t> v, e, f, c;  // c: corners, quads only
};

Expected<Counts> countsOf(const RegionFrame& frame, int deepest, const std::string& where) {
  Counts counts;
  uint64_t v = frame.baseCounts[0], e = frame.baseCounts[1], f = frame.baseCounts[2], c = frame.baseCounts[3];
  for (int l = 0;; ++l) {
    if (v > VertexId::kIndexMask || e > EdgeId::kIndexMask || f > FaceId::kIndexMask ||
        c > EdgeId::kIndexMask) {
      return invalidArgument(where + ": the base counts overflow the ids at level " + std::to_string(l));
    }
    counts.v.push_back(v), counts.e.push_back(e), counts.f.push_back(f), counts.c.push_back(c);
    if (l == deepest) break;
    // Loop's split (refinement.h) or the quad split (quad_split.h).
    if (frame.sides == 3) {
      std::tie(v, e, f) = std::make_tuple(v + e, 2 * e + 3 * f, 4 * f);
    } else {
      std::tie(v, e, f, c) = std::make_tuple(v + f + e, c + 2 * e, c, 4 * c);
    }
  }
  return counts;
}

// Loop's children (refinement.h): the vertex on edge e is V + e; edge e
// halves into 2e (from its first end) and 2e+1 (to its second); face f has
// interior edges 2E + 3f + {0, 1, 2} running m0->m2, m1->m0, m2->m1 and
// children 4f + {0, 1, 2} at its corners and 4f + 3 in the middle.
template <typename Record>
void splitTriangle(const Node& p, uint64_t V, uint64_t E, const Record& record, std::vector<Node>& next) {
  std::array<Point, 3> m;
  std::array<uint64_t, 3> mv;
  // half[j][0]: the half of edge j at corner j, half[j][1] at corner j+1,
  // each with whether it runs from the corner to the midpoint.
  std::array<std::array<std::pair<uint64_t, bool>, 2>, 3> half;
  for (int j = 0; j < 3; ++j) {
    m[j] = mid(p.at[j], p.at[(j + 1) % 3]);
    mv[j] = V + p.edge[j];
    record(m[j], mv[j]);
    if (p.forward[j]) {
      half[j][0] = {2 * p.edge[j], true};       // (corner j, m)
      half[j][1] = {2 * p.edge[j] + 1, false};  // (m, corner j+1)
    } else {
      half[j][0] = {2 * p.edge[j] + 1, false};  // (m, corner j)
      half[j][1] = {2 * p.edge[j], true};       // (corner j+1, m)
    }
  }
  const uint64_t i0 = 2 * E + 3 * p.face, i1 = i0 + 1, i2 = i0 + 2;
  // Child edge k joins child corners k and k+1; `forward` says whether
  // the edge runs that way. A half running corner->m joins (corner, m).
  // c0 = (v0, m0, m2): half0@0 (v0->m0), i0 (m0->m2), half2@v0 (m2->v0)
  next.push_back({4 * p.face,
                  0,
                  {p.at[0], m[0], m[2]},
                  {p.vertex[0], mv[0], mv[2]},
                  {half[0][0].first, i0, half[2][1].first},
                  {half[0][0].second, true, !half[2][1].second}});
  // c1 = (m0, v1, m1): half0@v1 (m0->v1), half1@v1 (v1->m1), i1 (m1->m0)
  next.push_back({4 * p.face + 1,
                  0,
                  {m[0], p.at[1], m[1]},
                  {mv[0], p.vertex[1], mv[1]},
                  {half[0][1].first, half[1][0].first, i1},
                  {!half[0][1].second, half[1][0].second, true}});
  // c2 = (m2, m1, v2): i2 (m2->m1), half1@v2 (m1->v2), half2@v2 (v2->m2)
  next.push_back({4 * p.face + 2,
                  0,
                  {m[2], m[1], p.at[2]},
                  {mv[2], mv[1], p.vertex[2]},
                  {i2, half[1][1].first, half[2][0].first},
                  {true, !half[1][1].second, half[2][0].second}});
  // c3 = (m1, m2, m0): i2 (m2->m1), i0 (m0->m2), i1 (m1->m0), all backwards
  next.push_back(
      {4 * p.face + 3, 0, {m[1], m[2], m[0]}, {mv[1], mv[2], mv[0]}, {i2, i0, i1}, {false, false, false}});
}

// The quad split (quad_split.h, docs/ARCHITECTURE.md "The quad split"): the
// face vertex is V + f, the vertex on edge e is V + F + e; child j is
// firstChild + j at corner j, which keeps position j; interior edge
// firstChild + j runs from the face vertex to the vertex on edge j; half
// C + 2e + end runs from e's vertex to the child of e's end `end`.
template <typename Record>
void splitQuad(const Node& p, uint64_t V, uint64_t F, uint64_t C, const Record& record,
               std::vector<Node>& next) {
  const Point centre = mid(p.at[0], p.at[2]);
  const uint64_t cv = V + p.face;
  record(centre, cv);
  std::array<Point, 4> m;
  std::array<uint64_t, 4> mv;
  for (int j = 0; j < 4; ++j) {
    m[j] = mid(p.at[j], p.at[(j + 1) & 3]);
    mv[j] = V + F + p.edge[j];
    record(m[j], mv[j]);
  }
  for (int j = 0; j < 4; ++j) {
    const int prev = (j + 3) & 3;
    Node child{p.firstChild + j, 4 * (p.firstChild + j), {}, {}, {}, {}};
    // Position j + k holds the kind-k corner and the kind-k edge, which joins
    // it to the corner at position j + k + 1.
    const std::array<Point, 4> at{p.at[j], m[j], centre, m[prev]};
    const std::array<uint64_t, 4> vertex{p.vertex[j], mv[j], cv, mv[prev]};
    const std::array<uint64_t, 4> edge{C + 2 * p.edge[j] + (p.forward[j] ? 0 : 1), p.firstChild + j,
                                       p.firstChild + prev, C + 2 * p.edge[prev] + (p.forward[prev] ? 1 : 0)};
    const std::array<bool, 4> forward{false, false, true, true};
    for (int k = 0; k < 4; ++k) {
      const int position = (j + k) & 3;
      child.at[position] = at[k];
      child.vertex[position] = vertex[k];
      child.edge[position] = edge[k];
      child.forward[position] = forward[k];
    }
    next.push_back(child);
  }
}

}  // namespace

Expected<RegionLattice> RegionLattice::build(const RegionFrame& frame, int depth) {
  const FaceId root = FaceId::fromPacked(frame.face);
  const std::string where = "region lattice of " + root.toString();
  if (frame.sides != 3 && frame.sides != 4)
    return invalidArgument(where + ": a face of " + std::to_string(frame.sides) + " sides has no lattice");
  if (depth < 0 || depth > kMaxLatticeDepth || root.level() + depth > kMaxIdLevel) {
    return invalidArgument(where + ": depth " + std::to_string(depth) + " outside [0, " +
                           std::to_string(kMaxLatticeDepth) + "]");
  }
  const int deepest = root.level() + depth;
  TESSERA_ASSIGN_OR_RETURN(const Counts counts, countsOf(frame, deepest, where));
  const int r = root.level();
  const int sides = frame.sides;
  for (int j = 0; j < sides; ++j) {
    if (frame.corners[j] >= counts.v[r] || frame.edges[j] >= counts.e[r]) {
      return invalidArgument(where + ": corner or edge " + std::to_string(j) +
                             " is not an element of level " + std::to_string(r));
    }
  }
  if (root.index() >= counts.f[r])
    return invalidArgument("region lattice: face " + root.toString() + " does not exist");
  if (sides == 4 && (r > 0 ? frame.firstChild != 4 * root.index() : frame.firstChild + 4 > counts.c[0])) {
    return invalidArgument(where + ": first child " + std::to_string(frame.firstChild) +
                           " is not the quad's");
  }

  RegionLattice lattice;
  lattice.depth_ = depth;
  lattice.sides_ = sides;
  const int n = 1 << depth;
  lattice.ids_.assign(static_cast<size_t>(n + 1) * (n + 1), ~uint64_t{0});
  const auto record = [&](const Point& p, uint64_t index) {
    uint64_t& slot = lattice.ids_[static_cast<size_t>(p[0]) * (n + 1) + p[1]];
    if (slot != ~uint64_t{0}) return;
    const int birth =
        static_cast<int>(std::upper_bound(counts.v.begin(), counts.v.end(), index) - counts.v.begin());
    const VertexId id(birth, index);
    slot = id.packed();
    lattice.points_.emplace(id.packed(), p);
  };

  Node top{root.index(), frame.firstChild, {}, frame.corners, frame.edges, {}};
  top.at = sides == 3 ? std::array<Point, 4>{Point{0, 0}, Point{n, 0}, Point{0, n}, Point{}}
                      : std::array<Point, 4>{Point{0, 0}, Point{n, 0}, Point{n, n}, Point{0, n}};
  for (int j = 0; j < sides; ++j) {
    top.forward[j] = (frame.forward >> j & 1) != 0;
    record(top.at[j], top.vertex[j]);
  }
  std::vector<Node> nodes{top};
  for (int l = r; l < deepest; ++l) {
    std::vector<Node> next;
    next.reserve(nodes.size() * 4);
    for (const Node& p : nodes) {
      if (sides == 3) {
        splitTriangle(p, counts.v[l], counts.e[l], record, next);
      } else {
        splitQuad(p, counts.v[l], counts.f[l], counts.c[l], record, next);
      }
    }
    nodes = std::move(next);
  }
  return lattice;
}

std::optional<VertexId> RegionLattice::idAt(int u, int v) const {
  const int n = side();
  if (u < 0 || v < 0 || u > n || v > n || (sides_ == 3 && u + v > n)) return std::nullopt;
  const uint64_t packed = ids_[static_cast<size_t>(u) * (n + 1) + v];
  if (packed == ~uint64_t{0}) return std::nullopt;
  return VertexId::fromPacked(packed);
}

std::optional<std::array<int, 2>> RegionLattice::pointOf(VertexId id) const {
  auto it = points_.find(id.packed());
  if (it == points_.end()) return std::nullopt;
  return it->second;
}

}  // namespace tessera
