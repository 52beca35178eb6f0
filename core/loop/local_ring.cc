#include "core/loop/local_ring.h"

#include <cassert>

#include "core/loop/crease.h"
#include "core/loop/masks.h"
#include "core/mesh/sharpness.h"

namespace tessera {

namespace {

// Sharpness of the child of an edge with sharpness s at an end vertex whose
// ring edges have `ringAtEnd` (SharpnessInheritance::halfSharpness).
float halfAtEnd(float s, std::span<const float> ringAtEnd, CreaseMethod method) {
  if (isSmooth(s)) return kSharpnessSmooth;
  if (method != CreaseMethod::kChaikin || !isSemiSharp(s)) return decrementSharpness(s);
  return subdivideEdgeSharpnessAtVertex(method, s, ringAtEnd);
}

int countSharp(std::span<const float> sharpness) {
  int count = 0;
  for (float s : sharpness) count += isSharp(s) ? 1 : 0;
  return count;
}

// The centre's point under one rule (LoopStencils::vertexPointForRule).
template <typename T>
T centreForRule(VertexRule rule, std::span<const float> ringSharpness, std::span<const T> p) {
  const int n = static_cast<int>(ringSharpness.size());
  switch (rule) {
    case VertexRule::kSmooth:
    case VertexRule::kDart: {
      const double w = loop::smoothEdgeWeight(n);
      T sum = p[1];
      for (int k = 1; k < n; ++k) sum += p[1 + k];
      return (1.0 - n * w) * p[0] + w * sum;
    }
    case VertexRule::kCrease: {
      int ends[2];
      sharpEdgePair(ringSharpness, ends);
      return loop::kCreaseVertexWeight * p[0] +
             loop::kCreaseNeighbourWeight * (p[1 + ends[0]] + p[1 + ends[1]]);
    }
    case VertexRule::kCorner:
      return p[0];
  }
  return p[0];
}

// The points of the next level for one channel (positions or the centre's
// weight), given the sharpness the step decided (LoopStencils::vertexChild
// and edgeChild, read for a lone ring).
template <typename T>
void stepPoints(const LocalRing& ring, std::span<const T> p, const std::vector<float>& halves,
                const std::vector<float>& farHalves, VertexRule childRule, double blend,
                std::vector<T>& out) {
  const int n = ring.valence;
  out.resize(p.size());
  out[0] = centreForRule(ring.rule, std::span<const float>(ring.edgeSharpness), p);
  if (!isSmoothLike(ring.rule) && childRule != ring.rule) {
    out[0] = blend * out[0] + (1.0 - blend) * centreForRule(childRule, std::span<const float>(halves), p);
  }
  for (int k = 0; k < n; ++k) {
    const float s = ring.edgeSharpness[k];
    const T mid = 0.5 * (p[0] + p[1 + k]);
    if (isSharp(s) && isSharp(halves[k]) && isSharp(farHalves[k])) {
      out[1 + k] = mid;
      continue;
    }
    // Boundary ring edges are infinitely sharp and took the branch above.
    assert(!(ring.boundary && (k == 0 || k == n - 1)));
    const T& before = p[1 + (k + n - 1) % n];
    const T& after = p[1 + (k + 1) % n];
    T point = loop::kEdgeEndWeight * (p[0] + p[1 + k]) + loop::kEdgeOppositeWeight * (before + after);
    if (isSharp(s)) point = static_cast<double>(s) * mid + (1.0 - static_cast<double>(s)) * point;
    out[1 + k] = point;
  }
}

}  // namespace

int refineUntilStationary(LocalRing (&rings)[2], CreaseMethod method) {
  int steps = 0;
  for (; !rings[steps % 2].isStationary(); ++steps) {
    assert(steps < kMaxLoneRingDecaySteps);
    if (steps >= kMaxLoneRingDecaySteps) break;
    refineLocalRing(rings[steps % 2], method, rings[1 - steps % 2]);
  }
  return steps;
}

bool LocalRing::isStationary() const {
  if (isSemiSharp(vertexSharpness)) return false;
  for (float s : edgeSharpness) {
    if (isSemiSharp(s)) return false;
  }
  return true;
}

void farRingSharpness(const Level& level, Index u, const FarRingSharpness* far, std::vector<float>& out) {
  if (far != nullptr) return far->edgesAt(u, out);
  out.resize(level.valence(u));
  level.ringSharpness(u, out.data());
}

LocalRing gatherLocalRing(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method,
                          const FarRingSharpness* far) {
  LocalRing ring;
  gatherLocalRing(level, v, points, method, ring, far);
  return ring;
}

void gatherLocalRing(const Level& level, Index v, std::span<const Vec3> points, CreaseMethod method,
                     LocalRing& ring, const FarRingSharpness* farRings) {
  ring.valence = level.valence(v);
  ring.boundary = level.isBoundaryVertex(v);
  ring.rule = level.vertexRules[v];
  ring.vertexSharpness = level.vertexSharpness[v];
  ring.edgeSharpness.resize(ring.valence);
  level.ringSharpness(v, ring.edgeSharpness.data());
  ring.points.assign(1, points[v]);
  ring.centreWeight.assign(1, 1.0);
  auto ringV = level.ringVerticesOf(v);
  auto ringE = level.ringEdgesOf(v);
  ring.farRingSharpness.resize(method == CreaseMethod::kChaikin ? ring.valence : 0);
  for (int k = 0; k < ring.valence; ++k) {
    ring.points.push_back(points[ringV[k]]);
    ring.centreWeight.push_back(0.0);
    if (method == CreaseMethod::kChaikin && isSemiSharp(level.edgeSharpness[ringE[k]])) {
      farRingSharpness(level, ringV[k], farRings, ring.farRingSharpness[k]);
    }
  }
}

LocalRing refineLocalRing(const LocalRing& ring, CreaseMethod method) {
  LocalRing child;
  refineLocalRing(ring, method, child);
  return child;
}

void refineLocalRing(const LocalRing& ring, CreaseMethod method, LocalRing& child) {
  const int n = ring.valence;
  thread_local std::vector<float> halves, farHalves;
  halves.resize(n);
  farHalves.resize(n);
  for (int k = 0; k < n; ++k) {
    const float s = ring.edgeSharpness[k];
    halves[k] = halfAtEnd(s, ring.edgeSharpness, method);
    // Uniform decay reads no ring: both halves decay alike.
    farHalves[k] =
        method == CreaseMethod::kChaikin ? halfAtEnd(s, ring.farRingSharpness[k], method) : halves[k];
  }
  const float childVertexSharpness = decrementSharpness(ring.vertexSharpness);
  // SharpnessInheritance::vertexChildRule: sharpness never grows, so a
  // smooth centre stays smooth.
  const VertexRule childRule = ring.rule == VertexRule::kSmooth
                                   ? VertexRule::kSmooth
                                   : vertexRule(childVertexSharpness, countSharp(halves));
  double blend = 1.0;
  if (!isSmoothLike(ring.rule) && childRule != ring.rule) {
    blend = fractionalWeightAtVertex(ring.vertexSharpness, childVertexSharpness, ring.edgeSharpness, halves);
  }

  child.valence = n;
  child.boundary = ring.boundary;
  child.rule = childRule;
  child.vertexSharpness = childVertexSharpness;
  stepPoints<Vec3>(ring, ring.points, halves, farHalves, childRule, blend, child.points);
  stepPoints<double>(ring, ring.centreWeight, halves, farHalves, childRule, blend, child.centreWeight);
  child.edgeSharpness = halves;
  // The child of ring edge k is a new edge vertex: its ring holds the two
  // halves of edge k and smooth edges inside the faces (4 or 6 in all).
  if (method != CreaseMethod::kChaikin) {
    child.farRingSharpness.clear();
    return;
  }
  child.farRingSharpness.resize(n);
  for (int k = 0; k < n; ++k) {
    const bool boundaryEdge = ring.boundary && (k == 0 || k == n - 1);
    child.farRingSharpness[k] = {halves[k], farHalves[k], 0.0f, 0.0f};
    if (!boundaryEdge) child.farRingSharpness[k].insert(child.farRingSharpness[k].end(), {0.0f, 0.0f});
  }
}

}  // namespace tessera
