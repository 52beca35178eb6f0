// Random sparse selections for the sparse level tests (header only).
#pragma once

#include <random>
#include <vector>

#include "core/hierarchy/sparse_level.h"

namespace tessera::testing {

// Unrefined faces of `level` whose corners are all complete (those a
// sparse level may refine), each kept with probability `fraction`.
inline std::vector<Index> refinableFaces(const SparseLevel& level, double fraction, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Index> faces;
  for (Index f = 0; f < level.mesh.numFaces(); ++f) {
    bool ok = !level.isRefined(f);
    for (Index v : level.mesh.faceVerticesOf(f)) ok = ok && level.isComplete(v);
    if (ok && unit(rng) < fraction) faces.push_back(f);
  }
  return faces;
}

}  // namespace tessera::testing
