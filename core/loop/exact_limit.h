// The limit of the Loop surface at one vertex that is not smooth: its
// position, its normal on each side of the sharp edges through it, and how
// much its own control point moves that position.
//
// Semi-sharp features that have not decayed at this level are refined away
// on the vertex's ring alone (local_ring.h); the stationary rules left then
// give the exact masks (limit_masks.h). So darts, crease sectors of any
// size, corner sectors and semi-sharp features at any level get the true
// limit, where OpenSubdiv's PrimvarRefiner::Limit() applies the masks of the
// current rules (and limit.cc once did the same).
#pragma once

#include <span>
#include <vector>

#include "core/loop/limit.h"
#include "core/loop/loop_options.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

class FarRingSharpness;  // local_ring.h

struct VertexLimit {
  Vec3 position;
  // d position / d points[v], for direct manipulation's one-step solve.
  double selfWeight = 1.0;
  // The sector limitFrame() describes (limit.h): tangent1 along the crease
  // for a crease vertex, tangent1 x tangent2 the sector's normal.
  LimitFrame frame;
  // The other sectors' normals, numbered as otherLimitSectors() numbers them.
  std::vector<LimitSector> others;
};

// Ring positions of the sharp (semi-sharp or infinitely sharp) edges of v.
std::vector<int> sharpRingEdges(const Level& level, Index v);

// `withOtherSides` false leaves VertexLimit::others empty (limitFrame() does
// not need them).
// `far` supplies the far rings Chaikin's decay reads where the level does
// not hold them (local_ring.h).
VertexLimit exactVertexLimit(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method,
                             bool withOtherSides = true, const FarRingSharpness* far = nullptr);

// The position and the primary sector's unit normal only (what
// computeLimit writes): the same values as exactVertexLimit's frame.position
// and frame.normal(), without building the frame.
void exactLimitPositionAndNormal(const Level& level, Index v, std::span<const Vec3> points,
                                 CreaseMethod method, Vec3& position, Vec3& normal,
                                 const FarRingSharpness* far = nullptr);

}  // namespace tessera
