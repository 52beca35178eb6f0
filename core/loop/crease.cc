#include "core/loop/crease.h"

#include <cassert>

namespace tessera {

float decrementSharpness(float s) {
  if (isSmooth(s)) return kSharpnessSmooth;
  if (isInfinite(s)) return kSharpnessInfinite;
  return s > 1.0f ? s - 1.0f : kSharpnessSmooth;
}

float subdivideEdgeSharpnessAtVertex(CreaseMethod method, float edgeSharpness,
                                     std::span<const float> sharpnessAtVertex) {
  if (method == CreaseMethod::kUniform || sharpnessAtVertex.size() < 2) {
    return decrementSharpness(edgeSharpness);
  }
  if (isSmooth(edgeSharpness)) return kSharpnessSmooth;
  if (isInfinite(edgeSharpness)) return kSharpnessInfinite;

  // Chaikin: 3/4 of this edge plus 1/4 of the mean of the other semi-sharp
  // edges at the vertex, so sharpness varies smoothly along a crease.
  float sum = 0.0f;
  int count = 0;
  for (float s : sharpnessAtVertex) {
    if (isSemiSharp(s)) {
      sum += s;
      ++count;
    }
  }
  float s = edgeSharpness;
  if (count > 1) s = 0.75f * s + 0.25f * ((sum - edgeSharpness) / static_cast<float>(count - 1));
  s -= 1.0f;
  return isSharp(s) ? s : kSharpnessSmooth;
}

float fractionalWeightAtVertex(float parentVertexSharpness, float childVertexSharpness,
                               std::span<const float> parentEdgeSharpness,
                               std::span<const float> childEdgeSharpness) {
  assert(parentEdgeSharpness.size() == childEdgeSharpness.size());
  int count = 0;
  float sum = 0.0f;
  if (isSharp(parentVertexSharpness) && isSmooth(childVertexSharpness)) {
    count = 1;
    sum = parentVertexSharpness;
  }
  for (size_t i = 0; i < parentEdgeSharpness.size(); ++i) {
    if (isSharp(parentEdgeSharpness[i]) && isSmooth(childEdgeSharpness[i])) {
      sum += parentEdgeSharpness[i];
      ++count;
    }
  }
  if (count == 0) return 0.0f;
  float w = sum / static_cast<float>(count);
  return w > 1.0f ? 1.0f : w;
}

void sharpEdgePair(std::span<const float> edgeSharpness, int ends[2]) {
  int found = 0;
  ends[0] = ends[1] = 0;
  for (int i = 0; i < static_cast<int>(edgeSharpness.size()) && found < 2; ++i) {
    if (isSharp(edgeSharpness[i])) ends[found++] = i;
  }
  assert(found == 2);
}

}  // namespace tessera
