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

}  // namespace tessera
