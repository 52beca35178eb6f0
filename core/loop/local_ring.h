// One vertex and its ring of neighbours, refined on their own.
//
// Loop's rules are local: the next level's centre and ring points depend
// only on this level's centre, ring and ring-edge sharpness (the vertex rule
// and the edge rule, Pulli & Lounsbery, "Hierarchical Editing and Rendering
// of Subdivision Surfaces" §2.4). So the limit at a vertex can be found
// from its ring alone by repeating one step, without refining the mesh. The
// step here applies the same rules, with the same sharpness decay and the
// same blending of fractional sharpness, as interpolate.cc and
// sharpness_inheritance.cc (Sdc semantics, which the oracle suite checks);
// tests/core/local_ring_test.cc checks it against refineLevel +
// interpolateLevel.
//
// Used where a semi-sharp feature has not decayed by the finest level: the
// ring is refined until every sharpness is 0 or infinite, after which the
// rules no longer change and the stationary masks apply (limit_masks.h).
#pragma once

#include <span>
#include <vector>

#include "core/loop/loop_options.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

// The sharpness of every edge at vertex u of a level, in ring order where
// the order is known: what Chaikin's decay at the far end of a semi-sharp
// ring edge reads (Sdc CREASE_CHAIKIN). A whole level knows it
// (Level::ringSharpness); a level that does not hold every edge at u -- a
// sparse level's incomplete vertex (core/hierarchy/sparse_level.h) -- needs
// its owner to supply it, since the decay reads one ring further than the
// Loop stencils.
class FarRingSharpness {
 public:
  virtual ~FarRingSharpness() = default;
  virtual void edgesAt(Index u, std::vector<float>& out) const = 0;
};

// The far ring of u: `far`'s where given, the level's own otherwise.
void farRingSharpness(const Level& level, Index u, const FarRingSharpness* far, std::vector<float>& out);

struct LocalRing {
  int valence = 0;
  bool boundary = false;  // ring edges 0 and valence-1 are boundary edges
  VertexRule rule = VertexRule::kSmooth;
  float vertexSharpness = 0.0f;
  std::vector<float> edgeSharpness;  // ring edge k: centre to neighbour k
  // Chaikin decay of ring edge k at its far end reads the sharpness of the
  // far vertex's ring (Sdc CREASE_CHAIKIN); empty for uniform decay.
  std::vector<std::vector<float>> farRingSharpness;
  std::vector<Vec3> points;  // [0] the centre, [1 + k] neighbour k
  // The same stencils applied to the scalar 1 at the centre and 0 elsewhere:
  // how much of the original centre each point holds (direct manipulation).
  std::vector<double> centreWeight;

  // Every sharpness is 0 or infinite: the rules are the same at every
  // further level.
  bool isStationary() const;
};

// The ring of v at this level, its points and sharpness.
LocalRing gatherLocalRing(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method,
                          const FarRingSharpness* far = nullptr);
// The same into `out`, reusing its storage.
void gatherLocalRing(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method,
                     LocalRing& out, const FarRingSharpness* far = nullptr);

// One Loop step: the centre's child and the children of its ring edges,
// which form the centre's ring at the next level, in the same ring order.
LocalRing refineLocalRing(const LocalRing& ring, CreaseMethod method);
// The same into `child` (not `ring`), reusing its storage.
void refineLocalRing(const LocalRing& ring, CreaseMethod method, LocalRing& child);

// Sharpness below 10 decays by at least 1 per level (Chaikin's average never
// exceeds the largest), so 10 steps reach the stationary rules.
inline constexpr int kMaxLoneRingDecaySteps = 12;

// Refines rings[0] until it is stationary, alternating between the two
// rings; returns the number of steps, so the result is rings[steps % 2].
int refineUntilStationary(LocalRing (&rings)[2], CreaseMethod method);

}  // namespace tessera
