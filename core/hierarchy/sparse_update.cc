// Incremental update of the sparse hierarchy (Pulli & Lounsbery, "Hierarchical
// Editing and Rendering of Subdivision Surfaces" §4.2, Fig. 7): an
// edit at level l changes the points (or rules) of a few level-l vertices;
// level by level, only the children whose stencils read a changed vertex
// are recomputed, plus offset vertices whose frame reads one of them;
// limits are refreshed where a displayed vertex or a ring neighbour changed.
#include <algorithm>

#include "core/hierarchy/child_stencils.h"
#include "core/hierarchy/face_corners.h"
#include "core/hierarchy/interpolation_conflicts.h"
#include "core/hierarchy/limit_reads.h"
#include "core/hierarchy/sparse_hierarchy.h"
#include "core/loop/interpolate.h"
#include "core/loop/sharpness_inheritance.h"
#include "core/topology/tags.h"

namespace tessera {

namespace {

// Deduplication and membership through per-level marks, which are left all
// zero again: the cost follows the edit's footprint, never the level's size.
class Marked {
 public:
  explicit Marked(std::vector<uint8_t>& marks) : marks_(marks) {}
  ~Marked() {
    for (Index i : items_) marks_[i] = 0;
  }
  void add(Index i) {
    if (!marks_[i]) marks_[i] = 1, items_.push_back(i);
  }
  bool has(Index i) const { return marks_[i] != 0; }
  const std::vector<Index>& items() const { return items_; }
  std::vector<Index> toVector() const { return items_; }

