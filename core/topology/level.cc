#include "core/topology/level.h"

#include <algorithm>

namespace tessera::topology {

void Level::ringSharpness(Index v, float* out) const {
  // A sparse level's incomplete vertex lists its ring edges as kNoIndex
  // (core/hierarchy/sparse_level.h): they count as smooth, never as
  // whatever lies before the array (found by ASan under Chaikin decay,
  // which reads the far vertex's ring of a semi-sharp edge).
  int k = 0;
  for (Index e : ringEdgesOf(v)) out[k++] = e >= 0 ? edgeSharpness[e] : kSharpnessSmooth;
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

}  // namespace tessera::topology
