#include "core/loop/exact_limit.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/loop/decay_matrix.h"
#include "core/loop/limit_masks.h"
#include "core/loop/limit_stencil.h"
#include "core/loop/local_ring.h"
#include "core/mesh/sharpness.h"

namespace tessera {

namespace {

Vec3 apply(const std::vector<double>& mask, std::span<const Vec3> ring) {
  Vec3 sum(0, 0, 0);
  for (size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] != 0.0) sum += mask[i] * ring[i];
  }
  return sum;
}

Vec3 unit(const Vec3& a) {
  const double len2 = a.sqrnorm();
  return len2 > 0.0 ? (1.0 / std::sqrt(len2)) * a : Vec3(0, 0, 0);
}

// Area-weighted normal of the ring faces firstEdge .. firstEdge+count-1,
// read from the ring points (centre first): only used to orient a normal
// where the surface has no tangent plane.
Vec3 faceNormalSum(std::span<const Vec3> ring, int firstEdge, int count, int n) {
  Vec3 sum(0, 0, 0);
  for (int k = firstEdge; k < firstEdge + count; ++k) {
    const Vec3& a = ring[1 + k % n];
    const Vec3& b = ring[1 + (k + 1) % n];
    sum += (a - ring[0]) % (b - ring[0]);
  }
  return sum;
}

Vec3 sectorNormal(const SectorMasks& sector, std::span<const Vec3> ring, int n) {
  switch (sector.kind) {
    case SectorMasks::Kind::kTangentPlane:
    case SectorMasks::Kind::kDominantAndCrease:
      return unit(apply(sector.tangent1, ring) % apply(sector.tangent2, ring));
    case SectorMasks::Kind::kBoundingCurves: {
      // A reflex sector (wider than a half turn) flips the cross product of
      // its bounding directions: its faces decide the side.
      const Vec3 planes = apply(sector.tangent1, ring) % apply(sector.tangent2, ring);
      const Vec3 faces = faceNormalSum(ring, sector.firstEdge, sector.faceCount, n);
      return unit(dot(planes, faces) > 0.0 ? planes : faces);
    }
    case SectorMasks::Kind::kConeAxis: {
      const Vec3 axis = apply(sector.tangent1, ring);
      const Vec3 faces = faceNormalSum(ring, sector.firstEdge, sector.faceCount, n);
      return unit(dot(axis, faces) >= 0.0 ? axis : -1.0 * axis);
    }
  }
  return Vec3(0, 0, 0);
}

