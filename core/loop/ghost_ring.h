// Locally interpolating vertices ("Interactively Morphing Irregularly Shaped
// Images Employing Subdivision Techniques" §4, after Claes et al.): a vertex
// V0 of level l whose ring at level l+1 is a "ghost ring" centred on it, so
// that the unchanged Loop rules keep it in place at every later level and
// its limit position is V0 itself.
//
// The paper inserts ghost points Q_i on the edges V0-V_i of the control mesh
// so that V0 is their centroid (eq. 3); a Loop step then keeps V0 (eq. 4) and
// the new edge points keep the centroid (eq. 5), at any valence. Tessera
// places the ghosts where the next level already has a vertex on each edge
// V0-V_i -- the edge point of that edge -- instead of adding vertices to
// level l: the control mesh keeps Loop's topology, so the sparse hierarchy,
// limit masks and tessellation need no special case. Level l+1 is the plain
// Loop step of level l except for V0's child, which stays at V0, and its
// ring, which becomes the ghost ring:
//
//   interior V0:  G_i = V0 + (P_i - mean(P)) / tension,
//
// where P_i are the plain Loop edge points around V0. Scaling the ghost
// configuration about V0 keeps eq. 3 (the paper's tension); tension 1 keeps
// the plain ring's shape, moved so that V0 is its centroid; a larger tension
// pulls the ring in and the surface tightens around V0.
//
// A boundary vertex, or a vertex on an infinitely sharp crease, follows the
// paper's border construction: the crease rules read only the two crease
// neighbours, so the two crease edge points become ghosts on each side of
// V0 at the same distance on the tangent line,
//
//   G_a = V0 - h t,  G_b = V0 + h t,  h = |P_b - P_a| / (2 tension),
//
// with t the unit tangent: the user's, or by default the direction of the
// plain crease edge points P_b - P_a (the chord of the two crease
// neighbours). The other edge points stay plain.
//
// Where neither holds (a corner or cusp, which already interpolates, a dart,
// or a semi-sharp feature, whose rules change from level to level and break
// eq. 5) no ghost ring applies: ghostRuleOf says why.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/loop/loop_options.h"
#include "core/topology/level.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera {

// Tension is a scale of the ghost ring, so it must be positive; very large
// values collapse the ring onto V0 (a cone point in the limit).
inline constexpr double kMinTension = 1e-3;
inline constexpr double kMaxTension = 1e3;

struct InterpolationTag {
  double tension = 1.0;
  Vec3 tangent{0, 0, 0};  // crease and boundary vertices; zero: the default
};

Status checkTension(double tension, const std::string& what);

enum class GhostRule { kInterior, kCrease, kNone };

// Which construction applies at vertex v of `level` (complete ring), and
// if none, why not (in `reason`).
GhostRule ghostRuleOf(const Level& level, Index v, std::string* reason = nullptr);

struct GhostRing {
  Vec3 centre;                                // V0's child
  std::vector<std::pair<Index, Vec3>> edges;  // level-l edge of V0 -> its child's point
};

// The ghost ring of v at the next level from the level's points, or nothing
// when ghostRuleOf(level, v) is kNone.
std::optional<GhostRing> ghostRing(const Level& level, Index v, std::span<const Vec3> points,
                                   const LoopOptions& options, const InterpolationTag& tag);

}  // namespace tessera
