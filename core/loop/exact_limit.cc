#include "core/loop/exact_limit.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <unordered_map>

#include "core/loop/limit_masks.h"
#include "core/loop/local_ring.h"
#include "core/mesh/sharpness.h"

namespace tessera {

namespace {

// Sharpness below 10 decays by at least 1 per level (Chaikin's average never
// exceeds the largest), so 10 steps reach the stationary rules.
constexpr int kMaxDecaySteps = 12;

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
    if ((k - s.firstEdge + n) % n < s.faceCount) return s;
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
// allocation. Masks are never evicted, so the raw pointers stay valid.
const StationaryMasks& masksFor(int n, bool boundary, VertexRule rule, const std::vector<bool>& sharp) {
  constexpr int kPackedValence = 52;
  if (n <= kPackedValence) {
    uint64_t key = static_cast<uint64_t>(n) | (boundary ? 1ull << 6 : 0) | (static_cast<uint64_t>(rule) << 7);
    for (int k = 0; k < n; ++k) key |= sharp[k] ? 1ull << (12 + k) : 0;
    thread_local std::unordered_map<uint64_t, const StationaryMasks*> local;
    auto it = local.find(key);
    if (it != local.end()) return *it->second;
    const StationaryMasks* masks = stationaryMasks({n, boundary, rule, sharp}).get();
    local.emplace(key, masks);
    return *masks;
  }
  return *stationaryMasks({n, boundary, rule, sharp});
}

}  // namespace

VertexLimit exactVertexLimit(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method,
                             bool withOtherSides) {
  const int n = level.valence(v);
  thread_local std::vector<bool> sharpEdges;
  thread_local std::vector<Vec3> ringPoints;
  thread_local std::vector<double> centreWeight;
  sharpEdges.assign(n, false);
  bool boundary = level.isBoundaryVertex(v);
  VertexRule finalRule = level.vertexRules[v];
  if (stationaryAtLevel(level, v)) {
    // The common case: the ring's points as they are.
    auto ringE = level.ringEdgesOf(v);
    auto ringV = level.ringVerticesOf(v);
    ringPoints.resize(n + 1);
    ringPoints[0] = points[v];
    centreWeight.assign(n + 1, 0.0);
    centreWeight[0] = 1.0;
    for (int k = 0; k < n; ++k) {
      ringPoints[1 + k] = points[ringV[k]];
      sharpEdges[k] = isSharp(level.edgeSharpness[ringE[k]]);
    }
  } else {
    // Semi-sharp features left: refine the ring alone until they decay.
    thread_local LocalRing rings[2];
    int at = 0;
    gatherLocalRing(level, v, points, method, rings[0]);
    for (int step = 0; !rings[at].isStationary(); ++step) {
      assert(step < kMaxDecaySteps);
      if (step >= kMaxDecaySteps) break;
      refineLocalRing(rings[at], method, rings[1 - at]);
      at = 1 - at;
    }
    const LocalRing& ring = rings[at];
    for (int k = 0; k < n; ++k) sharpEdges[k] = isSharp(ring.edgeSharpness[k]);
    ringPoints.assign(ring.points.begin(), ring.points.end());
    centreWeight.assign(ring.centreWeight.begin(), ring.centreWeight.end());
    boundary = ring.boundary;
    finalRule = ring.rule;
  }
  const StationaryMasks& stationary = masksFor(n, boundary, finalRule, sharpEdges);
  const StationaryMasks* masks = &stationary;
  const std::span<const Vec3> p(ringPoints);

  VertexLimit out;
  out.position = apply(masks->position, p);
  out.selfWeight = 0.0;
  for (size_t i = 0; i < masks->position.size(); ++i) out.selfWeight += masks->position[i] * centreWeight[i];

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
  const int m = static_cast<int>(sharp.size());
  const bool sided = !isSmoothLike(rule) && m >= 2;
  const int primary = !sided ? 0 : ((rule == VertexRule::kCrease || sharp[0] == 0) ? 0 : m - 1);
  const int primaryFirstFace = sided ? sharp[primary] : 0;
  const SectorMasks& primarySector = sectorOfFace(*masks, primaryFirstFace, n);
  const Vec3 normal = sectorNormal(primarySector, p, n);
  out.frame.position = out.position;
  Vec3 along = apply(primarySector.tangent1, p);
  if (rule == VertexRule::kCrease) {
    // Along the crease, first to second sharp edge, at OpenSubdiv's scale:
    // exactly the crease curve's tangent while it is infinitely sharp.
    auto ringV = level.ringVerticesOf(v);
    along = 1.5 * (points[ringV[sharp[0]]] - points[ringV[sharp[1]]]);
  }
  completeFrame(normal, along, out.frame);
  if (!sided || !withOtherSides) return out;
  const bool levelBoundary = level.isBoundaryVertex(v);
  for (int i = 0; i < m; ++i) {
    if (i == primary) continue;
    const bool wraps = i + 1 == m;
    if (wraps && levelBoundary) continue;
    const int from = sharp[i];
    const int to = wraps ? sharp[0] + n : sharp[i + 1];
    out.others.push_back({from, to - from, sectorNormal(sectorOfFace(*masks, from, n), p, n)});
  }
  return out;
}

}  // namespace tessera
