// The limit position of the vertex one Loop step puts on an edge, read from
// the level's own points: what a tile's error needs (docs/VIEWS.md "The
// error of a tile") without refining the level under the tile.
//
// That vertex is regular wherever its edge is smooth or infinitely sharp:
// valence 6 inside (4 on the boundary), and its own edges are the halves of
// the parent edge and edges inside the parent's two faces, all smooth for a
// smooth edge, the halves infinitely sharp for a sharp one. So its limit
// has a fixed mask over its ring one level down: Loop's regular smooth
// mask (1/2 for the vertex, 1/12 for each neighbour) or the crease's cubic
// B-spline mask (2/3 for the vertex, 1/6 for each end's child; Hoppe et
// al., "Piecewise Smooth Surface Reconstruction"). Those ring points are
// the level's stencils over the 1-rings of the edge's ends, so the ends
// must be complete. A semi-sharp edge changes rule on the way to the limit:
// it has no fixed mask here, and the caller refines instead.
//
// The points one level down must be the stencils' predictions there: no
// offset, tag or interpolating vertex's ghost ring may reach the vertex's
// ring (the sparse hierarchy knows, SparseHierarchy::edgeChildIsPredicted).
#pragma once

#include <optional>
#include <span>
#include <unordered_map>

#include "core/loop/interpolate.h"
#include "core/loop/loop_options.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

// Over one level's points. The stencils it evaluates are kept: neighbouring
// edges share them (a smooth edge's limit reads five edge children and two
// vertex children), so a tile's edges cost about one stencil each.
class EdgeChildLimits {
 public:
  EdgeChildLimits(const Level& level, std::span<const Vec3> points, const LoopOptions& options)
      : level_(level), points_(points), stencils_(level, options) {}

  // nullopt for a semi-sharp edge. Both ends of e must be complete.
  std::optional<Vec3> limit(Index e);

 private:
  const Vec3& edgeChild(Index e);
  const Vec3& vertexChild(Index v);

  const Level& level_;
  const std::span<const Vec3> points_;
  LoopStencils stencils_;
  std::unordered_map<Index, Vec3> edgeChildren_, vertexChildren_;
};

}  // namespace tessera
