#include "core/loop/level.h"

#include <algorithm>

namespace tessera {

void Level::ringSharpness(Index v, float* out) const {
  int k = 0;
  for (Index e : ringEdgesOf(v)) out[k++] = edgeSharpness[e];
}

int Level::computeMaxValence() const {
  int m = 0;
  for (int v = 0; v < numVertices; ++v) m = std::max(m, valence(v));
  return m;
}

void Level::recomputeVertexRules() {
  vertexRules.resize(numVertices);
  for (Index v = 0; v < numVertices; ++v) {
    int sharp = 0;
    for (Index e : ringEdgesOf(v)) sharp += isSharp(edgeSharpness[e]) ? 1 : 0;
    vertexRules[v] = vertexRule(vertexSharpness[v], sharp);
  }
}

}  // namespace tessera
