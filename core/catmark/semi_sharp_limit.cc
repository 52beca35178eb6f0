#include "core/catmark/semi_sharp_limit.h"

#include <algorithm>
#include <functional>
#include <vector>

#include "core/catmark/interpolate.h"
#include "core/catmark/quad_split.h"
#include "core/mesh/sharpness.h"

namespace tessera {

namespace {

// Sharpness decays by at least 1 a level (Sdc), and is semi-sharp below
// kSharpnessInfinite: this many steps leave none.
constexpr int kMaxDecaySteps = 11;

struct RingPatch {
  PolyTopology topology;
  std::vector<Vec3> points;
};

// The faces around v with their corners, v numbered 0; the sharpness of v
// and of its edges. Nothing where a corner repeats or the faces are no fan.
std::optional<RingPatch> ringPatch(const Level& level, Index v, const std::function<Vec3(Index)>& pointOf) {
  std::vector<Index> global{v};  // local vertex -> the level's
  auto localOf = [&](Index x) {
    auto it = std::find(global.begin(), global.end(), x);
    if (it != global.end()) return static_cast<int>(it - global.begin());
    global.push_back(x);
    return static_cast<int>(global.size()) - 1;
  };
  RingPatch patch;
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
  patch.topology.numVertices = static_cast<int>(global.size());
  patch.topology.vertexSharpness.assign(global.size(), kSharpnessSmooth);
  if (!level.vertexSharpness.empty()) patch.topology.vertexSharpness[0] = level.vertexSharpness[v];
  for (Index x : global) patch.points.push_back(pointOf(x));
  return patch;
}

std::optional<CatmarkLimitFrame> decayed(const Level& level, Index v,
                                         const std::function<Vec3(Index)>& pointOf,
                                         const CreaseOptions& options) {
  if (options.creaseMethod != CreaseMethod::kUniform) return std::nullopt;
  auto patch = ringPatch(level, v, pointOf);
  if (!patch) return std::nullopt;
  auto built = buildPolyLevel(patch->topology, options);
  if (!built.isOk() || !built->allQuads()) return std::nullopt;
  Level current = std::move(*built);
  std::vector<Vec3> points = std::move(patch->points);
  for (int step = 0; step < kMaxDecaySteps && hasUndecayedSemiSharpness(current, 0); ++step) {
    // The vertex is vertex 0 of each patch, and a vertex's child keeps its
    // index (quad_split.h).
    const Level child = splitToQuads(current, options, SplitDetail::kFull);
    std::vector<Vec3> childPoints(static_cast<size_t>(child.numVertices));
    interpolateCatmark(current, child, points, childPoints);
    auto next = ringPatch(child, 0, [&](Index x) { return childPoints[static_cast<size_t>(x)]; });
    if (!next) return std::nullopt;
    built = buildPolyLevel(next->topology, options);
    if (!built.isOk()) return std::nullopt;
    current = std::move(*built);
    points = std::move(next->points);
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

bool takesDecayedLimit(const Level& level, Index v, const CreaseOptions& options) {
  return options.creaseMethod == CreaseMethod::kUniform && hasUndecayedSemiSharpness(level, v);
}

std::optional<CatmarkLimitFrame> decayedLimitFrame(const Level& level, Index v, std::span<const Vec3> points,
                                                   const CreaseOptions& options) {
  return decayed(
      level, v, [&](Index x) { return points[static_cast<size_t>(x)]; }, options);
}

std::optional<double> decayedSelfLimitWeight(const Level& level, Index v, const CreaseOptions& options) {
  auto frame = decayed(
      level, v, [&](Index x) { return x == v ? Vec3(1, 0, 0) : Vec3(0, 0, 0); }, options);
  if (!frame) return std::nullopt;
  return frame->position[0];
}

}  // namespace tessera
