#include "core/tessellation/displayed_vertices.h"

#include <unordered_map>

#include "core/catmark/dart_masks.h"
#include "core/catmark/limit.h"
#include "core/hierarchy/incidence.h"
#include "core/loop/limit.h"

namespace tessera {

namespace {

// Whether the limit mask of a complete vertex at this level may differ
// from its true limit: a semi-sharp edge or vertex sharpness still acts on
// it (its own sharpness or one of its edges' is finite and not yet decayed:
// the mask counts it as sharp, ARCHITECTURE "Semi-sharp limits"), or it is
// a Loop dart, whose mask is the smooth one (core/loop/limit.cc, as
// OpenSubdiv's) although its sharp edge refines by the crease rule: a
// dart's mask only converges towards its limit level by level. A
// Catmull-Clark dart's masks are its own ring's (core/catmark/dart_masks.h),
// exact up to kMaxExactDartValence.
bool maskInexact(const Level& m, Index v, bool quads) {
  if (m.vertexRules[v] == VertexRule::kDart && !(quads && catmark::hasExactDartMasks(m.valence(v))))
    return true;
  if (isSemiSharp(m.vertexSharpness[v])) return true;
  for (Index e : m.ringEdgesOf(v)) {
    if (isSemiSharp(m.edgeSharpness[e])) return true;
  }
  return false;
}

// Where a displayed vertex's limit comes from, a function of the document
// alone (the rule and its reasons are in tessellation.h): from the level
// the vertex was born at, down to the deepest level whose active edits
// reach its limit, then further while its limit mask is inexact (semi-sharp
// features, Loop's darts), up to the document's deepest level. Vertex children keep
// their canonical index, so whichever leaf reaches the vertex (any `v` of
// it) gives the same answer, and regions sharing a border agree bit for
// bit. When the hierarchy does not hold the vertex's ring at the chosen
// level, a face to grow it there is appended to `growth` and nothing is
// returned.
}  // namespace

std::optional<VertexRef> limitSource(const SparseHierarchy& h, const LevelCounts& counts, VertexRef v,
                                     std::vector<FaceId>& growth) {
  while (v.level > 0 && h.level(v.level).isVertexChild(v.local)) {
    v = {v.level - 1, h.level(v.level).origin[v.local]};
  }
  // A Catmull-Clark base of other polygons than quads has no limits
  // (level_limits.h): its vertices take theirs from level 1 at the earliest.
  const int earliest = h.hasLimits(v.level) ? v.level : v.level + 1;
  VertexRef at = v;
  for (VertexRef w = v;;) {
    if (w.level <= earliest || h.isReachedByEdit(w.level, w.local)) at = w;
    if (w.level + 1 >= h.numLevels()) break;
    const Index child = h.level(w.level).childOfVertex[w.local];
    if (child < 0) break;
    w = {w.level + 1, child};
  }
  auto held = [&](int l, Index local) { return local >= 0 && h.level(l).isComplete(local); };
  auto grow = [&](int l, uint64_t canonical) {
    growth.push_back(incidentFace(h.level(0).mesh, counts, VertexId(l, canonical)));
    return std::nullopt;
  };
  if (at.level < earliest) return grow(earliest, h.level(at.level).vertexIds[at.local]);
  if (!held(at.level, at.local)) return grow(at.level, h.level(at.level).vertexIds[at.local]);
  while (at.level < counts.maxLevel() && maskInexact(h.level(at.level).mesh, at.local, h.quads())) {
    const Index child = at.level + 1 < h.numLevels() ? h.level(at.level).childOfVertex[at.local] : kNoIndex;
    if (!held(at.level + 1, child)) return grow(at.level + 1, h.level(at.level).vertexIds[at.local]);
    at = {at.level + 1, child};
  }
  return at;
}

namespace {

// The limit normal of side `side` > 0 of a crease or corner vertex
// (limitSideOfRingFace's numbering; side 0's is its limit normal).
Vec3 sideNormal(const SparseHierarchy& h, VertexRef v, int side) {
  const SparseFarRings far = h.farRings(v.level);
  if (h.quads())
    return catmarkOtherLimitSectors(h.level(v.level).mesh, v.local, h.points(v.level), h.options(),
                                    &far)[side - 1]
        .normal;
  return otherLimitSectors(h.level(v.level).mesh, v.local, h.points(v.level), h.creaseMethod(),
                           &far)[side - 1]
      .normal;
}

// The side of a displayed vertex (`at`: its limit's level and index) that
// a triangle inside leaf face f of level l lies on, chosen topologically:
// the sector, at the limit's level, of the ring face that descends from f
// or that f descends from. Those ring faces are one contiguous run of the
// ring (a single face, for a corner of f: its corner child and that one's,
// and so on); a tag set below f's level can put a sharp edge among them,
// so the run's first face (counter-clockwise) decides. Sides then follow
// the leaves around the vertex in ring order, each side's triangles form
// one fan, and every leaf or region that reaches the vertex agrees -- where
// a flat triangle's normal against the sectors' normals need not: at the
// limit's level, deeper than the display, a semi-sharp edge may have
// decayed and merged two displayed sectors into one whose normal is far
// from (even perpendicular to) the faces in it.
// On the quad split the same holds with the split's ancestors, and the
// sides of core/catmark/limit.h.
int sideOf(const SparseHierarchy& h, const LevelCounts& counts, VertexRef at, int l, Index f) {
  const SparseLevel& level = h.level(at.level);
  if (isSmoothLike(level.mesh.vertexRules[at.local])) return 0;
  const uint64_t leaf = h.level(l).faceIds[f];
  auto ring = level.mesh.ringFacesOf(at.local);
  const int n = static_cast<int>(ring.size());
  auto inLeaf = [&](int k) {
    if (ring[k] < 0) return false;
    const uint64_t g = level.faceIds[ring[k]];
    return at.level >= l ? counts.ancestorAt(FaceId(at.level, g), l).index() == leaf
                         : counts.ancestorAt(FaceId(l, leaf), at.level).index() == g;
  };
  int k = 0;
  while (k < n && !inLeaf(k)) ++k;
  if (k == n) return 0;  // not reached: the leaf holds the vertex
  for (int steps = 1; steps < n && inLeaf((k + n - 1) % n); ++steps) k = (k + n - 1) % n;
  if (!h.quads()) return limitSideOfRingFace(level.mesh, at.local, k);
  const SparseFarRings far = h.farRings(at.level);
  return catmarkLimitSideOfRingFace(level.mesh, at.local, k, h.options(), &far);
}

}  // namespace

RegionMesh meshOfTriangles(const SparseHierarchy& h, const LevelCounts& counts,
                           const std::vector<RefTriangle>& triangles, const std::vector<VertexRef>& leaves,
                           std::vector<FaceId>& growth) {
  RegionMesh mesh;
  std::unordered_map<uint64_t, int> index;  // (canonical vertex, side) -> region vertex
  // Each corner's limit source once: a vertex is a corner of about six
  // triangles. Keyed by (level, local index).
  std::unordered_map<uint64_t, std::optional<VertexRef>> sources;
  sources.reserve(triangles.size());
  auto sourceOf = [&](VertexRef v) -> const std::optional<VertexRef>& {
    const uint64_t key = (static_cast<uint64_t>(v.level) << 32) | static_cast<uint32_t>(v.local);
    auto [it, fresh] = sources.try_emplace(key);
    if (fresh) it->second = limitSource(h, counts, v, growth);
    return it->second;
  };
  for (size_t i = 0; i < triangles.size(); ++i) {
    const RefTriangle& t = triangles[i];
    VertexRef at[3];
    bool held = true;
    for (int k = 0; k < 3; ++k) {
      const std::optional<VertexRef>& source = sourceOf(t[k]);
      held = held && source.has_value();
      if (source) at[k] = *source;
    }
    if (!held) continue;  // the caller grows the hierarchy and starts again
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const int side = sideOf(h, counts, at[k], leaves[i].level, leaves[i].local);
      const uint64_t canonical = h.level(at[k].level).vertexIds[at[k].local];
      const uint64_t key = canonical * 64 + static_cast<uint64_t>(side);
      auto [it, fresh] = index.emplace(key, static_cast<int>(mesh.positions.size()));
      if (fresh) {
        const VertexId id(counts.birthLevel(VertexId(at[k].level, canonical)), canonical);
        mesh.positions.push_back(h.limitPosition(at[k].level, at[k].local));
        mesh.normals.push_back(side == 0 ? h.limitNormal(at[k].level, at[k].local)
                                         : sideNormal(h, at[k], side));
        mesh.vertexIds.push_back(id.packed());
      }
      tri[k] = it->second;
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

}  // namespace tessera
