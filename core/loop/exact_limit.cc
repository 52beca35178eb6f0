#include "core/loop/exact_limit.h"

#include <algorithm>
#include <cassert>
#include <cmath>

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

VertexLimit exactVertexLimit(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method) {
  const int n = level.valence(v);
  LocalRing ring = gatherLocalRing(level, v, points, method);
  for (int step = 0; !ring.isStationary(); ++step) {
    assert(step < kMaxDecaySteps);
    if (step >= kMaxDecaySteps) break;
    ring = refineLocalRing(ring, method);
  }
  StationaryRing stationary{n, ring.boundary, ring.rule, std::vector<bool>(n)};
  for (int k = 0; k < n; ++k) stationary.sharpEdges[k] = isSharp(ring.edgeSharpness[k]);
  const std::shared_ptr<const StationaryMasks> masks = stationaryMasks(stationary);
  const std::span<const Vec3> p(ring.points);

  VertexLimit out;
  out.position = apply(masks->position, p);
  out.selfWeight = 0.0;
  for (size_t i = 0; i < masks->position.size(); ++i) out.selfWeight += masks->position[i] * ring.centreWeight[i];

  // The sectors of this level (limit.h's numbering), each with the normal
  // of the stationary sector it lies in: sharpness never grows, so each of
  // this level's sectors lies inside one.
  const VertexRule rule = level.vertexRules[v];
  const std::vector<int> sharp = sharpRingEdges(level, v);
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
  if (!sided) return out;
  const bool boundary = level.isBoundaryVertex(v);
  for (int i = 0; i < m; ++i) {
    if (i == primary) continue;
    const bool wraps = i + 1 == m;
    if (wraps && boundary) continue;
    const int from = sharp[i];
    const int to = wraps ? sharp[0] + n : sharp[i + 1];
    out.others.push_back({from, to - from, sectorNormal(sectorOfFace(*masks, from, n), p, n)});
  }
  return out;
}

}  // namespace tessera
