// incidence.h's relations under the quad split (LevelCounts::quads; the
// numbering of docs/ARCHITECTURE.md "Numbering"), by arithmetic on ids from
// the base level's adjacency alone. incidence.cc calls these for a
// Catmull-Clark hierarchy.
#pragma once

#include <array>

#include "core/hierarchy/ids.h"
#include "core/topology/level.h"
#include "core/util/status.h"

namespace tessera::quad_incidence {

FaceId incidentFace(const Level& base, const LevelCounts& counts, VertexId vertex);
FaceId incidentFace(const Level& base, const LevelCounts& counts, EdgeId edge);
std::array<VertexId, 2> edgeEnds(const Level& base, const LevelCounts& counts, EdgeId edge);
// Two distinct vertices of one level > 0 (checked by the caller); `apart`
// is the error when no edge joins them.
Expected<EdgeId> edgeBetween(const Level& base, const LevelCounts& counts, VertexId a, VertexId b,
                             const Status& apart);

}  // namespace tessera::quad_incidence
