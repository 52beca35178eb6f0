#include "core/catmark/semi_sharp_limit.h"

#include <algorithm>
#include <functional>
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

// The faces around v with their corners, v numbered 0; the sharpness of v
// and of its edges. buildPolyLevel refuses it where a corner repeats.
RingPatch ringPatch(const Level& level, Index v, const std::function<Vec3(Index)>& pointOf) {
  RingPatch patch;
  patch.global.push_back(v);
  auto localOf = [&](Index x) {
    auto it = std::find(patch.global.begin(), patch.global.end(), x);
    if (it != patch.global.end()) return static_cast<int>(it - patch.global.begin());
    patch.global.push_back(x);
    return static_cast<int>(patch.global.size()) - 1;
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

std::optional<CatmarkLimitFrame> decayed(const Level& level, Index v,
                                         const std::function<Vec3(Index)>& pointOf,
                                         const CreaseOptions& options, const FarRingSharpness* farSource) {
  const bool chaikin = options.creaseMethod == CreaseMethod::kChaikin;
  RingPatch patch = ringPatch(level, v, pointOf);
  auto built = buildPolyLevel(patch.topology, options);
  if (!built.isOk() || !built->allQuads()) return std::nullopt;
  Level current = std::move(*built);
  std::vector<Vec3> points = std::move(patch.points);
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
  return catmarkLimitFrame(current, 0, points, options);
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
  return decayed(
      level, v, [&](Index x) { return points[static_cast<size_t>(x)]; }, options, far);
}

std::optional<double> decayedSelfLimitWeight(const Level& level, Index v, const CreaseOptions& options,
                                             const FarRingSharpness* far) {
  auto frame = decayed(
      level, v, [&](Index x) { return x == v ? Vec3(1, 0, 0) : Vec3(0, 0, 0); }, options, far);
  if (!frame) return std::nullopt;
  return frame->position[0];
}

}  // namespace tessera
