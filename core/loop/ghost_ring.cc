#include "core/loop/ghost_ring.h"

#include <cmath>

#include "core/loop/interpolate.h"
#include "core/mesh/sharpness.h"

namespace tessera {

Status checkTension(double tension, const std::string& what) {
  if (!(tension >= kMinTension && tension <= kMaxTension)) {  // also NaN
    // The bounds as written in ghost_ring.h (to_string would print 0.001000).
    return invalidArgument(
        what + ": tension must be in [0.001, 1000] (it scales the ghost ring by 1/tension), got " +
        std::to_string(tension));
  }
  return Status::ok();
}

GhostRule ghostRuleOf(const Level& m, Index v, std::string* reason) {
  auto none = [&](const char* why) {
    if (reason != nullptr) *reason = why;
    return GhostRule::kNone;
  };
  if (isSharp(m.vertexSharpness[v])) return none("it is a corner or cusp, which already interpolates");
  int infinite = 0;
  for (Index e : m.ringEdgesOf(v)) {
    if (e < 0) return none("its ring is not complete");
    const float s = m.edgeSharpness[e];
    if (isSemiSharp(s)) return none("a semi-sharp edge meets it (its rule changes from level to level)");
    if (isInfinite(s)) ++infinite;
  }
  if (infinite == 0) return GhostRule::kInterior;
  if (infinite == 2) return GhostRule::kCrease;
  return none(infinite == 1 ? "it is a dart (one sharp edge), whose sharp edge breaks the centroid rule"
                            : "three or more sharp edges make it a corner, which already interpolates");
}

std::optional<GhostRing> ghostRing(const Level& m, Index v, std::span<const Vec3> points,
                                   const LoopOptions& options, const InterpolationTag& tag) {
  const GhostRule rule = ghostRuleOf(m, v);
  if (rule == GhostRule::kNone) return std::nullopt;
  LoopStencils stencils(m, options);
  GhostRing ring;
  const Vec3 v0 = points[v];
  ring.centre = v0;
  for (Index e : m.ringEdgesOf(v)) ring.edges.emplace_back(e, stencils.edgeChild(e, points));
  const double scale = 1.0 / tag.tension;
  if (rule == GhostRule::kInterior) {
    Vec3 mean(0, 0, 0);
    for (const auto& [e, p] : ring.edges) mean += p;
    mean *= 1.0 / static_cast<double>(ring.edges.size());
    for (auto& [e, p] : ring.edges) p = v0 + (p - mean) * scale;
    return ring;
  }
  std::pair<Index, Vec3>* ends[2] = {nullptr, nullptr};
  for (auto& entry : ring.edges) {
    if (isInfinite(m.edgeSharpness[entry.first])) (ends[0] == nullptr ? ends[0] : ends[1]) = &entry;
  }
  const Vec3 chord = ends[1]->second - ends[0]->second;
  const double length = chord.norm();
  Vec3 t = tag.tangent.norm() > 0 ? tag.tangent : chord;
  const double tn = t.norm();
  if (!(length > 0) || !(tn > 0)) return ring;  // coincident points: nothing to centre on
  t *= 1.0 / tn;
  if (dot(t, chord) < 0) t *= -1.0;
  const double h = 0.5 * length * scale;
  ends[0]->second = v0 - t * h;
  ends[1]->second = v0 + t * h;
  return ring;
}

}  // namespace tessera