// tangent1: `along` in the plane normal to `normal` (any direction there if
// `along` is normal to it); tangent2 = normal x tangent1 of the same length,
// so that tangent1 x tangent2 = |tangent1|^2 normal.
void completeFrame(const Vec3& normal, const Vec3& along, LimitFrame& frame) {
  if (normal.sqrnorm() == 0.0) {
    frame.tangent1 = frame.tangent2 = Vec3(0, 0, 0);
    return;
  }
  Vec3 t = along - dot(along, normal) * normal;
  if (t.sqrnorm() <= 1e-24 * std::max(along.sqrnorm(), 1e-300)) {
    const Vec3 axis = std::abs(normal[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    t = axis - dot(axis, normal) * normal;
    t = std::sqrt(std::max(along.sqrnorm(), 1.0) / t.sqrnorm()) * t;
  }
  frame.tangent1 = t;
  frame.tangent2 = normal % t;
}

// The stationary sector holding ring face k.
const SectorMasks& sectorOfFace(const StationaryMasks& masks, int k, int n) {
  for (const SectorMasks& s : masks.sectors) {
    int offset = k - s.firstEdge;  // both in [0, n): no division needed
    if (offset < 0) offset += n;
    if (offset < s.faceCount) return s;
  }
  return masks.sectors.front();
}

}  // namespace

std::vector<int> sharpRingEdges(const Level& level, Index v) {
  std::vector<int> sharp;
  auto ring = level.ringEdgesOf(v);
  for (int k = 0; k < static_cast<int>(ring.size()); ++k) {
    if (isSharp(level.edgeSharpness[ring[k]])) sharp.push_back(k);
  }
  return sharp;
}

namespace {

bool stationaryAtLevel(const Level& level, Index v) {
  if (isSemiSharp(level.vertexSharpness[v])) return false;
  for (Index e : level.ringEdgesOf(v)) {
    if (isSemiSharp(level.edgeSharpness[e])) return false;
  }
  return true;
}

// The masks of a ring whose rules no longer change, through a per-thread
// map keyed by a packed word (valence, boundary, rule, sharp edges) in front
// of the process-wide cache, so the common case takes no lock and no
// allocation. Cached masks are never evicted, so the raw pointers stay
// valid; masks the full cache did not keep are held here until the next
// call on this thread, which outlives every use in this file.
const StationaryMasks& masksFor(int n, bool boundary, VertexRule rule, const std::vector<bool>& sharp) {
  constexpr int kPackedValence = 52;
  thread_local std::shared_ptr<const StationaryMasks> held;
  uint64_t key = 0;
  thread_local std::unordered_map<uint64_t, const StationaryMasks*> local;
  if (n <= kPackedValence) {
    key = static_cast<uint64_t>(n) | (boundary ? 1ull << 6 : 0) | (static_cast<uint64_t>(rule) << 7);
    for (int k = 0; k < n; ++k) key |= sharp[k] ? 1ull << (12 + k) : 0;
    auto it = local.find(key);
    if (it != local.end()) return *it->second;
  }
  bool cached = false;
  held = stationaryMasks({n, boundary, rule, sharp}, &cached);
  if (cached && n <= kPackedValence) local.emplace(key, held.get());
  return *held;
}

// What every use of a vertex's exact limit starts from: the masks, the
// ring points they weigh (the level's ring, or the stationary ring its
// semi-sharp features decay into), how much of the centre each point holds,
// and this level's sharp ring edges with the primary sector among them.
// The spans point into per-thread storage, valid until the next call.
struct RingLimit {
  int valence = 0;
  const StationaryMasks* masks = nullptr;
  // The masks weigh the level's own ring (not a decayed one).
  bool weighsLevelRing = false;
  std::span<const Vec3> points;
  std::span<const double> centreWeight;
  std::span<const int> sharp;
  bool sided = false;
  int primary = 0;
  const SectorMasks* primarySector = nullptr;
};

RingLimit ringLimit(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method,
                    const FarRingSharpness* far) {
  const int n = level.valence(v);
  thread_local std::vector<bool> sharpEdges;
  thread_local std::vector<Vec3> ringPoints;
  thread_local std::vector<double> centreWeight;
  sharpEdges.assign(n, false);
  // The masks, and the ring points they weigh: the level's own ring, or
  // the stationary ring its semi-sharp features decay into.
  const StationaryMasks* masks = nullptr;
  bool weighsLevelRing = true;
  auto gatherLevelRing = [&] {
    auto ringV = level.ringVerticesOf(v);
    ringPoints.resize(n + 1);
    ringPoints[0] = points[v];
    for (int k = 0; k < n; ++k) ringPoints[1 + k] = points[ringV[k]];
    centreWeight.assign(n + 1, 0.0);
    centreWeight[0] = 1.0;
  };
  if (stationaryAtLevel(level, v)) {
    // The common case: the ring's points as they are.
    gatherLevelRing();
    auto ringE = level.ringEdgesOf(v);
    for (int k = 0; k < n; ++k) sharpEdges[k] = isSharp(level.edgeSharpness[ringE[k]]);
    masks = &masksFor(n, level.isBoundaryVertex(v), level.vertexRules[v], sharpEdges);
  } else if (const DecayMatrix* decay = cachedDecayMatrix(level, v, points, method, far)) {
    // Semi-sharp features left: the ring's steps until they decay, as one
    // cached matrix (decay_matrix.h).
    gatherLevelRing();
    if (decay->composedSuffices) {
      // The stationary masks composed with the decay weigh the level's ring.
      masks = &decay->composed;
    } else {
      weighsLevelRing = false;
      thread_local std::vector<Vec3> levelRing;
      levelRing.assign(ringPoints.begin(), ringPoints.end());
      decay->apply(levelRing, ringPoints);
      for (int i = 0; i <= n; ++i) centreWeight[i] = decay->weights[static_cast<size_t>(i) * (n + 1)];
      for (int k = 0; k < n; ++k) sharpEdges[k] = decay->sharpEdges[k];
      masks = &masksFor(n, decay->boundary, decay->rule, sharpEdges);
    }
  } else {
    // The cache is full: refine the ring here until its features decay.
    weighsLevelRing = false;
    thread_local LocalRing rings[2];
    gatherLocalRing(level, v, points, method, rings[0], far);
    const LocalRing& ring = rings[refineUntilStationary(rings, method) % 2];
    for (int k = 0; k < n; ++k) sharpEdges[k] = isSharp(ring.edgeSharpness[k]);
    ringPoints.assign(ring.points.begin(), ring.points.end());
    centreWeight.assign(ring.centreWeight.begin(), ring.centreWeight.end());
    masks = &masksFor(n, ring.boundary, ring.rule, sharpEdges);
  }
  RingLimit out;
  out.valence = n;
  out.masks = masks;
  out.weighsLevelRing = weighsLevelRing;
  out.points = ringPoints;
  out.centreWeight = centreWeight;
  // The sectors of this level (limit.h's numbering), each with the normal
  // of the stationary sector it lies in: sharpness never grows, so each of
  // this level's sectors lies inside one.
  const VertexRule rule = level.vertexRules[v];
  thread_local std::vector<int> sharp;
  sharp.clear();
  {
    auto ringE = level.ringEdgesOf(v);
    for (int k = 0; k < n; ++k) {
      if (isSharp(level.edgeSharpness[ringE[k]])) sharp.push_back(k);
    }
  }
  out.sharp = sharp;
  const int m = static_cast<int>(sharp.size());
  out.sided = !isSmoothLike(rule) && m >= 2;
  out.primary = !out.sided ? 0 : ((rule == VertexRule::kCrease || sharp[0] == 0) ? 0 : m - 1);
  out.primarySector = &sectorOfFace(*masks, out.sided ? sharp[out.primary] : 0, n);
  return out;
}

}  // namespace

VertexLimit exactVertexLimit(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method,
                             bool withOtherSides, const FarRingSharpness* far) {
  const RingLimit ring = ringLimit(level, v, points, method, far);
  const StationaryMasks& masks = *ring.masks;
  const std::span<const Vec3> p = ring.points;
  const std::span<const int> sharp = ring.sharp;
  const int n = ring.valence;
  const int m = static_cast<int>(sharp.size());

  VertexLimit out;
  out.position = apply(masks.position, p);
  out.selfWeight = 0.0;
  for (size_t i = 0; i < masks.position.size(); ++i)
    out.selfWeight += masks.position[i] * ring.centreWeight[i];

  const Vec3 normal = sectorNormal(*ring.primarySector, p, n);
  out.frame.position = out.position;
  Vec3 along = apply(ring.primarySector->tangent1, p);
  if (level.vertexRules[v] == VertexRule::kCrease) {
    // Along the crease, first to second sharp edge, at OpenSubdiv's scale:
    // exactly the crease curve's tangent while it is infinitely sharp.
    auto ringV = level.ringVerticesOf(v);
    along = 1.5 * (points[ringV[sharp[0]]] - points[ringV[sharp[1]]]);
  }
  completeFrame(normal, along, out.frame);
  if (!ring.sided || !withOtherSides) return out;
  const bool levelBoundary = level.isBoundaryVertex(v);
  for (int i = 0; i < m; ++i) {
    if (i == ring.primary) continue;
    const bool wraps = i + 1 == m;
    if (wraps && levelBoundary) continue;
    const int from = sharp[i];
    const int to = wraps ? sharp[0] + n : sharp[i + 1];
    out.others.push_back({from, to - from, sectorNormal(sectorOfFace(masks, from, n), p, n)});
  }
  return out;
}

void exactLimitPositionAndNormal(const Level& level, Index v, std::span<const Vec3> points,
                                 CreaseMethod method, Vec3& position, Vec3& normal,
                                 const FarRingSharpness* far) {
  LimitStencilKey key;
  const bool keyed = method == CreaseMethod::kUniform && limitStencilKey(level, v, key);
  const LimitStencil* stencil = keyed ? findLimitStencil(key) : nullptr;
  if (stencil != nullptr && !stencil->position.empty()) {
    // The same sums, in the same order, as apply() and sectorNormal().
    auto ringV = level.ringVerticesOf(v);
    const Vec3& centre = points[v];
    Vec3 p = stencil->position[0] * centre, t1 = stencil->tangent1[0] * centre,
         t2 = stencil->tangent2[0] * centre;
    for (size_t k = 0; k < ringV.size(); ++k) {
      const Vec3& q = points[ringV[k]];
      p += stencil->position[1 + k] * q;
      t1 += stencil->tangent1[1 + k] * q;
      t2 += stencil->tangent2[1 + k] * q;
    }
    position = p;
    normal = unit(t1 % t2);
    return;
  }
  const RingLimit ring = ringLimit(level, v, points, method, far);
  position = apply(ring.masks->position, ring.points);
  normal = sectorNormal(*ring.primarySector, ring.points, ring.valence);
  // Done unless the configuration is keyable and new (an empty stencil
  // marks one known to need this path).
  if (!keyed || stencil != nullptr) return;
  // A new configuration: keep its masks over the level's ring, or an empty
  // stencil where the normal is not a cross product of two of them.
  const bool linear = ring.weighsLevelRing && ring.primarySector->normalIsCrossProduct();
  insertLimitStencil(key, linear ? LimitStencil{ring.masks->position, ring.primarySector->tangent1,
                                                ring.primarySector->tangent2}
                                 : LimitStencil{});
}

}  // namespace tessera
