// Random sparse selections and quad-split counts for the sparse level
// tests (header only).
#pragma once

#include <random>
#include <vector>

#include "core/hierarchy/ids.h"
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

// The counts of `level`'s quad split (Catmull-Clark) down to `maxLevel`.
inline LevelCounts quadCountsOf(const Level& level, int maxLevel) {
  std::vector<int> sizes;
  for (Index f = 0; f < level.numFaces(); ++f) sizes.push_back(level.faceSize(f));
  return LevelCounts::quads(level.numVertices, level.numEdges(), sizes, maxLevel);
}

}  // namespace tessera::testing
