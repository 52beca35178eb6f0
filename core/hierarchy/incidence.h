// A face incident to a vertex or an edge of any level, found by arithmetic on
// canonical ids (ids.h) from the base level's adjacency alone: the sparse
// hierarchy uses it to decide where it must grow before that part of the
// level exists.
#pragma once

#include "core/hierarchy/ids.h"
#include "core/loop/level.h"

namespace tessera {

FaceId incidentFace(const Level& base, const LevelCounts& counts, VertexId vertex);
FaceId incidentFace(const Level& base, const LevelCounts& counts, EdgeId edge);

}  // namespace tessera
