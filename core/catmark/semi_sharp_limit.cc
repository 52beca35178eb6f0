#include "core/catmark/semi_sharp_limit.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <unordered_map>
#include <vector>

#include "core/catmark/interpolate.h"
#include "core/catmark/quad_split.h"
#include "core/loop/crease.h"
#include "core/mesh/sharpness.h"

namespace tessera {

namespace {

// Sharpness decays by at least 1 a level (Sdc), and is semi-sharp below
// kSharpnessInfinite: this many steps leave none.
constexpr int kMaxDecaySteps = 11;

struct RingPatch {
  PolyTopology topology;
  std::vector<Vec3> points;
  std::vector<Index> global;  // patch vertex -> the level's; v is patch vertex 0
};

// The patch's numbering of v's ring: v, then its faces' corners as they
// come. The cached weights are over these slots, so ringPatch numbers its
// vertices by them too.
void patchSlots(const Level& level, Index v, std::vector<Index>& slots) {
  slots.assign(1, v);
  for (Index f : level.ringFacesOf(v)) {
    if (f == kNoIndex) continue;
    for (Index x : level.faceVerticesOf(f))
      if (std::find(slots.begin(), slots.end(), x) == slots.end()) slots.push_back(x);
  }
}

// The faces around v with their corners, numbered as patchSlots (v is 0);
// the sharpness of v and of its edges. buildPolyLevel refuses it where a
// corner repeats.
RingPatch ringPatch(const Level& level, Index v, const std::function<Vec3(Index)>& pointOf) {
  RingPatch patch;
  patchSlots(level, v, patch.global);
  auto localOf = [&](Index x) {
    return static_cast<int>(std::find(patch.global.begin(), patch.global.end(), x) - patch.global.begin());
  };
  std::vector<int> face;
  for (Index f : level.ringFacesOf(v)) {
    if (f == kNoIndex) continue;
    face.clear();
    for (Index x : level.faceVerticesOf(f)) face.push_back(localOf(x));
    patch.topology.addFace(face);
  }
  const auto ringVertices = level.ringVerticesOf(v);
  const auto ringEdges = level.ringEdgesOf(v);
  for (size_t k = 0; k < ringEdges.size(); ++k) {
    const Index e = ringEdges[k];
    // A boundary edge is the patch's boundary too, whose rule the options give.
    if (level.edgeFaces[e][1] == kNoIndex) continue;
    const float s = level.edgeSharpness[e];
    if (s > kSharpnessSmooth) patch.topology.creases.push_back({0, localOf(ringVertices[k]), s});
  }
  patch.topology.numVertices = static_cast<int>(patch.global.size());
  patch.topology.vertexSharpness.assign(patch.global.size(), kSharpnessSmooth);
  if (!level.vertexSharpness.empty()) patch.topology.vertexSharpness[0] = level.vertexSharpness[v];
  for (Index x : patch.global) patch.points.push_back(pointOf(x));
  return patch;
}

// Per patch vertex, the sharpness of every edge at it in the whole mesh:
// what Chaikin's decay of a semi-sharp ring edge reads at its far end.
// Filled for the far ends of v's semi-sharp edges only.
using FarEdges = std::vector<std::vector<float>>;

// Chaikin's far halves, which the patch, holding none of the far vertex's
// other edges, cannot decay: each semi-sharp ring edge's far half decayed
// from `far` into `child` (splitToQuads' numbering), the rule of the vertex
// on the edge from both halves (Vtr's reclassification, as splitSharpness
// makes it), and that vertex's own edges for the next step.
FarEdges decayFarHalves(const Level& current, const FarEdges& far, Level& child) {
  FarEdges next(static_cast<size_t>(child.numVertices));
  const Index corners = static_cast<Index>(current.faceVertices.size());
  for (Index e : current.ringEdgesOf(0)) {
    const float s = current.edgeSharpness[e];
    if (!isSemiSharp(s)) continue;
    const int farEnd = current.edgeVertices[e][0] == 0 ? 1 : 0;
    const Index w = current.edgeVertices[e][farEnd];
    const float farHalf =
        subdivideEdgeSharpnessAtVertex(CreaseMethod::kChaikin, s, far[static_cast<size_t>(w)]);
    const float nearHalf = child.edgeSharpness[corners + 2 * e + (1 - farEnd)];
    child.edgeSharpness[corners + 2 * e + farEnd] = farHalf;
    const Index m = edgeChildVertex(current, e);
    child.vertexRules[m] =
        vertexRule(kSharpnessSmooth, (isSharp(nearHalf) ? 1 : 0) + (isSharp(farHalf) ? 1 : 0));
    // Its other edges lie inside the edge's faces, born smooth.
    next[static_cast<size_t>(m)] = {nearHalf, farHalf};
  }
  return next;
}

// The ring once its features decayed: the last patch (v is its vertex 0)
// and its points, and where v's ring faces went: per position k of v's
// ring in the level, the position in the patch's ring of 0 of the face
// that descends from ring face k at v (the boundary's gap to the gap).
struct DecayedRing {
  Level level;
  std::vector<Vec3> points;
  std::vector<int> ringPosition;
};

// Position of patch face `face` (kNoIndex: the boundary's gap) in the ring
// of vertex 0.
int ringPositionOf(const Level& patch, Index face) {
  const auto ring = patch.ringFacesOf(0);
  return static_cast<int>(std::find(ring.begin(), ring.end(), face) - ring.begin());
}

// The patch face (ringPatch numbers faces as the ring of 0 holds them,
// skipping the gap) of child face `face` of `child`, or kNoIndex.
Index patchFaceOf(const Level& child, Index face) {
  if (face == kNoIndex) return kNoIndex;
  Index patchFace = 0;
  for (Index f : child.ringFacesOf(0)) {
    if (f == face) return patchFace;
    if (f != kNoIndex) ++patchFace;
  }
  return kNoIndex;
}

std::optional<DecayedRing> refineUntilDecayed(const Level& level, Index v,
                                              const std::function<Vec3(Index)>& pointOf,
                                              const CreaseOptions& options,
                                              const FarRingSharpness* farSource) {
  const bool chaikin = options.creaseMethod == CreaseMethod::kChaikin;
  RingPatch patch = ringPatch(level, v, pointOf);
  auto built = buildPolyLevel(patch.topology, options);
  if (!built.isOk() || !built->allQuads()) return std::nullopt;
  Level current = std::move(*built);
  std::vector<Vec3> points = std::move(patch.points);
  // Per position of v's ring, the patch face at v that descends from it.
  std::vector<Index> tracked;
  Index patchFace = 0;
  for (Index f : level.ringFacesOf(v)) tracked.push_back(f == kNoIndex ? kNoIndex : patchFace++);
  FarEdges far(static_cast<size_t>(current.numVertices));
  if (chaikin) {
    const auto ringVertices = level.ringVerticesOf(v);
    const auto ringEdges = level.ringEdgesOf(v);
    for (size_t k = 0; k < ringEdges.size(); ++k) {
      if (!isSemiSharp(level.edgeSharpness[ringEdges[k]])) continue;
      const auto local = std::find(patch.global.begin(), patch.global.end(), ringVertices[k]);
      farRingSharpness(level, ringVertices[k], farSource,
                       far[static_cast<size_t>(local - patch.global.begin())]);
    }
  }
  for (int step = 0; step < kMaxDecaySteps && hasUndecayedSemiSharpness(current, 0); ++step) {
    // The vertex is vertex 0 of each patch, and a vertex's child keeps its
    // index (quad_split.h).
    Level child = splitToQuads(current, options, SplitDetail::kFull);
    FarEdges childFar;
    if (chaikin) childFar = decayFarHalves(current, far, child);
    std::vector<Vec3> childPoints(static_cast<size_t>(child.numVertices));
    interpolateCatmark(current, child, points, childPoints);
    // A face's child at corner j is faceBegin + j (quad_split.h).
    for (Index& f : tracked) {
      if (f == kNoIndex) continue;
      const auto corners = current.faceVerticesOf(f);
      const auto j = std::find(corners.begin(), corners.end(), Index{0}) - corners.begin();
      f = patchFaceOf(child, current.faceBegin(f) + static_cast<Index>(j));
    }
    RingPatch next = ringPatch(child, 0, [&](Index x) { return childPoints[static_cast<size_t>(x)]; });
    built = buildPolyLevel(next.topology, options);
    if (!built.isOk()) return std::nullopt;
    current = std::move(*built);
    points = std::move(next.points);
    far.assign(static_cast<size_t>(current.numVertices), {});
    if (chaikin) {
      for (size_t local = 0; local < next.global.size(); ++local)
        far[local] = std::move(childFar[static_cast<size_t>(next.global[local])]);
    }
  }
  if (hasUndecayedSemiSharpness(current, 0)) return std::nullopt;
  DecayedRing ring{std::move(current), std::move(points), {}};
  for (Index f : tracked) ring.ringPosition.push_back(ringPositionOf(ring.level, f));
  return ring;
}

// Per position of v's ring, the side it lies on in the decayed ring
// (limitSideOfRingFace's numbering there).
std::vector<int> sidesOf(const DecayedRing& ring) {
  std::vector<int> sides;
  for (int position : ring.ringPosition) sides.push_back(limitSideOfRingFace(ring.level, 0, position));
  return sides;
}

// The decayed limit is linear in the ring's points (every step and the
// masks are), so it is kept as weights over the patch's points (its slots,
// ringPatch's order: v, then its faces' corners as they come), per
// configuration: everything the refinement reads besides the points. A
// vertex then costs a key, a lookup and three dot products over the ring, as
// Loop's composed decay matrices do (core/loop/decay_matrix.h). Every call
// goes through the weights, found or computed, so a limit never depends on
// what the cache held.
struct DecayedWeights {
  bool exact = false;  // false: the ring could not be rebuilt, Limit()'s masks stay
  std::vector<double> position, tangent1, tangent2;  // per slot
  // Per position of v's ring, its side once decayed: limitSideOfRingFace
  // of the decayed ring. Topological, so it is part of the configuration.
  std::vector<int> sides;
};

uint32_t bitsOf(float s) {
  uint32_t b;
  std::memcpy(&b, &s, sizeof b);
  return b;
}

// What the refinement reads besides the points: the options, the ring's
// faces (their corners, as slots), the sharpness of v and of its edges, and
// under Chaikin's decay the far ends' edges, in the order the decay sums
// them.
void configurationKey(const Level& level, Index v, std::span<const Index> slots, const CreaseOptions& options,
                      const FarRingSharpness* far, std::vector<uint32_t>& key) {
  key.clear();
  key.push_back(static_cast<uint32_t>(options.creaseMethod) * 16 + static_cast<uint32_t>(options.boundary));
  key.push_back(bitsOf(level.vertexSharpness.empty() ? kSharpnessSmooth : level.vertexSharpness[v]));
  auto slotOf = [&](Index x) {
    return static_cast<uint32_t>(std::find(slots.begin(), slots.end(), x) - slots.begin());
  };
  for (Index f : level.ringFacesOf(v)) {
    if (f == kNoIndex) {
      key.push_back(0xffffffffu);
      continue;
    }
    const auto corners = level.faceVerticesOf(f);
    key.push_back(static_cast<uint32_t>(corners.size()));
    for (Index x : corners) key.push_back(slotOf(x));
  }
  const auto ringVertices = level.ringVerticesOf(v);
  const auto ringEdges = level.ringEdgesOf(v);
  thread_local std::vector<float> farEdges;
  for (size_t k = 0; k < ringEdges.size(); ++k) {
    const Index e = ringEdges[k];
    key.push_back(slotOf(ringVertices[k]));
    key.push_back(level.edgeFaces[e][1] == kNoIndex ? 0xffffffffu : bitsOf(level.edgeSharpness[e]));
    if (options.creaseMethod != CreaseMethod::kChaikin || !isSemiSharp(level.edgeSharpness[e])) continue;
    farRingSharpness(level, ringVertices[k], far, farEdges);
    key.push_back(static_cast<uint32_t>(farEdges.size()));
    for (float x : farEdges) key.push_back(bitsOf(x));
  }
}

struct KeyHash {
  size_t operator()(const std::vector<uint32_t>& key) const {
    uint64_t h = 1469598103934665603ull;  // FNV-1a over the words
    for (uint32_t w : key) h = (h ^ w) * 1099511628211ull;
    return static_cast<size_t>(h);
  }
};

DecayedWeights computeWeights(const Level& level, Index v, std::span<const Index> slots,
                              const CreaseOptions& options, const FarRingSharpness* far) {
  DecayedWeights w;
  const size_t n = slots.size();
  w.position.assign(n, 0.0);
  w.tangent1.assign(n, 0.0);
  w.tangent2.assign(n, 0.0);
  // Three slots at a time: slot `first + k` is the unit point along axis k.
  for (size_t first = 0; first < n; first += 3) {
    auto ring = refineUntilDecayed(
        level, v,
        [&](Index x) {
          Vec3 p(0, 0, 0);
          for (size_t k = 0; k < 3 && first + k < n; ++k)
            if (slots[first + k] == x) p[static_cast<int>(k)] = 1.0;
          return p;
        },
        options, far);
    if (!ring) return DecayedWeights{};
    const CatmarkLimitFrame frame = catmarkLimitFrame(ring->level, 0, ring->points, options);
    if (first == 0) w.sides = sidesOf(*ring);
    for (size_t k = 0; k < 3 && first + k < n; ++k) {
      w.position[first + k] = frame.position[static_cast<int>(k)];
      w.tangent1[first + k] = frame.tangent1[static_cast<int>(k)];
      w.tangent2[first + k] = frame.tangent2[static_cast<int>(k)];
    }
  }
  w.exact = true;
  return w;
}

// Per thread, so a lookup takes no lock. Cleared when it outgrows its
// bound: a document's tags make few configurations, and a miss costs only
// the refinement again.
constexpr size_t kWeightsCacheEntries = 1 << 14;

const DecayedWeights& decayedWeights(const Level& level, Index v, std::span<const Index> slots,
                                     const CreaseOptions& options, const FarRingSharpness* far) {
  thread_local std::unordered_map<std::vector<uint32_t>, DecayedWeights, KeyHash> cache;
  thread_local std::vector<uint32_t> key;
  configurationKey(level, v, slots, options, far, key);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  if (cache.size() >= kWeightsCacheEntries) cache.clear();
  return cache.emplace(key, computeWeights(level, v, slots, options, far)).first->second;
}

}  // namespace

bool hasUndecayedSemiSharpness(const Level& level, Index v) {
  if (!level.vertexSharpness.empty() && isSemiSharp(level.vertexSharpness[v])) return true;
  for (Index e : level.ringEdgesOf(v))
    if (isSemiSharp(level.edgeSharpness[e])) return true;
  return false;
}

bool takesDecayedLimit(const Level& level, Index v, const CreaseOptions&) {
  return hasUndecayedSemiSharpness(level, v);
}

std::optional<CatmarkLimitFrame> decayedLimitFrame(const Level& level, Index v, std::span<const Vec3> points,
                                                   const CreaseOptions& options,
                                                   const FarRingSharpness* far) {
  thread_local std::vector<Index> slots;
  patchSlots(level, v, slots);
  const DecayedWeights& w = decayedWeights(level, v, slots, options, far);
  if (!w.exact) return std::nullopt;
  CatmarkLimitFrame frame{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0)};
  for (size_t k = 0; k < slots.size(); ++k) {
    const Vec3& p = points[static_cast<size_t>(slots[k])];
    frame.position += w.position[k] * p;
    frame.tangent1 += w.tangent1[k] * p;
    frame.tangent2 += w.tangent2[k] * p;
  }
  return frame;
}