 private:
  std::vector<uint8_t>& marks_;
  std::vector<Index> items_;
};

void sortUnique(std::vector<Index>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// A complete vertex whose ring or self is marked.
bool touches(const Level& m, Index v, const Marked& set) {
  if (set.has(v)) return true;
  for (Index u : m.ringVerticesOf(v)) {
    if (set.has(u)) return true;
  }
  return false;
}

}  // namespace

DirtySet SparseHierarchy::update(const Edit& edit, std::span<const Edit> edits) {
  DirtySet dirty;
  const int l = edit.level();
  std::vector<Index> sources = applyEditAtItsLevel(edit, edits);
  if (std::holds_alternative<MoveEdit>(edit.change))
    dirty.pointsRecomputed += static_cast<int64_t>(sources.size());
  propagate(l, std::move(sources), dirty);
  std::sort(dirty.limits.begin(), dirty.limits.end());
  std::sort(dirty.leaves.begin(), dirty.leaves.end());
  dirty.leaves.erase(std::unique(dirty.leaves.begin(), dirty.leaves.end()), dirty.leaves.end());
  for (FaceId f : dirty.leaves) dirty.baseFaces.push_back(counts_.baseFace(f).index());
  std::sort(dirty.baseFaces.begin(), dirty.baseFaces.end());
  dirty.baseFaces.erase(std::unique(dirty.baseFaces.begin(), dirty.baseFaces.end()), dirty.baseFaces.end());
  return dirty;
}

// Re-resolves the edited elements from the whole edit list (so adding,
// undoing, redoing and removing are one operation) and returns the level-l
// vertices whose point or rule changed.
std::vector<Index> SparseHierarchy::applyEditAtItsLevel(const Edit& edit, std::span<const Edit> edits) {
  const int l = edit.level();
  LevelState& state = levels_[l];
  Level& m = state.topo.mesh;
  std::vector<Index> sources;
  if (const auto* move = std::get_if<MoveEdit>(&edit.change)) {
    for (const VertexOffset& target : move->offsets) {
      const Index v = state.topo.findVertex(target.vertex.index());
      bool any = false;
      Vec3 sum(0, 0, 0);
      for (const Edit& other : edits) {
        const auto* m2 = std::get_if<MoveEdit>(&other.change);
        if (m2 == nullptr || !other.active) continue;
        for (const VertexOffset& o : m2->offsets) {
          if (o.vertex == target.vertex) sum += o.localOffset, any = true;
        }
      }
      if (any) {
        state.offsets[v] = sum;
      } else {
        state.offsets.erase(v);
      }
      applyOffset(l, v);
      sources.push_back(v);
    }
  } else if (const auto* tag = std::get_if<EdgeSharpnessEdit>(&edit.change)) {
    const Index e = state.topo.findEdge(tag->edge.index());
    state.edgeTags.erase(e);
    for (const Edit& other : edits) {
      const auto* t = std::get_if<EdgeSharpnessEdit>(&other.change);
      if (t != nullptr && other.active && t->edge == tag->edge)
        state.edgeTags[e] = canonicalSharpness(t->sharpness);
    }
    auto it = state.edgeTags.find(e);
    m.edgeSharpness[e] = it != state.edgeTags.end() ? it->second : inheritedEdgeSharpness(l, e);
    sources = {m.edgeVertices[e][0], m.edgeVertices[e][1]};
    for (Index v : sources) recomputeRule(l, v);
  } else if (const auto* interp = std::get_if<InterpolationEdit>(&edit.change)) {
    // Nothing changes at level l: the next level's ghost ring does, which
    // propagate() recomputes from the faces around the vertex.
    const Index v = state.topo.findVertex(interp->vertex.index());
    state.interpolationTags.erase(v);
    if (const Edit* deciding = decidingInterpolationEdit(edits, interp->vertex)) {
      const auto& t = std::get<InterpolationEdit>(deciding->change);
      if (t.interpolating) state.interpolationTags[v] = {t.tension, t.tangent};
    }
    if (l + 1 < numLevels()) refreshReached(l + 1, verticesAround(l + 1, ghostRingChildren(l, v)));
    sources = {v};
  } else {
    const auto& vtag = std::get<VertexSharpnessEdit>(edit.change);
    const Index v = state.topo.findVertex(vtag.vertex.index());
    state.vertexTags.erase(v);
    for (const Edit& other : edits) {
      const auto* t = std::get_if<VertexSharpnessEdit>(&other.change);
      if (t != nullptr && other.active && t->vertex == vtag.vertex)
        state.vertexTags[v] = canonicalSharpness(t->sharpness);
    }
    auto it = state.vertexTags.find(v);
    m.vertexSharpness[v] = it != state.vertexTags.end()
                               ? topology::heldVertexSharpness(m, v, it->second, options_.boundary)
                               : inheritedVertexSharpness(l, v);
    recomputeRule(l, v);
    sources = {v};
  }
  sortUnique(sources);
  refreshReached(l, verticesAround(l, sources));
  return sources;
}

// Vertices of the faces around `vertices` (present faces only).
std::vector<Index> SparseHierarchy::verticesAround(int l, const std::vector<Index>& vertices) {
  const Level& m = levels_[l].topo.mesh;
  Marked out(levels_[l].vertexMarks);
  for (Index v : vertices) {
    for (Index f : m.ringFacesOf(v)) {
      if (f < 0) continue;
      forEachFaceVertex(m, f, [&](Index x) { out.add(x); });
    }
  }
  return out.toVector();
}

void SparseHierarchy::propagate(int l, std::vector<Index> changed, DirtySet& dirty) {
  refreshLimitsNear(l, changed, verticesAround(l, changed), dirty);
  for (int k = l; k + 1 < numLevels() && !changed.empty(); ++k) {
    // A child's stencil reads a changed vertex exactly when the child
    // belongs to a vertex or an edge of a face around it.
    const Level& m = levels_[k].topo.mesh;
    Marked faces(levels_[k].faceMarks);
    for (Index v : changed) {
      for (Index f : m.ringFacesOf(v)) {
        if (f >= 0) faces.add(f);
      }
    }
    // A ghost ring's points all read the mean of its plain edge points, so
    // a change anywhere around an interpolating vertex recomputes it whole.
    for (const auto& [v0, tag] : levels_[k].interpolationTags) {
      const auto around = m.ringFacesOf(v0);
      if (std::none_of(around.begin(), around.end(), [&](Index f) { return f >= 0 && faces.has(f); }))
        continue;
      for (Index f : around) {
        if (f >= 0) faces.add(f);
      }
    }
    std::vector<Index> next = refreshChildren(k, faces.items());
    if (next.empty()) break;
    dirty.pointsRecomputed += static_cast<int64_t>(next.size());
    // Offsets are stored in frames of the predicted ring: a frame moves when
    // a ring neighbour's prediction does, even if the vertex's own does not.
    LevelState& child = levels_[k + 1];
    std::vector<Index> reframed;
    if (!child.offsets.empty()) {
      const std::vector<Index> near = verticesAround(k + 1, next);
      Marked predictedChanged(child.vertexMarks);
      for (Index v : next) predictedChanged.add(v);
      for (Index w : near) {
        if (child.offsets.count(w) == 0 || predictedChanged.has(w) ||
            !touches(child.topo.mesh, w, predictedChanged)) {
          continue;
        }
        applyOffset(k + 1, w);
        reframed.push_back(w);
      }
    }
    dirty.pointsRecomputed += static_cast<int64_t>(reframed.size());
    next.insert(next.end(), reframed.begin(), reframed.end());
    refreshLimitsNear(k + 1, next, verticesAround(k + 1, next), dirty);
    changed.swap(next);
  }
}

// Sharpness, rules, predictions and points of the children (at level l+1)
// of the vertices and edges of `parentFaces`, in that order: each step reads
// only what the previous one and the parent level settled.
std::vector<Index> SparseHierarchy::refreshChildren(int l, const std::vector<Index>& parentFaces) {
  const LevelState& parent = levels_[l];
  const SparseLevel& p = parent.topo;
  LevelState& state = levels_[l + 1];
  SparseLevel& c = state.topo;
  SharpnessInheritance inherit(p.mesh, options_);
  Marked vertices(state.vertexMarks);
  for (Index f : parentFaces) {
    for (Index u : p.mesh.faceVerticesOf(f)) {
      if (const Index child = p.childOfVertex[u]; child >= 0) vertices.add(child);
    }
    if (!p.childOfFace.empty()) {
      if (const Index child = p.childOfFace[f]; child >= 0) vertices.add(child);
    }
    for (Index e : p.mesh.faceEdgesOf(f)) {
      if (const Index child = p.childOfEdge[e]; child >= 0) vertices.add(child);
      const Index half = p.halvesOfEdge[e];
      if (half < 0) continue;
      for (int end = 0; end < 2; ++end) {
        auto tag = state.edgeTags.find(half + end);
        c.mesh.edgeSharpness[half + end] =
            tag != state.edgeTags.end() ? tag->second : inherit.halfSharpness(e, end);
      }
    }
  }
  for (Index v : vertices.items()) {
    auto tag = state.vertexTags.find(v);
    c.mesh.vertexSharpness[v] = tag != state.vertexTags.end()
                                    ? topology::heldVertexSharpness(c.mesh, v, tag->second, options_.boundary)
                                    : inheritedVertexSharpness(l + 1, v);
  }
  for (Index v : vertices.items()) recomputeRule(l + 1, v);
  ChildStencils stencils(p, options_, counts_.split());
  for (Index v : vertices.items()) state.predicted[v] = stencils.predict(c, v, parent.points);
  for (const auto& [v0, tag] : parent.interpolationTags) {
    if (const Index child = p.childOfVertex[v0]; child >= 0 && vertices.has(child)) applyGhostRing(l + 1, v0);
  }
  // Frames read the predicted ring: only once every prediction is settled.
  for (Index v : vertices.items()) applyOffset(l + 1, v);
  return vertices.toVector();
}

void SparseHierarchy::refreshLimitsNear(int l, const std::vector<Index>& changed,
                                        const std::vector<Index>& candidates, DirtySet& dirty) {
  const LevelState& state = levels_[l];
  const Level& m = state.topo.mesh;
  const LevelLimits limits = limitsOf(l);
  Marked changedSet(levels_[l].vertexMarks);
  for (Index v : changed) changedSet.add(v);
  // A leaf is around about three of the refreshed vertices: listed once.
  Marked leaves(levels_[l].faceMarks);
  for (Index w : candidates) {
    if (!state.topo.isComplete(w) ||
        !limitReadsAny(m, w, counts_.quads(), [&](Index u) { return changedSet.has(u); })) {
      continue;
    }
    refreshLimit(l, w, limits);
    ++dirty.limitsRecomputed;
    dirty.limits.push_back(VertexId(l, state.topo.vertexIds[w]));
    if (!state.displayed[w]) continue;
    for (Index f : m.ringFacesOf(w)) {
      if (f >= 0 && state.leaf[f]) leaves.add(f);
    }
  }
  for (Index f : leaves.items()) dirty.leaves.push_back(FaceId(l, state.topo.faceIds[f]));
}

}  // namespace tessera
