// A face incident to a vertex or an edge of any level, found by arithmetic on
// canonical ids (ids.h) from the base level's adjacency alone: the sparse
// hierarchy uses it to decide where it must grow before that part of the
// level exists.
//
// edgeEnds and edgeBetween relate edges and vertices of any level the same
// way, so that a client holding only vertex ids (a tessera-view pick) can
// name an edge: an edge of level l > 0 is either a half of a parent edge,
// joining a parent vertex to the vertex on that edge, or interior to a parent
// face, joining the vertices on two of its edges (refinement.h) or, under
// the quad split, the face's vertex to the vertex on one of its edges
// (quad_incidence.h).
#pragma once

#include <array>

#include "core/hierarchy/ids.h"
#include "core/topology/level.h"
#include "core/util/status.h"

namespace tessera {

FaceId incidentFace(const Level& base, const LevelCounts& counts, VertexId vertex);
FaceId incidentFace(const Level& base, const LevelCounts& counts, EdgeId edge);

// The two end vertices of an edge, in the order of the uniform refinement's
// edgeVertices. The id must exist (LevelCounts::check).
std::array<VertexId, 2> edgeEnds(const Level& base, const LevelCounts& counts, EdgeId edge);

// The edge joining two vertices of one level, in either order. Errors name
// both ids: unknown ids (kNotFound), different levels, the same vertex
// twice, or vertices that no edge of that level joins (kInvalidArgument).
Expected<EdgeId> edgeBetween(const Level& base, const LevelCounts& counts, VertexId a, VertexId b);

}  // namespace tessera
