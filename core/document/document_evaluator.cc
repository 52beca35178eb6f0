#include "core/document/document_evaluator.h"

#include "core/catmark/interpolate.h"
#include "core/catmark/quad_split.h"
#include "core/loop/ghost_ring.h"
#include "core/loop/interpolate.h"
#include "core/loop/local_frame.h"
#include "core/loop/refinement.h"
#include "core/topology/tags.h"

namespace tessera {

int Edit::level() const {
  struct Visitor {
    int operator()(const MoveEdit& m) const {
      return m.offsets.empty() ? 0 : m.offsets.front().vertex.level();
    }
    int operator()(const EdgeSharpnessEdit& e) const { return e.edge.level(); }
    int operator()(const VertexSharpnessEdit& v) const { return v.vertex.level(); }
    int operator()(const InterpolationEdit& t) const { return t.vertex.level(); }
  };
  return std::visit(Visitor{}, change);
}

namespace {

// Later edits win: they are applied in edit order.
void applySharpnessEdits(std::span<const Edit> edits, int level, BoundaryInterpolation boundary,
                         Level& topology) {
  bool changed = false;
  for (const Edit& edit : edits) {
    if (!edit.active || edit.level() != level) continue;
    if (const auto* e = std::get_if<EdgeSharpnessEdit>(&edit.change)) {
      topology.edgeSharpness[e->edge.index()] = canonicalSharpness(e->sharpness);
      changed = true;
    } else if (const auto* v = std::get_if<VertexSharpnessEdit>(&edit.change)) {
      const auto at = static_cast<Index>(v->vertex.index());
      topology.vertexSharpness[at] = topology::heldVertexSharpness(topology, at, v->sharpness, boundary);
      changed = true;
    }
  }
  if (changed) topology.recomputeVertexRules();
}

void applyOffsets(std::span<const Edit> edits, int level, const Level& topology,
                  std::span<const Vec3> predicted, std::vector<Vec3>& points) {
  for (const Edit& edit : edits) {
    if (!edit.active || edit.level() != level) continue;
    const auto* move = std::get_if<MoveEdit>(&edit.change);
    if (move == nullptr) continue;
    for (const VertexOffset& o : move->offsets) {
      const Index v = static_cast<Index>(o.vertex.index());
      points[v] += localFrame(topology, v, predicted).toWorld(o.localOffset);
    }
  }
}

// The interpolating vertices of level l (later edits of a vertex win) write
// their ghost rings over the plain predictions of level l+1 (ghost_ring.h).
void applyGhostRings(std::span<const Edit> edits, int level, const Level& topology,
                     std::span<const Vec3> points, const LoopOptions& options,
                     std::vector<Vec3>& childPoints) {
  std::vector<std::pair<Index, InterpolationTag>> tags;
  for (const Edit& edit : edits) {
    const auto* t = std::get_if<InterpolationEdit>(&edit.change);
    if (t == nullptr || !edit.active || edit.level() != level) continue;
    const Index v = static_cast<Index>(t->vertex.index());
    std::erase_if(tags, [&](const auto& entry) { return entry.first == v; });
    if (t->interpolating) tags.emplace_back(v, InterpolationTag{t->tension, t->tangent});
  }
  for (const auto& [v, tag] : tags) {
    const auto ring = ghostRing(topology, v, points, options, tag);
    if (!ring) continue;
    childPoints[v] = ring->centre;  // uniform numbering: vertex v -> child v, edge e -> V + e
    for (const auto& [e, point] : ring->edges) childPoints[topology.numVertices + e] = point;
  }
}

// Level l from level l-1: `refine` builds its topology, `interpolate`
// its predicted points from level l-1's points.
template <class Refine, class Interpolate>
Evaluation evaluateLevels(Level base0, std::span<const Vec3> basePoints, BoundaryInterpolation boundary,
                          std::span<const Edit> edits, int level, Refine refine, Interpolate interpolate) {
  Evaluation eval;
  eval.levels.push_back(std::move(base0));
  applySharpnessEdits(edits, 0, boundary, eval.levels[0]);
  eval.predicted.emplace_back(basePoints.begin(), basePoints.end());
  eval.points.push_back(eval.predicted[0]);
  applyOffsets(edits, 0, eval.levels[0], eval.predicted[0], eval.points[0]);

  for (int l = 1; l <= level; ++l) {
    eval.levels.push_back(refine(eval.levels[l - 1]));
    // Points of level l come from level l-1 under the rules it passes down;
    // a tag set at level l changes how level l refines, so it applies after.
    std::vector<Vec3> predicted(eval.levels[l].numVertices);
    interpolate(l - 1, eval.levels[l - 1], eval.levels[l], eval.points[l - 1], predicted);
    applySharpnessEdits(edits, l, boundary, eval.levels[l]);
    eval.points.push_back(predicted);
    applyOffsets(edits, l, eval.levels[l], predicted, eval.points[l]);
    eval.predicted.push_back(std::move(predicted));
  }
  return eval;
}

}  // namespace

Expected<Evaluation> evaluateDocument(const BaseTopology& base, std::span<const Vec3> basePoints,
                                      const LoopOptions& options, std::span<const Edit> edits, int level) {
  TESSERA_ASSIGN_OR_RETURN(Level base0, buildBaseLevel(base, options));
  return evaluateLevels(
      std::move(base0), basePoints, options.boundary, edits, level,
      [&](const Level& parent) { return refineLevel(parent, options); },
      [&](int parentLevel, const Level& parent, const Level&, std::span<const Vec3> parentPoints,
          std::vector<Vec3>& predicted) {
        interpolateLevel(parent, options, parentPoints, predicted);
        applyGhostRings(edits, parentLevel, parent, parentPoints, options, predicted);
      });
}

Expected<Evaluation> evaluateCatmarkDocument(const PolyTopology& base, std::span<const Vec3> basePoints,
                                             const CreaseOptions& options, std::span<const Edit> edits,
                                             int level) {
  for (const Edit& edit : edits) {
    if (std::holds_alternative<InterpolationEdit>(edit.change)) {
      return invalidArgument(edit.id.toString() +
                             ": interpolating vertices are defined for Loop documents only");
    }
  }
  TESSERA_ASSIGN_OR_RETURN(Level base0, buildPolyLevel(base, options));
  return evaluateLevels(
      std::move(base0), basePoints, options.boundary, edits, level,
      [&](const Level& parent) { return splitToQuads(parent, options, SplitDetail::kFull); },
      [](int, const Level& parent, const Level& child, std::span<const Vec3> parentPoints,
         std::vector<Vec3>& predicted) { interpolateCatmark(parent, child, parentPoints, predicted); });
}

}  // namespace tessera
