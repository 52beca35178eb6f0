// One level of the sparse hierarchy (Pulli & Lounsbery, "Hierarchical Editing
// and Rendering of Subdivision Surfaces" §4.1): the faces of a uniform
// level that the forest of quadtrees actually holds, with local indices so
// that the Loop stencils, limit masks and frames of core/loop run on it
// unchanged, and each element's canonical id (hierarchy/ids.h) alongside.
//
// A vertex is *complete* when its whole ring of faces is present; only
// complete vertices carry an ordered ring, and only they may be refined,
// evaluated at the limit or given a frame. The ring of an incomplete vertex
// lists just its present faces (ringFaces, ringFaceLocal; its ring edges
// and vertices are kNoIndex), which is what the incremental update
// needs to find the stencils a changed vertex enters. An edge whose face
// exists in the uniform level but not here has kAbsentFace in edgeFaces, so
// it is never mistaken for a boundary.
//
// Local numbering follows the uniform one restricted to what is present
// (children of parent vertices first, then vertices on parent edges; edge
// halves before interior edges; faces four per refined parent face), so the
// canonical ids of every kind come out ascending and lookups are binary
// searches.
#pragma once

#include <cstdint>
#include <span>

#include "core/hierarchy/ids.h"
#include "core/loop/loop_options.h"
#include "core/topology/level.h"
#include "core/util/buffer.h"

namespace tessera {

inline constexpr Index kAbsentFace = -2;

struct SparseLevel {
  int depth = 0;  // the subdivision level
  Level mesh;
  Buffer<uint64_t> vertexIds, edgeIds, faceIds;  // canonical indices, ascending
  Buffer<uint8_t> complete;                      // per vertex

  // Where each vertex came from: vertices [0, numVertexChildren) are the
  // children of parent vertex origin[v], the rest lie on parent edge origin[v].
  Index numVertexChildren = 0;
  Buffer<Index> origin;
  Buffer<Index> faceParent;  // per group of four child faces: the parent face
  // Set when the next level is built, kNoIndex where there is no child:
  Buffer<Index> firstChildFace;  // per face: the first of its 4 consecutive children
  Buffer<Index> childOfVertex;   // per vertex: its child vertex
  Buffer<Index> childOfEdge;     // per edge: the vertex on it
  Buffer<Index> halvesOfEdge;    // per edge: the first of its two consecutive halves

  Index findVertex(uint64_t canonical) const;  // kNoIndex if not present
  Index findEdge(uint64_t canonical) const;
  Index findFace(uint64_t canonical) const;
  bool isComplete(Index v) const { return complete[v] != 0; }
  bool isRefined(Index f) const { return firstChildFace[f] != kNoIndex; }

  size_t memoryBytes() const;
};

// Level 0 holds every base face; every vertex is complete.
SparseLevel sparseBaseLevel(Level base);

// Refines the faces of `parent` flagged in `refine` (one flag per face).
// Every vertex of a refined face must be complete. Sharpness and rules are
// inherited from the parent (sharpness_inheritance.h); tags set on the new
// level are applied by the caller. Sets parent.firstChildFace.
SparseLevel refineSparse(SparseLevel& parent, std::span<const uint8_t> refine, const LevelCounts& counts,
                         const LoopOptions& options);

}  // namespace tessera
