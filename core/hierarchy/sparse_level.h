// One level of the sparse hierarchy (Pulli & Lounsbery, "Hierarchical Editing
// and Rendering of Subdivision Surfaces" §4.1): the faces of a uniform
// level that the forest of quadtrees actually holds, with local indices so
// that the Loop stencils, limit masks and frames of core/loop run on it
// unchanged, and each element's canonical id (hierarchy/ids.h) alongside.
//
// A vertex is *complete* when its whole ring of faces is present; only
// complete vertices carry an ordered ring, and only they may be refined,
// evaluated at the limit or given a frame. The ring of an incomplete vertex
// lists its present faces (ringFaces, ringFaceLocal; its ring edges and
// vertices are kNoIndex), which is what the incremental update needs to
// find the stencils a changed vertex enters, then kAbsentFace up to the
// size of its whole ring: every row is as long as the ring it will hold,
// so growth in place fills rows where they are. An edge whose face
// exists in the uniform level but not here has kAbsentFace in edgeFaces, so
// it is never mistaken for a boundary.
//
// A level is split from its parent by the document's scheme: Loop's 1-to-4
// triangle split (sparse_triangle_split.cc) or Catmull-Clark's quad split
// (sparse_quad_split.cc), numbered as LevelCounts says (hierarchy/ids.h;
// docs/ARCHITECTURE.md "Numbering"). A freshly built level numbers what is
// present as the uniform level does (triangles: children of parent
// vertices first, then vertices on parent edges; edge halves before
// interior edges; faces four per refined parent face. Quads: children of
// parent vertices, then vertices in parent faces, then on parent edges;
// interior edges before halves; faces one per corner of a refined parent
// face), so its canonical ids come out ascending. Growth in place
// (extendSparse) appends what its newly refined parents add, so a grown
// level's ids are ascending only through its order arrays, which lookups
// search; local indices, once given, never change while the level lives.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/hierarchy/ids.h"
#include "core/loop/loop_options.h"
#include "core/topology/level.h"
#include "core/util/buffer.h"

namespace tessera {

inline constexpr Index kAbsentFace = -2;

struct SparseLevel {
  int depth = 0;  // the subdivision level
  Level mesh;
  Buffer<uint64_t> vertexIds, edgeIds, faceIds;  // canonical indices
  // Local indices by ascending canonical id; empty while the ids themselves
  // ascend (a level as built, before it grew in place).
  Buffer<Index> vertexOrder, edgeOrder, faceOrder;
  Buffer<uint8_t> complete;  // per vertex

  // Where each vertex came from (LevelCounts::Origin): the child of parent
  // vertex origin[v], the vertex on parent edge origin[v], or (quads) the
  // vertex in parent face origin[v]. Level 0 has none.
  Buffer<Index> origin;
  Buffer<uint8_t> originKind;
  // The parent face of child face f is faceParent[f / facesPerParent]: one
  // entry per four children where every refined parent face has four (every
  // level of triangles or quads), one per child below a base level of other
  // polygons.
  Buffer<Index> faceParent;
  int facesPerParent = 4;
  // Set when the next level is built, kNoIndex where there is no child:
  Buffer<Index> firstChildFace;  // per face: the first of its consecutive children, child j at corner j
  Buffer<Index> childOfVertex;   // per vertex: its child vertex
  Buffer<Index> childOfEdge;     // per edge: the vertex on it
  Buffer<Index> halvesOfEdge;    // per edge: the first of its two consecutive halves
  Buffer<Index> childOfFace;     // per face, quad split only: the vertex in it

  Index findVertex(uint64_t canonical) const;  // kNoIndex if not present
  Index findEdge(uint64_t canonical) const;
  Index findFace(uint64_t canonical) const;
  bool isComplete(Index v) const { return complete[v] != 0; }
  // Whether vertex v (depth > 0) is the child of a parent vertex.
  bool isVertexChild(Index v) const {
    return originKind[v] == static_cast<uint8_t>(LevelCounts::Origin::kVertex);
  }
  bool isFaceChild(Index v) const {
    return originKind[v] == static_cast<uint8_t>(LevelCounts::Origin::kFace);
  }
  Index parentOfFace(Index f) const { return faceParent[facesPerParent == 4 ? f >> 2 : f]; }
  bool isRefined(Index f) const { return firstChildFace[f] != kNoIndex; }

  size_t memoryBytes() const;
};

// Level 0 holds every base face; every vertex is complete.
SparseLevel sparseBaseLevel(Level base);

// Refines the faces of `parent` flagged in `refine` (one flag per face) by
// the split `counts` names. Every vertex of a refined face must be complete. Sharpness and rules are
// inherited from the parent (sharpness_inheritance.h); tags set on the new
// level are applied by the caller. Sets parent.firstChildFace.
SparseLevel refineSparse(SparseLevel& parent, std::span<const uint8_t> refine, const LevelCounts& counts,
                         const LoopOptions& options);

// What growing a level in place added: its vertices from firstNewVertex on
// are new, and `completed` lists every vertex that is complete now and was
// not before (the new complete ones included), ascending.
struct LevelExtension {
  Index firstNewVertex = 0;
  std::vector<Index> completed;
};

// Grows `child`, the level refineSparse made of `parent`, in place by the
// children of parent faces `faces` (ascending, none refined yet, every
// vertex of each complete): their vertices, edges and
// faces are appended, the edges and rings they touch are completed, and
// nothing present changes its local index or value. Updates parent's child
// links. The same level refineSparse would build with every flagged face,
// but in another local order.
LevelExtension extendSparse(SparseLevel& parent, SparseLevel& child, std::span<const Index> faces,
                            const LevelCounts& counts, const LoopOptions& options);

}  // namespace tessera
