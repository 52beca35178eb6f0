// What the two splits of a sparse level share (sparse_level.h): the order
// arrays of a level's ids, and the rows of its rings. Each split supplies
// its rules for the rings, a type with
//   completeValence(parent, child, links, v)  the valence of child vertex v
//       once its ring is whole, 0 while a face of it is missing;
//   wholeValence(parent, child, v)  the length of v's row, whether the
//       ring is whole yet or not;
//   writeCompleteRing(parent, child, links, v, ringE, ringV, ringF, ringL)
//       v's whole ring in the order the uniform split gives it, so that
//       frames and limit tangents agree with it exactly.
// `links` gives the child numbering: a map while a level is built, the
// parent's child links while it grows in place.
#pragma once

#include <algorithm>
#include <cassert>
#include <vector>

#include "core/hierarchy/sparse_level.h"

namespace tessera::sparse_split {

// The first child of parent face f as the child level's edges and rings
// record it, from a parent-face-to-first-child table: a face the uniform
// level lacks (f < 0) stays what it is; a present face without children
// yet is kAbsentFace, never taken for a boundary (sparse_level.h).
template <typename FirstChildren>
Index firstChildOrAbsent(const FirstChildren& firstChild, Index f) {
  return f < 0 ? f : (firstChild[f] < 0 ? kAbsentFace : firstChild[f]);
}

// Brings `order` (local indices by ascending id; empty: the identity) over
// the ids appended from `first` on.
void mergeOrder(const Buffer<uint64_t>& ids, Index first, Buffer<Index>& order);
// `order` for ids built in a parent's local order, which ascend only while
// the parent's do: empty if they ascend, else their ascending order.
void orderIfUnsorted(const Buffer<uint64_t>& ids, Buffer<Index>& order);

// The rings of a level just built: complete vertices get their whole ring;
// an incomplete vertex lists its present faces, for the incremental update,
// in a row as long as its whole ring (free slots kAbsentFace), so that
// growth in place fills the row where it is.
template <typename Rules, typename Links>
void writeRings(const SparseLevel& parent, const Links& links, const Rules& rules, SparseLevel& child) {
  const Level& p = parent.mesh;
  Level& c = child.mesh;
  child.complete.assign(c.numVertices, 0);
  std::vector<Index> presentFaces(c.numVertices, 0);
  for (Index v : c.faceVertices) ++presentFaces[v];
  c.ringOffsets.resize(c.numVertices + 1);
  c.ringOffsets[0] = 0;
  for (Index v = 0; v < c.numVertices; ++v) {
    child.complete[v] = rules.completeValence(p, child, links, v) > 0;
    c.ringOffsets[v + 1] = c.ringOffsets[v] + rules.wholeValence(p, child, v);
  }
  const Index total = c.ringOffsets[c.numVertices];
  c.ringEdges.resize(total);
  c.ringVertices.resize(total);
  c.ringFaces.resize(total);
  c.ringFaceLocal.resize(total);

  for (Index v = 0; v < c.numVertices; ++v) {
    if (child.complete[v]) continue;
    for (Index slot = c.ringOffsets[v] + presentFaces[v]; slot < c.ringOffsets[v + 1]; ++slot) {
      c.ringEdges[slot] = c.ringVertices[slot] = kNoIndex;
      c.ringFaces[slot] = kAbsentFace;
      c.ringFaceLocal[slot] = 0;
    }
  }
  const int size = c.regularFaceSize;
  for (Index f = 0; f < c.numFaces(); ++f) {
    const Index* fv = c.faceVertices.data() + size * f;
    for (int k = 0; k < size; ++k) {
      const Index v = fv[k];
      if (child.complete[v]) continue;
      const Index slot = c.ringOffsets[v] + --presentFaces[v];
      c.ringEdges[slot] = c.ringVertices[slot] = kNoIndex;
      c.ringFaces[slot] = f;
      c.ringFaceLocal[slot] = static_cast<LocalIndex>(k);
    }
  }
  for (Index v = 0; v < c.numVertices; ++v) {
    if (!child.complete[v]) continue;
    const Index at = c.ringOffsets[v];
    rules.writeCompleteRing(p, child, links, v, c.ringEdges.data() + at, c.ringVertices.data() + at,
                            c.ringFaces.data() + at, c.ringFaceLocal.data() + at);
  }
}

// The rings of a level grown in place by faces from `oldFaces` on and
// vertices from `oldVertices` on. Every row is as long as the vertex's
// whole ring from the start, so none moves. The new vertices' rows are
// appended; the corners of the new faces (none of them was complete, or
// the face would have been present) list them in their free slots, and
// those whose ring is now whole get it written in the uniform order and
// are added to `completed`.
template <typename Rules, typename Links>
void growRings(const SparseLevel& parent, const Links& links, const Rules& rules, Index oldVertices,
               Index oldFaces, SparseLevel& child, std::vector<Index>& completed) {
  const Level& p = parent.mesh;
  Level& c = child.mesh;
  const Index nv = c.numVertices, nf = c.numFaces();
  c.ringOffsets.resize(nv + 1);
  for (Index v = oldVertices; v < nv; ++v)
    c.ringOffsets[v + 1] = c.ringOffsets[v] + rules.wholeValence(p, child, v);
  const Index total = c.ringOffsets[nv];
  c.ringEdges.resize(total, kNoIndex);
  c.ringVertices.resize(total, kNoIndex);
  c.ringFaces.resize(total, kAbsentFace);
  c.ringFaceLocal.resize(total, 0);
  child.complete.resize(nv, 0);
  std::vector<Index> corners;
  const int size = c.regularFaceSize;
  for (Index f = oldFaces; f < nf; ++f) {
    const Index* fv = c.faceVertices.data() + size * f;
    for (int k = 0; k < size; ++k) {
      const Index v = fv[k];
      assert(!child.complete[v] && "a new face at a complete vertex");
      Index slot = c.ringOffsets[v];
      while (c.ringFaces[slot] != kAbsentFace) ++slot;
      assert(slot < c.ringOffsets[v + 1]);
      c.ringFaces[slot] = f;
      c.ringFaceLocal[slot] = static_cast<LocalIndex>(k);
      corners.push_back(v);
    }
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  for (Index v : corners) {
    if (rules.completeValence(p, child, links, v) == 0) continue;
    child.complete[v] = 1;
    completed.push_back(v);
    const Index at = c.ringOffsets[v];
    rules.writeCompleteRing(p, child, links, v, c.ringEdges.data() + at, c.ringVertices.data() + at,
                            c.ringFaces.data() + at, c.ringFaceLocal.data() + at);
  }
}

}  // namespace tessera::sparse_split

namespace tessera {

// The two splits (sparse_triangle_split.cc, sparse_quad_split.cc), which
// refineSparse and extendSparse choose between by LevelCounts::split().
SparseLevel refineSparseTriangles(SparseLevel& parent, std::span<const uint8_t> refine,
                                  const LevelCounts& counts, const LoopOptions& options);
LevelExtension extendSparseTriangles(SparseLevel& parent, SparseLevel& child, std::span<const Index> faces,
                                     const LevelCounts& counts, const LoopOptions& options);
SparseLevel refineSparseQuads(SparseLevel& parent, std::span<const uint8_t> refine, const LevelCounts& counts,
                              const LoopOptions& options);
LevelExtension extendSparseQuads(SparseLevel& parent, SparseLevel& child, std::span<const Index> faces,
                                 const LevelCounts& counts, const LoopOptions& options);

}  // namespace tessera
