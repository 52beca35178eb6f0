#include "core/hierarchy/interpolation_conflicts.h"

#include <optional>
#include <vector>

#include "core/hierarchy/incidence.h"

namespace tessera {

namespace {

// The vertices interpolating after `edits` (later edits of a vertex win).
std::vector<VertexId> interpolatingVertices(std::span<const Edit> edits, const Edit* skip) {
  std::vector<VertexId> on;
  for (const Edit& edit : edits) {
    const auto* t = std::get_if<InterpolationEdit>(&edit.change);
    if (t == nullptr || !edit.active || &edit == skip) continue;
    std::erase(on, t->vertex);
    if (t->interpolating) on.push_back(t->vertex);
  }
  return on;
}

// A vertex of a finer level that is the interpolating vertex's descendant
// (vertex children keep their index, ids.h) or one of its ring neighbours.
bool inGhostRing(VertexId u, VertexId v0, const Level& base, const LevelCounts& counts) {
  if (u.level() <= v0.level()) return false;
  const VertexId descendant(u.level(), v0.index());
  return u == descendant || edgeBetween(base, counts, u, descendant).isOk();
}

bool onDescendant(VertexId u, VertexId v0) {
  return u.level() >= v0.level() && u.index() == v0.index();
}

Status conflict(const std::string& what, VertexId v0, const char* why) {
  return invalidArgument(what + " conflicts with interpolating vertex " + v0.toString() + ": " + why);
}

// Whether one edit `e` conflicts with interpolating vertex v0. Sharpness at
// v0's own level counts only for an edit made after the tag: before it, the
// tag's own check of v0's rule decides (Document::setInterpolation).
Status conflictWith(const Edit& e, VertexId v0, const Level& base, const LevelCounts& counts,
                    bool sameLevelSharpness) {
  if (const auto* move = std::get_if<MoveEdit>(&e.change)) {
    for (const VertexOffset& o : move->offsets) {
      if (inGhostRing(o.vertex, v0, base, counts)) {
        return conflict(
            "moving " + o.vertex.toString(), v0,
            "a finer-level move at or next to its descendant would pull it off its control point; "
            "move it or its ring at its own level instead");
      }
    }
  } else if (const auto* edge = std::get_if<EdgeSharpnessEdit>(&e.change)) {
    const int first = v0.level() + (sameLevelSharpness ? 0 : 1);
    if (edge->edge.level() < first || edge->sharpness == 0.0f) return Status::ok();
    for (VertexId end : edgeEnds(base, counts, edge->edge)) {
      if (onDescendant(end, v0)) {
        return conflict(
            "sharpness on " + edge->edge.toString(), v0,
            "a sharp edge at it makes a dart, corner or semi-sharp rule, under which it would drift; "
            "turn its interpolation off first");
      }
    }
  } else if (const auto* vertex = std::get_if<VertexSharpnessEdit>(&e.change)) {
    const bool atOrBelow = vertex->vertex.level() >= v0.level() + (sameLevelSharpness ? 0 : 1);
    if (vertex->sharpness != 0.0f && atOrBelow && onDescendant(vertex->vertex, v0)) {
      return conflict("sharpness on " + vertex->vertex.toString(), v0,
                      "a corner or cusp already interpolates; turn its interpolation off first");
    }
  }
  return Status::ok();
}

}  // namespace

Status checkInterpolationConflicts(const Edit& candidate, std::span<const Edit> edits, const Level& base,
                                   const LevelCounts& counts) {
  if (const auto* t = std::get_if<InterpolationEdit>(&candidate.change)) {
    if (!t->interpolating) return Status::ok();
    for (const Edit& other : edits) {
      if (!other.active || &other == &candidate || std::holds_alternative<InterpolationEdit>(other.change))
        continue;
      TESSERA_RETURN_IF_ERROR(
          conflictWith(other, t->vertex, base, counts, false).withContext(other.id.toString()));
    }
    // Two ghost rings may not share a point: each edge point around V0 must
    // keep V0 the centroid of its ring, which one point cannot do for two
    // centres. So no other interpolating vertex next to this one at its
    // level, nor at or next to its descendants below, nor the other way round.
    for (VertexId other : interpolatingVertices(edits, &candidate)) {
      if (other == t->vertex) continue;
      const bool overlap = other.level() == t->vertex.level()
                               ? edgeBetween(base, counts, other, t->vertex).isOk()
                           : other.level() > t->vertex.level() ? inGhostRing(other, t->vertex, base, counts)
                                                               : inGhostRing(t->vertex, other, base, counts);
      if (overlap) {
        return invalidArgument(t->vertex.toString() + " cannot interpolate next to interpolating vertex " +
                               other.toString() + ": their ghost rings would share points");
      }
    }
    return Status::ok();
  }
  for (VertexId v0 : interpolatingVertices(edits, &candidate)) {
    TESSERA_RETURN_IF_ERROR(conflictWith(candidate, v0, base, counts, true));
  }
  return Status::ok();
}

const Edit* decidingInterpolationEdit(std::span<const Edit> edits, VertexId vertex) {
  const Edit* deciding = nullptr;
  for (const Edit& edit : edits) {
    const auto* t = std::get_if<InterpolationEdit>(&edit.change);
    if (t != nullptr && edit.active && t->vertex == vertex) deciding = &edit;
  }
  return deciding;
}

}  // namespace tessera