std::optional<double> decayedSelfLimitWeight(const Level& level, Index v, const CreaseOptions& options,
                                             const FarRingSharpness* far) {
  thread_local std::vector<Index> slots;
  patchSlots(level, v, slots);
  const DecayedWeights& w = decayedWeights(level, v, slots, options, far);
  if (!w.exact) return std::nullopt;
  return w.position[0];  // slot 0 is v
}

std::optional<int> decayedSideOfRingFace(const Level& level, Index v, int ringFace,
                                         const CreaseOptions& options, const FarRingSharpness* far) {
  thread_local std::vector<Index> slots;
  patchSlots(level, v, slots);
  const DecayedWeights& w = decayedWeights(level, v, slots, options, far);
  if (!w.exact) return std::nullopt;
  return w.sides[static_cast<size_t>(ringFace)];
}

std::optional<std::vector<LimitSector>> decayedOtherLimitSectors(const Level& level, Index v,
                                                                 std::span<const Vec3> points,
                                                                 const CreaseOptions& options,
                                                                 const FarRingSharpness* far) {
  auto ring = refineUntilDecayed(
      level, v, [&](Index x) { return points[static_cast<size_t>(x)]; }, options, far);
  if (!ring) return std::nullopt;
  std::vector<LimitSector> sectors = catmarkOtherLimitSectors(ring->level, 0, ring->points, options);
  // Renumber each side's faces into v's ring at this level: the run of
  // positions that lie on it, which is contiguous (sides are bounded by
  // sharp edges, and the decayed ring's are v's infinitely sharp ones).
  const std::vector<int> sides = sidesOf(*ring);
  const int n = static_cast<int>(sides.size());
  for (size_t j = 0; j < sectors.size(); ++j) {
    const int side = static_cast<int>(j) + 1;
    LimitSector& sector = sectors[j];
    sector.faceCount = static_cast<int>(std::count(sides.begin(), sides.end(), side));
    sector.firstFace = 0;
    for (int k = 0; k < n; ++k) {
      if (sides[k] == side && sides[(k + n - 1) % n] != side) sector.firstFace = k;
    }
  }
  return sectors;
}

}  // namespace tessera
