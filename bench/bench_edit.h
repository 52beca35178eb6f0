// The edits of the edit-to-delta benchmarks (delta_bench.cc,
// codec_compare_bench.cc), so that both time the same kind of edit on the
// same grid: the document's quantization grid around the input mesh, and a
// single-vertex direct manipulation picked at random before the clock
// starts (docs/PERFORMANCE.md).
#pragma once

#include <random>

#include "core/document/document.h"
#include "core/mesh/base_mesh.h"
#include "core/tessellation/quantization_grid.h"

namespace tessera::bench {

// The grid of `mesh`'s bounding box (gridFor's defaults), as a server
// picks a document's grid.
inline Expected<QuantizationGrid> gridAround(const BaseMesh& mesh) {
  Vec3 lo = mesh.positions()[0], hi = lo;
  for (const Vec3& p : mesh.positions()) lo.minimize(p), hi.maximize(p);
  return gridFor(lo, hi);
}

// A vertex of `level`, drawn uniformly with `rng`, and where to drag its
// limit: a small fixed offset from where it is, so the edit changes the
// regions around it and no more.
struct LimitEdit {
  VertexId vertex;
  Vec3 target;
};

inline LimitEdit randomLimitEdit(const Document& doc, int level, std::mt19937& rng) {
  const VertexId v(level, std::uniform_int_distribution<uint64_t>(0, doc.counts().vertices(level) - 1)(rng));
  const Index local = *doc.hierarchy().completeVertex(v);
  const Vec3 limit = doc.hierarchy().limitFrameOf(level, local).position;
  return {v, limit + Vec3(0.002, -0.001, 0.003)};
}

}  // namespace tessera::bench
