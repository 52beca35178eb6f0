#include "core/hierarchy/sparse_hierarchy.h"

#include <algorithm>

#include "core/hierarchy/child_stencils.h"
#include "core/hierarchy/face_corners.h"
#include "core/hierarchy/incidence.h"
#include "core/hierarchy/limit_reads.h"
#include "core/loop/interpolate.h"
#include "core/loop/limit.h"
#include "core/loop/sharpness_inheritance.h"
#include "core/topology/tags.h"

namespace tessera {

namespace {

template <typename Visit>
void forEachElement(const Edit& edit, Visit&& visit) {
  if (const auto* move = std::get_if<MoveEdit>(&edit.change)) {
    for (const VertexOffset& o : move->offsets) visit(o.vertex);
  } else if (const auto* e = std::get_if<EdgeSharpnessEdit>(&edit.change)) {
    visit(e->edge);
  } else if (const auto* t = std::get_if<InterpolationEdit>(&edit.change)) {
    // Its ghost ring lives one level down: the hierarchy must hold V0's
    // child with its ring there, and the edit nodes reach that level (as a
    // move of the ring there would).
    visit(VertexId(t->vertex.level() + 1, t->vertex.index()));
  } else {
    visit(std::get<VertexSharpnessEdit>(edit.change).vertex);
  }
}

}  // namespace

SparseHierarchy::SparseHierarchy(const LoopOptions& options, const LevelCounts& counts, int uniformLevel)
    : options_(options), counts_(counts), selection_(counts, std::min(uniformLevel, counts.maxLevel())) {}

Expected<SparseHierarchy> SparseHierarchy::create(const BaseTopology& base, std::span<const Vec3> basePoints,
                                                  const LoopOptions& options, const LevelCounts& counts,
                                                  int uniformLevel, std::span<const Edit> edits) {
  TESSERA_ASSIGN_OR_RETURN(Level level0, buildBaseLevel(base, options));
  return create(std::move(level0), basePoints, options, counts, uniformLevel, edits);
}

Expected<SparseHierarchy> SparseHierarchy::create(Level level0, std::span<const Vec3> basePoints,
                                                  const LoopOptions& options, const LevelCounts& counts,
                                                  int uniformLevel, std::span<const Edit> edits) {
  if (uniformLevel < 0) return invalidArgument("the uniform level must be >= 0");
  if (level0.numVertices != static_cast<Index>(basePoints.size()) ||
      counts.vertices(0) != static_cast<uint64_t>(level0.numVertices) ||
      counts.faces(0) != static_cast<uint64_t>(level0.numFaces())) {
    return invalidArgument(
        "the base level, its points and the level counts disagree: " + std::to_string(level0.numVertices) +
        " vertices, " + std::to_string(basePoints.size()) + " points, counts for " +
        std::to_string(counts.vertices(0)) + " vertices and " + std::to_string(counts.faces(0)) + " faces");
  }
  if (counts.quads()) {
    for (const Edit& edit : edits) {
      if (const auto* t = std::get_if<InterpolationEdit>(&edit.change)) {
        return invalidArgument(edit.id.toString() + " makes " + t->vertex.toString() +
                               " interpolating, which Catmull-Clark documents do not support: interpolating "
                               "vertices are defined with Loop's ghost rings (docs/INTERPOLATION.md)");
      }
    }
  }
  SparseHierarchy eval(options, counts, uniformLevel);
  eval.baseEdgeSharpness_.assign(level0.edgeSharpness.begin(), level0.edgeSharpness.end());
  eval.baseVertexSharpness_.assign(level0.vertexSharpness.begin(), level0.vertexSharpness.end());
  eval.basePoints_.assign(basePoints.begin(), basePoints.end());
  eval.levels_.resize(1);
  eval.levels_[0].topo = sparseBaseLevel(std::move(level0));
  for (const Edit& edit : edits) eval.addDemand(edit);
  eval.evaluateLevel(0, edits);
  eval.growFrom(0, edits);
  return eval;
}

// ---- Structure ---------------------------------------------------------

std::vector<FaceId> SparseHierarchy::demandedFaces(const Edit& edit) const {
  std::vector<FaceId> faces;
  forEachElement(edit, [&](auto id) {
    if (id.level() > 0) faces.push_back(incidentFace(levels_[0].topo.mesh, counts_, id));
  });
  return faces;
}

void SparseHierarchy::addDemand(const Edit& edit) {
  for (FaceId face : demandedFaces(edit)) selection_.demandForEdit(face);
}

// A demanded face adds N1(its ancestor) to Sel at each level from the
// uniform one down to its parent's; covered if all of those are there.
bool SparseHierarchy::demandCovered(FaceId face) const {
  for (int k = selection_.uniformLevel(); k < face.level(); ++k) {
    if (k + 1 >= numLevels()) return false;
    if (!selection_.ancestorRingSelected(levels_[k].topo, levels_[k].selected, face)) return false;
  }
  return true;
}

// Growth adds faces and changes no value: a canonical vertex's prediction
// reads its parent's ring, and its limit its own complete ring, whatever
// else is present, and every caller grows for the edits the levels already
// reflect. So levels grow in place (extendSparse): what they held keeps its
// local index, prediction, point and limit, and only what is new is
// computed: the new vertices' predictions, and the limits of the vertices
// whose rings the growth completed. The selection only grows (a demand is
// never taken back), so no level ever loses a face.
void SparseHierarchy::growFrom(int l, std::span<const Edit> edits) {
  const int deepest = std::max(selection_.uniformLevel(), selection_.deepestDemand());
  std::vector<std::vector<Index>> completed(deepest + 1);
  std::vector<uint8_t> fresh(deepest + 1, 0);
  for (int k = l; k <= deepest; ++k) {
    const std::vector<Index> toRefine =
        selection_.growSelection(levels_[k].topo, levels_[k].selected, levels_[k].editSelected);
    ++levels_[k].generation;
    if (k == deepest) {
      SparseLevel& last = levels_[k].topo;
      last.firstChildFace.resize(last.mesh.numFaces(), kNoIndex);
      last.childOfVertex.resize(last.mesh.numVertices, kNoIndex);
      last.childOfEdge.resize(last.mesh.numEdges(), kNoIndex);
      last.halvesOfEdge.resize(last.mesh.numEdges(), kNoIndex);
      if (counts_.quads()) last.childOfFace.resize(last.mesh.numFaces(), kNoIndex);
      break;
    }
    if (k + 1 < numLevels()) {
      if (toRefine.empty()) continue;
      LevelExtension grown = extendSparse(levels_[k].topo, levels_[k + 1].topo, toRefine, counts_, options_);
      evaluateNewVertices(k + 1, grown);
      completed[k + 1] = std::move(grown.completed);
      continue;
    }
    Buffer<uint8_t> refined(levels_[k].topo.mesh.numFaces(), 0);
    for (Index f : toRefine) refined[f] = 1;
    SparseLevel child = refineSparse(levels_[k].topo, refined, counts_, options_);
    levels_.emplace_back();
    levels_[k + 1].topo = std::move(child);
    evaluateLevel(k + 1, edits);
    fresh[k + 1] = 1;
  }
  for (int k = l; k <= deepest; ++k) markLeaves(k, fresh[k] != 0, completed[k]);
}

void SparseHierarchy::evaluateNewVertices(int l, const LevelExtension& grown) {
  LevelState& state = levels_[l];
  const SparseLevel& topo = state.topo;
  const Index n = topo.mesh.numVertices;
  state.vertexMarks.resize(n, 0);
  state.faceMarks.resize(topo.mesh.numFaces(), 0);
  state.predicted.resize(n);
  state.points.resize(n);
  state.limitPosition.resize(n);
  state.limitNormal.resize(n);
  state.reached.resize(n, 0);
  const LevelState& parent = levels_[l - 1];
  ChildStencils stencils(parent.topo, options_, counts_.split());
  for (Index v = grown.firstNewVertex; v < n; ++v)
    state.predicted[v] = stencils.predict(topo, v, parent.points);
  // Ghost rings read only the parent: written again, they are what they
  // were where they were held, and set the new vertices they reach.
  for (const auto& [v, tag] : parent.interpolationTags) applyGhostRing(l, v);
  // No edit addresses a vertex the level did not hold (its node holds it).
  for (Index v = grown.firstNewVertex; v < n; ++v) state.points[v] = state.predicted[v];
  refreshReached(l, grown.completed);
}

void SparseHierarchy::markLeaves(int l, bool freshLevel, const std::vector<Index>& newLimits) {
  LevelState& state = levels_[l];
  const Level& m = state.topo.mesh;
  state.leaf.assign(m.numFaces(), 0);
  state.displayed.assign(m.numVertices, 0);
  for (Index f = 0; f < m.numFaces(); ++f) {
    const bool node = l == 0 || levels_[l - 1].selected[state.topo.parentOfFace(f)];
    if (!node || state.selected[f]) continue;
    state.leaf[f] = 1;
    forEachFaceVertex(m, f, [&](Index v) { state.displayed[v] = 1; });
  }
  freshLevel = freshLevel || state.limitPosition.empty();  // level 0, first marked
  if (!freshLevel && newLimits.empty()) return;
  if (!freshLevel) {
    const LevelLimits limits = limitsOf(l);
    state.limitPosition.resize(m.numVertices);
    state.limitNormal.resize(m.numVertices);
    for (Index v : newLimits) refreshLimit(l, v, limits);
    return;
  }
  const LevelLimits limits = limitsOf(l, CatmarkLimitEvaluator::Scope::kWholeLevel);
  // Each limit written once, in order: a resize first would zero the
  // arrays only for this loop to write them again (a tenth of building a
  // Catmull-Clark level, docs/PERFORMANCE.md "Catmull-Clark in the
  // hierarchy"). A vertex without a complete ring has none: zero.
  state.limitPosition.clear();
  state.limitNormal.clear();
  state.limitPosition.reserve(m.numVertices);
  state.limitNormal.reserve(m.numVertices);
  for (Index v = 0; v < m.numVertices; ++v) {
    if (!state.topo.isComplete(v)) {
      state.limitPosition.emplace_back(0, 0, 0);
      state.limitNormal.emplace_back(0, 0, 0);
      continue;
    }
    const LevelLimits::PositionNormal limit = limits.positionAndNormal(v, state.points);
    state.limitPosition.push_back(limit.position);
    state.limitNormal.push_back(limit.normal);
  }
}

LimitFrame SparseHierarchy::limitFrameOf(int l, Index v) const {
  return limitsOf(l).frame(v, levels_[l].points);
}

Vec3 SparseHierarchy::solveControlPoint(int l, Index v, const Vec3& target) const {
  const SparseLevel& parent = levels_[l].topo;
  const Index c = hasLimits(l) || l + 1 >= numLevels() ? kNoIndex : parent.childOfVertex[v];
  if (c == kNoIndex || !levels_[l + 1].topo.isComplete(c))
    return limitsOf(l).solveControlPoint(v, levels_[l].points, target);
  // The limit shown is the child's (displayed_vertices.h), read from level
  // l + 1's points, each of which the split's stencils make affine in this
  // control point: the limit moves by alpha times its displacement, with
  // alpha the child's limit mask applied to the stencils' weights of it
  // (both linear, so computed by applying them to a unit point). Exact
  // while no offset of level l + 1 near the child turns with its frame
  // (Pulli & Lounsbery §2.2 solve on the vertex's own level the same way).
  const SparseLevel& child = levels_[l + 1].topo;
  std::vector<Vec3> unit(static_cast<size_t>(parent.mesh.numVertices), Vec3(0, 0, 0));
  unit[v] = Vec3(1, 0, 0);
  ChildStencils stencils(parent, options_, counts_.split());
  std::vector<Vec3> weights(static_cast<size_t>(child.mesh.numVertices), Vec3(0, 0, 0));
  for (Index f : child.mesh.ringFacesOf(c)) {
    if (f < 0) continue;
    for (Index j : child.mesh.faceVerticesOf(f)) weights[j] = stencils.predict(child, j, unit);
  }
  const double alpha = limitsOf(l + 1).frame(c, weights).position[0];
  return levels_[l].points[v] + (1.0 / alpha) * (target - levels_[l + 1].limitPosition[c]);
}

LevelLimits SparseHierarchy::limitsOf(int l, CatmarkLimitEvaluator::Scope scope) const {
  return LevelLimits(levels_[l].topo, l > 0 ? &levels_[l - 1].topo : nullptr, options_, counts_.split(),
                     scope);
}

void SparseHierarchy::refreshLimit(int l, Index v, const LevelLimits& limits) {
  LevelState& state = levels_[l];
  const LevelLimits::PositionNormal limit = limits.positionAndNormal(v, state.points);
  state.limitPosition[v] = limit.position;
  state.limitNormal[v] = limit.normal;
}

// ---- One level's points and tags -------------------------------------

void SparseHierarchy::evaluateLevel(int l, std::span<const Edit> edits) {
  LevelState& state = levels_[l];
  const SparseLevel& topo = state.topo;
  resolveTags(l, edits);
  applyTags(l);
  const Index n = topo.mesh.numVertices;
  state.vertexMarks.assign(n, 0);
  state.faceMarks.assign(topo.mesh.numFaces(), 0);
  if (l == 0) {
    state.predicted.assign(basePoints_.begin(), basePoints_.end());
  } else {
    // A tag set on this level changes how it refines, not how it was
    // predicted: the stencils read only the parent (interpolate.h).
    // Appended, not resized and overwritten: each point written once.
    const LevelState& parent = levels_[l - 1];
    ChildStencils stencils(parent.topo, options_, counts_.split());
    state.predicted.clear();
    state.predicted.reserve(n);
    for (Index v = 0; v < n; ++v) state.predicted.push_back(stencils.predict(topo, v, parent.points));
    for (const auto& [v, tag] : parent.interpolationTags) applyGhostRing(l, v);
  }
  state.points = state.predicted;
  state.offsets.clear();
  for (const Edit& edit : edits) {
    const auto* move = std::get_if<MoveEdit>(&edit.change);
    if (move == nullptr || !edit.active || edit.level() != l) continue;
    for (const VertexOffset& o : move->offsets)
      state.offsets[topo.findVertex(o.vertex.index())] += o.localOffset;
  }
  for (const auto& [v, offset] : state.offsets) applyOffset(l, v);
  state.reached.assign(n, 0);
  std::vector<Index> edited;
  for (const auto& [v, offset] : state.offsets) edited.push_back(v);
  for (const auto& [v, s] : state.vertexTags) edited.push_back(v);
  for (const auto& [e, s] : state.edgeTags)
    edited.insert(edited.end(), {topo.mesh.edgeVertices[e][0], topo.mesh.edgeVertices[e][1]});
  if (l > 0) {
    for (const auto& [v, tag] : levels_[l - 1].interpolationTags) {
      for (Index c : ghostRingChildren(l - 1, v)) edited.push_back(c);
    }
  }
  if (!edited.empty()) refreshReached(l, verticesAround(l, edited));
}

void SparseHierarchy::refreshReached(int l, const std::vector<Index>& vertices) {
  LevelState& state = levels_[l];
  const SparseLevel& topo = state.topo;
  auto moved = [&](Index u) {
    return u >= 0 && (state.offsets.count(u) != 0 || state.vertexTags.count(u) != 0 || isGhosted(l, u));
  };
  for (Index v : vertices) {
    bool reached = false;
    if (topo.isComplete(v)) {
      reached = limitReadsAny(topo.mesh, v, counts_.quads(), moved);
      for (Index e : topo.mesh.ringEdgesOf(v)) reached = reached || state.edgeTags.count(e) != 0;
    }
    state.reached[v] = reached ? 1 : 0;
  }
}

// Later edits win: they are resolved in edit order.
void SparseHierarchy::resolveTags(int l, std::span<const Edit> edits) {
  LevelState& state = levels_[l];
  state.edgeTags.clear();
  state.vertexTags.clear();
  state.interpolationTags.clear();
  for (const Edit& edit : edits) {
    if (!edit.active || edit.level() != l) continue;
    if (const auto* t = std::get_if<InterpolationEdit>(&edit.change)) {
      const Index v = state.topo.findVertex(t->vertex.index());
      if (t->interpolating) {
        state.interpolationTags[v] = {t->tension, t->tangent};
      } else {
        state.interpolationTags.erase(v);
      }
    } else if (const auto* e = std::get_if<EdgeSharpnessEdit>(&edit.change)) {
      state.edgeTags[state.topo.findEdge(e->edge.index())] = canonicalSharpness(e->sharpness);
    } else if (const auto* v = std::get_if<VertexSharpnessEdit>(&edit.change)) {
      state.vertexTags[state.topo.findVertex(v->vertex.index())] = canonicalSharpness(v->sharpness);
    }
  }
}

void SparseHierarchy::applyTags(int l) {
  LevelState& state = levels_[l];
  Level& m = state.topo.mesh;
  for (const auto& [e, s] : state.edgeTags) m.edgeSharpness[e] = s;
  for (const auto& [v, s] : state.vertexTags)
    m.vertexSharpness[v] = topology::heldVertexSharpness(m, v, s, options_.boundary);
  for (const auto& [e, s] : state.edgeTags) {
    recomputeRule(l, m.edgeVertices[e][0]);
    recomputeRule(l, m.edgeVertices[e][1]);
  }
  for (const auto& [v, s] : state.vertexTags) recomputeRule(l, v);
}

float SparseHierarchy::inheritedVertexSharpness(int l, Index v) const {
  if (l == 0) return baseVertexSharpness_[v];
  const SparseLevel& topo = levels_[l].topo;
  if (!topo.isVertexChild(v)) return kSharpnessSmooth;
  return decrementSharpness(levels_[l - 1].topo.mesh.vertexSharpness[topo.origin[v]]);
}

float SparseHierarchy::inheritedEdgeSharpness(int l, Index e) const {
  if (l == 0) return baseEdgeSharpness_[e];
  // Halves of parent edges are numbered 2e + end, after the interior edges
  // under a quad split, before them under Loop's (docs/ARCHITECTURE.md "Numbering").
  const uint64_t firstHalf = counts_.quads() ? counts_.corners(l - 1) : 0;
  const uint64_t id = levels_[l].topo.edgeIds[e];
  if (id < firstHalf || id - firstHalf >= 2 * counts_.edges(l - 1)) return kSharpnessSmooth;  // interior
  const SparseLevel& parent = levels_[l - 1].topo;
  SharpnessInheritance inherit(parent.mesh, options_);
  return inherit.halfSharpness(parent.findEdge((id - firstHalf) / 2), static_cast<int>((id - firstHalf) % 2));
}

// Complete vertices read their own ring (tags on this level count); the
// others inherit the rule their parent passes down.
void SparseHierarchy::recomputeRule(int l, Index v) {
  Level& m = levels_[l].topo.mesh;
  const SparseLevel& topo = levels_[l].topo;
  if (topo.isComplete(v)) {
    int sharp = 0;
    for (Index e : m.ringEdgesOf(v)) sharp += isSharp(m.edgeSharpness[e]) ? 1 : 0;
    m.vertexRules[v] = vertexRule(m.vertexSharpness[v], sharp);
    return;
  }
  if (topo.isFaceChild(v)) {
    m.vertexRules[v] = VertexRule::kSmooth;  // a vertex in a parent face has smooth edges only
    return;
  }
  SharpnessInheritance inherit(levels_[l - 1].topo.mesh, options_);
  m.vertexRules[v] =
      topo.isVertexChild(v) ? inherit.vertexChildRule(topo.origin[v]) : inherit.edgeChildRule(topo.origin[v]);
}

void SparseHierarchy::applyOffset(int l, Index v) {
  LevelState& state = levels_[l];
  auto it = state.offsets.find(v);
  state.points[v] =
      it == state.offsets.end() ? state.predicted[v] : state.predicted[v] + frameOf(l, v).toWorld(it->second);
}

void SparseHierarchy::applyGhostRing(int l, Index v0) {
  const LevelState& parent = levels_[l - 1];
  const SparseLevel& p = parent.topo;
  LevelState& state = levels_[l];
  const auto tag = parent.interpolationTags.find(v0);
  if (tag == parent.interpolationTags.end() || !p.isComplete(v0)) return;
  const auto ring = ghostRing(p.mesh, v0, parent.points, options_, tag->second);
  if (!ring) return;
  if (const Index c = p.childOfVertex[v0]; c >= 0) state.predicted[c] = ring->centre;
  for (const auto& [e, point] : ring->edges) {
    if (const Index c = p.childOfEdge[e]; c >= 0) state.predicted[c] = point;
  }
}

bool SparseHierarchy::isGhosted(int l, Index v) const {
  if (l == 0) return false;
  const LevelState& parent = levels_[l - 1];
  if (parent.interpolationTags.empty()) return false;
  const SparseLevel& topo = levels_[l].topo;
  if (topo.isFaceChild(v)) return false;  // ghost rings are Loop's (core/loop/ghost_ring.h)
  auto applies = [&](Index u) {
    return parent.interpolationTags.count(u) != 0 && parent.topo.isComplete(u) &&
           ghostRuleOf(parent.topo.mesh, u) != GhostRule::kNone;
  };
  if (topo.isVertexChild(v)) return applies(topo.origin[v]);
  const auto& ends = parent.topo.mesh.edgeVertices[topo.origin[v]];
  return applies(ends[0]) || applies(ends[1]);
}

bool SparseHierarchy::edgeChildIsPredicted(int l, Index e) const {
  const LevelState& state = levels_[l];
  const Level& m = state.topo.mesh;
  if (!state.interpolationTags.empty()) {
    for (Index f : m.edgeFaces[e]) {
      if (f < 0) continue;
      for (Index v : m.faceVerticesOf(f)) {
        if (state.interpolationTags.count(v) != 0) return false;
      }
    }
  }
  if (l + 1 >= numLevels()) return true;
  const Index child = state.topo.childOfEdge.empty() ? kNoIndex : state.topo.childOfEdge[e];
  return child < 0 || !isReachedByEdit(l + 1, child);
}

std::vector<Index> SparseHierarchy::ghostRingChildren(int l, Index v) const {
  std::vector<Index> children;
  if (l + 1 >= numLevels() || v < 0) return children;
  const SparseLevel& p = levels_[l].topo;
  if (const Index c = p.childOfVertex[v]; c >= 0) children.push_back(c);
  for (Index e : p.mesh.ringEdgesOf(v)) {
    if (e >= 0 && p.childOfEdge[e] >= 0) children.push_back(p.childOfEdge[e]);
  }
  return children;
}

LocalFrame SparseHierarchy::frameOf(int l, Index v) const {
  return localFrame(levels_[l].topo.mesh, v, levels_[l].predicted);
}

// ---- Queries -------------------------------------------------------------

Expected<Index> SparseHierarchy::completeVertex(VertexId id) const {
  if (id.level() >= numLevels()) {
    return notFound(id.toString() + ": level " + std::to_string(id.level()) + " is not in the hierarchy");
  }
  const SparseLevel& topo = levels_[id.level()].topo;
  const Index v = topo.findVertex(id.index());
  if (v == kNoIndex || !topo.isComplete(v)) {
    return notFound(id.toString() + ": not held with its whole ring by the hierarchy");
  }
  return v;
}

HierarchyStats SparseHierarchy::stats() const {
  HierarchyStats stats;
  for (const LevelState& state : levels_) {
    HierarchyStats::PerLevel level;
    const Level& m = state.topo.mesh;
    level.faces = m.numFaces();
    level.vertices = m.numVertices;
    level.completeVertices = std::count(state.topo.complete.begin(), state.topo.complete.end(), 1);
    level.leaves = std::count(state.leaf.begin(), state.leaf.end(), 1);
    level.displayedVertices = std::count(state.displayed.begin(), state.displayed.end(), 1);
    const size_t vec3 = sizeof(Vec3);
    level.bytes = state.topo.memoryBytes() + state.selected.capacity() + state.leaf.capacity() +
                  state.displayed.capacity() + state.reached.capacity() + state.vertexMarks.capacity() +
                  state.faceMarks.capacity() +
                  vec3 * (state.predicted.capacity() + state.points.capacity() +
                          state.limitPosition.capacity() + state.limitNormal.capacity()) +
                  (sizeof(Index) + vec3 + 16) * state.offsets.size() +
                  (sizeof(Index) + sizeof(float) + 16) * (state.edgeTags.size() + state.vertexTags.size());
    stats.vertices += level.vertices;
    stats.displayedVertices += level.displayedVertices;
    stats.bytes += level.bytes;
    stats.levels.push_back(level);
  }
  return stats;
}

// ---- Growth ----------------------------------------------------------------

DirtySet SparseHierarchy::reserve(const Edit& edit, std::span<const Edit> edits) {
  DirtySet dirty;
  const std::vector<FaceId> faces = demandedFaces(edit);
  if (std::all_of(faces.begin(), faces.end(), [&](FaceId face) { return demandCovered(face); })) {
    // Held already (for a tessellation or an earlier edit): the edit still
    // makes its edit nodes, as in a document created with it.
    for (FaceId face : faces) {
      if (selection_.demandForEdit(face)) markEditNodes(face, dirty);
    }
    std::sort(dirty.limits.begin(), dirty.limits.end());
    dirty.limits.erase(std::unique(dirty.limits.begin(), dirty.limits.end()), dirty.limits.end());
    return dirty;
  }
  addDemand(edit);
  const int first = firstChangedSelection();
  growFrom(first, edits);
  dirty.grownFromLevel = first;
  return dirty;
}

DirtySet SparseHierarchy::forgetEditNodes(std::span<const Edit> edits) {
  DirtySet dirty;
  std::set<FaceId> now;
  for (const Edit& edit : edits) {
    for (FaceId face : demandedFaces(edit)) now.insert(face);
  }
  if (!selection_.replaceEditDemand(std::move(now))) return dirty;
  for (int k = 0; k < numLevels(); ++k) {
    LevelState& state = levels_[k];
    Buffer<uint8_t> editSelected;
    selection_.selectEdits(state.topo, editSelected);
    const Level& m = state.topo.mesh;
    for (Index f = 0; f < static_cast<Index>(editSelected.size()); ++f) {
      if (editSelected[f] == state.editSelected[f]) continue;
      for (Index v : m.faceVerticesOf(f)) {
        if (state.topo.isComplete(v)) dirty.limits.push_back(VertexId(k, state.topo.vertexIds[v]));
      }
    }
    state.editSelected = std::move(editSelected);
  }
  std::sort(dirty.limits.begin(), dirty.limits.end());
  dirty.limits.erase(std::unique(dirty.limits.begin(), dirty.limits.end()), dirty.limits.end());
  return dirty;
}

// What the selection adds to editSelected for one more demanded face, in
// place: N1 of its ancestor at every coarser level. A tessellation decides
// again only around changed limits, so where faces just became edit nodes
// the ancestor's corners, whose rings are exactly those faces, are
// reported as such (recomputed, unchanged).
void SparseHierarchy::markEditNodes(FaceId face, DirtySet& dirty) {
  for (int k = 0; k < face.level() && k < numLevels(); ++k) {
    LevelState& state = levels_[k];
    const Level& m = state.topo.mesh;
    const Index a = selection_.markAncestorRing(state.topo, face, state.editSelected);
    if (a == kNoIndex) continue;
    const LevelLimits limits = limitsOf(k);
    for (Index v : m.faceVerticesOf(a)) {
      if (!state.topo.isComplete(v)) continue;
      refreshLimit(k, v, limits);
      ++dirty.limitsRecomputed;
      dirty.limits.push_back(VertexId(k, state.topo.vertexIds[v]));
    }
  }
}

// Growth starts at the first level where new demand waits or the edit
// nodes change: levels above keep their topology, points and limits.
int SparseHierarchy::firstChangedSelection() const {
  for (int k = 0; k < numLevels(); ++k) {
    if (k >= selection_.uniformLevel() && selection_.hasFresh(k)) return k;
    Buffer<uint8_t> editSelected;
    selection_.selectEdits(levels_[k].topo, editSelected);
    if (editSelected != levels_[k].editSelected) return k;
  }
  return numLevels() - 1;
}

int SparseHierarchy::reserveFaces(std::span<const FaceId> faces, std::span<const Edit> edits) {
  // A view asks for many faces with common ancestors: in (level, index)
  // order, siblings are neighbours, and each ancestor is judged once.
  std::vector<FaceId> sorted(faces.begin(), faces.end());
  std::sort(sorted.begin(), sorted.end(), [](FaceId a, FaceId b) {
    return std::pair(a.level(), a.index()) < std::pair(b.level(), b.index());
  });
  std::vector<std::pair<uint64_t, bool>> judged(numLevels(), {~uint64_t{0}, false});
  bool covered = true;
  for (FaceId face : sorted) {
    if (face.level() <= 0) continue;
    bool held = true;
    for (int k = selection_.uniformLevel(); held && k < face.level(); ++k) {
      const uint64_t ancestor = counts_.ancestorAt(face, k).index();
      if (k + 1 >= numLevels()) {
        held = false;
      } else if (judged[k].first == ancestor) {
        held = judged[k].second;
      } else {
        held = selection_.ancestorRingSelected(levels_[k].topo, levels_[k].selected, face);
        judged[k] = {ancestor, held};
      }
    }
    if (!held) covered = false, selection_.demandForTessellation(face);
  }
  if (covered) return -1;
  const int first = firstChangedSelection();
  growFrom(first, edits);
  return first;
}

void SparseHierarchy::raiseUniformLevel(int level, std::span<const Edit> edits) {
  level = std::min(level, counts_.maxLevel());
  if (level <= selection_.uniformLevel()) return;
  const int first = selection_.uniformLevel();
  selection_.raiseUniformLevel(level);
  growFrom(first, edits);
}

}  // namespace tessera
