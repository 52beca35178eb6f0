#include "core/tessellation/region_lattice.h"

#include <tuple>

#include "core/hierarchy/incidence.h"
#include "core/hierarchy/sparse_hierarchy.h"

namespace tessera {

void writeFrame(ByteWriter& w, const RegionFrame& frame) {
  const FaceId face = FaceId::fromPacked(frame.face);
  w.put<uint8_t>(static_cast<uint8_t>(face.level()));
  w.putVarint(face.index());
  for (uint64_t c : frame.corners) w.putVarint(c);
  for (uint64_t e : frame.edges) w.putVarint(e);
  w.put<uint8_t>(frame.forward);
  for (uint64_t n : frame.baseCounts) w.putVarint(n);
}

Expected<RegionFrame> readFrame(ByteReader& r) {
  RegionFrame frame;
  uint8_t level = 0;
  uint64_t index = 0;
  TESSERA_RETURN_IF_ERROR(r.get(level, "the frame's face level"));
  TESSERA_RETURN_IF_ERROR(r.getVarint(index, 64, "the frame's face"));
  if (level > kMaxIdLevel || index > FaceId::kIndexMask) {
    return parseError(r.source() + ": the frame's face f" + std::to_string(level) + ":" +
                      std::to_string(index) + " is not a face id");
  }
  frame.face = FaceId(level, index).packed();
  for (uint64_t& c : frame.corners) TESSERA_RETURN_IF_ERROR(r.getVarint(c, 64, "the frame's corners"));
  for (uint64_t& e : frame.edges) TESSERA_RETURN_IF_ERROR(r.getVarint(e, 64, "the frame's edges"));
  TESSERA_RETURN_IF_ERROR(r.get(frame.forward, "the frame's edge directions"));
  for (uint64_t& n : frame.baseCounts) TESSERA_RETURN_IF_ERROR(r.getVarint(n, 64, "the frame's base counts"));
  return frame;
}

Expected<RegionFrame> regionFrame(const SparseHierarchy& h, const LevelCounts& counts, FaceId region) {
  // The lattice is the triangle's (Loop's 1-to-4 split); a quad face's
  // region carries its ids as labels (docs/REGION_ENCODING.md "Lattice ids").
  if (counts.quads())
    return unsupported("region " + region.toString() + ": lattice ids are defined for triangle faces only");
  const int r = region.level();
  if (r >= h.numLevels())
    return notFound("region " + region.toString() + ": the hierarchy holds no level " + std::to_string(r));
  const SparseLevel& level = h.level(r);
  const Index f = level.findFace(region.index());
  if (f < 0) return notFound("region " + region.toString() + ": the hierarchy does not hold its face");
  RegionFrame frame;
  frame.face = region.packed();
  for (int j = 0; j < 3; ++j) {
    frame.corners[j] = level.vertexIds[level.mesh.triangleVertices(f)[j]];
    frame.edges[j] = level.edgeIds[level.mesh.triangleEdges(f)[j]];
  }
  const Level& base = h.level(0).mesh;
  for (int j = 0; j < 3; ++j) {
    // The canonical direction, from the ids alone (not the sparse level's
    // local orientation).
    const auto ends = edgeEnds(base, counts, EdgeId(r, frame.edges[j]));
    if (ends[0].index() == frame.corners[j] && ends[1].index() == frame.corners[(j + 1) % 3]) {
      frame.forward |= static_cast<uint8_t>(1u << j);
    } else if (ends[1].index() != frame.corners[j] || ends[0].index() != frame.corners[(j + 1) % 3]) {
      return internalError("region " + region.toString() + ": edge " + EdgeId(r, frame.edges[j]).toString() +
                           " does not join corners " + std::to_string(j) + " and " +
                           std::to_string((j + 1) % 3));
    }
  }
  frame.baseCounts = {counts.vertices(0), counts.edges(0), counts.faces(0)};
  return frame;
}

namespace {

// A face of the recursion: its canonical index, corner lattice points and
// vertex indices, and its edges' canonical indices and directions.
struct Node {
  uint64_t face;
  std::array<std::array<int, 2>, 3> at;
  std::array<uint64_t, 3> vertex;
  std::array<uint64_t, 3> edge;
  std::array<bool, 3> forward;  // edge j runs from corner j to corner j+1
};

}  // namespace

Expected<RegionLattice> RegionLattice::build(const RegionFrame& frame, int depth) {
  const FaceId root = FaceId::fromPacked(frame.face);
  if (depth < 0 || depth > kMaxLatticeDepth || root.level() + depth > kMaxIdLevel) {
    return invalidArgument("region lattice of " + root.toString() + ": depth " + std::to_string(depth) +
                           " outside [0, " + std::to_string(kMaxLatticeDepth) + "]");
  }
  const int deepest = root.level() + depth;
  // Ids beyond 58 bits would wrap (a frame may come off the wire): the
  // counts are checked level by level before LevelCounts computes them.
  // Below 2^58 a level's counts cannot wrap 64 bits on the way to the next.
  uint64_t v = frame.baseCounts[0], e = frame.baseCounts[1], f = frame.baseCounts[2];
  for (int l = 0;; ++l) {
    if (v > VertexId::kIndexMask || e > EdgeId::kIndexMask || f > FaceId::kIndexMask) {
      return invalidArgument("region lattice of " + root.toString() +
                             ": the base counts overflow the ids at level " + std::to_string(l));
    }
    if (l == deepest) break;
    std::tie(v, e, f) = std::make_tuple(v + e, 2 * e + 3 * f, 4 * f);
  }
  const LevelCounts counts(frame.baseCounts[0], frame.baseCounts[1], frame.baseCounts[2], deepest);
  for (int j = 0; j < 3; ++j) {
    if (frame.corners[j] >= counts.vertices(root.level()) || frame.edges[j] >= counts.edges(root.level())) {
      return invalidArgument("region lattice of " + root.toString() + ": corner or edge " +
                             std::to_string(j) + " is not an element of level " +
                             std::to_string(root.level()));
    }
  }
  if (root.index() >= counts.faces(root.level())) {
    return invalidArgument("region lattice: face " + root.toString() + " does not exist");
  }

  RegionLattice lattice;
  lattice.depth_ = depth;
  const int n = 1 << depth;
  lattice.ids_.assign(static_cast<size_t>(n + 1) * (n + 1), ~uint64_t{0});
  auto record = [&](std::array<int, 2> p, uint64_t index) {
    uint64_t& slot = lattice.ids_[static_cast<size_t>(p[0]) * (n + 1) + p[1]];
    if (slot != ~uint64_t{0}) return;
    const VertexId id(counts.birthLevel(VertexId(deepest, index)), index);
    slot = id.packed();
    lattice.points_.emplace(id.packed(), p);
  };

  std::vector<Node> nodes{{root.index(),
                           {{{0, 0}, {n, 0}, {0, n}}},
                           frame.corners,
                           frame.edges,
                           {(frame.forward & 1) != 0, (frame.forward & 2) != 0, (frame.forward & 4) != 0}}};
  for (int j = 0; j < 3; ++j) record(nodes[0].at[j], nodes[0].vertex[j]);
  // Level by level (refinement.h): the vertex on edge e is V + e; edge e
  // halves into 2e (from its first end) and 2e+1 (to its second); face f has
  // interior edges 2E + 3f + {0, 1, 2} running m0->m2, m1->m0, m2->m1 and
  // children 4f + {0, 1, 2} at its corners and 4f + 3 in the middle.
  for (int l = root.level(); l < deepest; ++l) {
    const uint64_t V = counts.vertices(l), E = counts.edges(l);
    std::vector<Node> next;
    next.reserve(nodes.size() * 4);
    for (const Node& p : nodes) {
      std::array<std::array<int, 2>, 3> m;
      std::array<uint64_t, 3> mv;
      // half[j][0]: the half of edge j at corner j, half[j][1] at corner j+1,
      // each with whether it runs from the corner to the midpoint.
      std::array<std::array<std::pair<uint64_t, bool>, 2>, 3> half;
      for (int j = 0; j < 3; ++j) {
        const auto& a = p.at[j];
        const auto& b = p.at[(j + 1) % 3];
        m[j] = {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2};
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
                      {p.at[0], m[0], m[2]},
                      {p.vertex[0], mv[0], mv[2]},
                      {half[0][0].first, i0, half[2][1].first},
                      {half[0][0].second, true, !half[2][1].second}});
      // c1 = (m0, v1, m1): half0@v1 (m0->v1), half1@v1 (v1->m1), i1 (m1->m0)
      next.push_back({4 * p.face + 1,
                      {m[0], p.at[1], m[1]},
                      {mv[0], p.vertex[1], mv[1]},
                      {half[0][1].first, half[1][0].first, i1},
                      {!half[0][1].second, half[1][0].second, true}});
      // c2 = (m2, m1, v2): i2 (m2->m1), half1@v2 (m1->v2), half2@v2 (v2->m2)
      next.push_back({4 * p.face + 2,
                      {m[2], m[1], p.at[2]},
                      {mv[2], mv[1], p.vertex[2]},
                      {i2, half[1][1].first, half[2][0].first},
                      {true, !half[1][1].second, half[2][0].second}});
      // c3 = (m1, m2, m0): i2 (m2->m1), i0 (m0->m2), i1 (m1->m0), all backwards
      next.push_back(
          {4 * p.face + 3, {m[1], m[2], m[0]}, {mv[1], mv[2], mv[0]}, {i2, i0, i1}, {false, false, false}});
    }
    nodes = std::move(next);
  }
  return lattice;
}

std::optional<VertexId> RegionLattice::idAt(int u, int v) const {
  const int n = side();
  if (u < 0 || v < 0 || u + v > n) return std::nullopt;
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
