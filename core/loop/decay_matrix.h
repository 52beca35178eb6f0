// The lone-ring steps that take a ring with semi-sharp features to the first
// ring whose rules no longer change, composed into one matrix.
//
// Each Loop step on a lone ring (local_ring.h) is linear in the ring's points,
// and its weights depend only on the ring's sharpness: the vertex and edge
// rules, the decay and the fractional blending of Pulli & Lounsbery,
// "Hierarchical Editing and Rendering of Subdivision Surfaces" §2.4 (Sdc's
// semantics). So the k steps until every sharpness is 0 or infinite compose
// into one (n+1) x (n+1) matrix per sharpness configuration. Real documents
// repeat few configurations (a feature line tagged 2.5 gives the same rings
// all along it), so the matrix is computed once per configuration and each
// vertex costs one product instead of 1 to 10 ring refinements (docs/LIMITS.md
// "Speed": exact limits no slower than OpenSubdiv's Limit()).
#pragma once

#include <span>
#include <vector>

#include "core/loop/crease.h"
#include "core/loop/limit_masks.h"
#include "core/loop/local_ring.h"
#include "core/loop/loop_options.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

struct DecayMatrix {
  int valence = 0;
  int steps = 0;  // lone-ring steps composed
  // The stationary ring reached.
  bool boundary = false;
  VertexRule rule = VertexRule::kSmooth;
  std::vector<bool> sharpEdges;
  // Row-major (n+1) x (n+1), centre first: point i of the stationary ring is
  // sum_j weights[i * (n+1) + j] * ring point j. Column 0 is how much of the
  // original centre each point holds (LocalRing::centreWeight).
  std::vector<double> weights;
  // The stationary ring's masks (limit_masks.h) composed with this matrix:
  // the same weights, over the original ring. They give the limit position
  // and every tangent without forming the stationary ring.
  StationaryMasks composed;
  // Every sector's normal is the cross product of two of its masks. False
  // when a sector without a tangent plane orients its normal by the faces of
  // the stationary ring (SectorMasks::Kind), which are not linear in it.
  bool composedSuffices = false;

  // out = this matrix applied to `points` (n+1 of them, centre first).
  void apply(std::span<const Vec3> points, std::vector<Vec3>& out) const;
};

// The matrix of vertex v's configuration at this level, from a per-thread
// cache keyed by the sharpness its lone-ring steps read (the points only
// fill a ring on a miss). nullptr when the cache is full: the caller then
// refines the ring itself, so a document with unboundedly many distinct
// sharpness values costs time, never unbounded memory.
const DecayMatrix* cachedDecayMatrix(const Level& level, Index v, std::span<const Vec3> points,
                                     CreaseMethod method, const FarRingSharpness* far = nullptr);

// Uncached: the ring's semi-sharp features refined away on unit points.
DecayMatrix computeDecayMatrix(const LocalRing& ring, CreaseMethod method);

// The number of configurations one thread keeps.
inline constexpr size_t kDecayMatrixCacheEntries = 8192;

}  // namespace tessera
