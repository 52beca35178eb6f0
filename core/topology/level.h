// Level: the topology of one subdivision level as flat index arrays, in the
// manner of OpenSubdiv's Vtr::Level -- topology kept apart from positions, so
// moving points re-evaluates and never rebuilds it. One type serves every
// scheme, as Vtr::Level serves both Vtr::TriRefinement and
// Vtr::QuadRefinement: the Loop levels (core/loop), the sparse Loop levels
// (core/hierarchy) and the polygon levels of Catmull-Clark, bilinear and
// Doo-Sabin (core/schemes). Levels are built by buildLevel (level_builder.h)
// and tagged by applyTags (tags.h); the refinements write them directly.
//
// Faces may have any number of corners (docs/ARCHITECTURE.md
// "core/topology: one topology for every scheme"). Their vertices and
// edges are compressed rows over faceVertices and faceEdges. A level whose
// faces all have one size
// (regularFaceSize: 3 for every Loop level, 4 for every level after a quad
// split) stores no faceOffsets: face f is entries regularFaceSize * f onward,
// so the Loop loops read a triangle at 3f without a lookup (triangleVertices),
// as OpenSubdiv's refiner keeps a regular face size.
//
// Conventions (OpenSubdiv's, so that limit tangents and crease sides agree):
//  * Face edge j joins face corners j and j+1.
//  * A vertex has an ordered ring of n edges e_0..e_{n-1} and faces f_0..,
//    counter-clockwise: face f_k lies between e_k (v's outgoing edge in f_k)
//    and e_{k+1} (its incoming edge). A boundary ring starts at the boundary
//    edge that leaves v; its last face f_{n-1} is kNoIndex.
//  * An interior ring of a base vertex starts at its lowest-numbered face.
//  * Edge faces are listed in face order at level 0; the refinements keep
//    the order OpenSubdiv gives the children (core/loop/refinement.h,
//    core/catmark/quad_split.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "core/mesh/sharpness.h"
#include "core/util/buffer.h"

namespace tessera::topology {

using Index = int32_t;
// A corner or edge position within a face (Vtr's LocalIndex).
using LocalIndex = uint16_t;
inline constexpr Index kNoIndex = -1;
// Positions within a face are LocalIndex values.
inline constexpr int kMaxFaceSize = 65535;

struct Level {
  int numVertices = 0;
  int maxValence = 0;
  int maxFaceSize = 0;
  // Corners of every face when they all have as many, else 0 (faceOffsets
  // then holds numFaces() + 1 row starts).
  int regularFaceSize = 0;
  // False for a last level refined faces-only (core/loop/refinement.h
  // RefineDetail, core/catmark/quad_split.h SplitDetail): only faceVertices,
  // sharpness and rules are present.
  bool fullTopology = true;

  Buffer<Index> faceOffsets;   // empty when regularFaceSize is set
  Buffer<Index> faceVertices;  // corners of each face, counter-clockwise
  Buffer<Index> faceEdges;     // parallel to faceVertices
  // Levels of triangles only: bit j set when the face is edgeFaces[1] of its
  // edge j, so it runs that edge from edgeVertices[1] to [0] (edgeFaces[0]
  // runs it from [0] to [1]). The triangle split reads it to orient halves.
  Buffer<uint8_t> faceEdgeSides;

  Buffer<std::array<Index, 2>> edgeVertices;
  Buffer<std::array<Index, 2>> edgeFaces;           // [1] is kNoIndex on a boundary
  Buffer<std::array<LocalIndex, 2>> edgeFaceLocal;  // position of the edge in each face; 0 where no face

  // Rings in compressed rows: ringOffsets[v] .. ringOffsets[v+1].
  // ringVertices[k] is the far end of ringEdges[k], stored because the
  // interpolation and limit loops read it for every vertex; ringFaceLocal[k]
  // is v's corner in ringFaces[k].
  Buffer<Index> ringOffsets;  // numVertices + 1
  Buffer<Index> ringEdges;
  Buffer<Index> ringVertices;
  Buffer<Index> ringFaces;
  Buffer<LocalIndex> ringFaceLocal;

  Buffer<float> edgeSharpness;
  Buffer<float> vertexSharpness;
  Buffer<VertexRule> vertexRules;

  int numFaces() const {
    switch (regularFaceSize) {
      case 0:
        return static_cast<int>(faceOffsets.size()) - 1;
      case 3:
        return static_cast<int>(faceVertices.size() / 3);
      case 4:
        return static_cast<int>(faceVertices.size() / 4);
      default:
        return static_cast<int>(faceVertices.size() / regularFaceSize);
    }
  }
  int numEdges() const { return static_cast<int>(edgeVertices.size()); }
  int numCorners() const { return static_cast<int>(faceVertices.size()); }

  // Where face f's row starts in faceVertices and faceEdges, and its size.
  Index faceBegin(Index f) const { return regularFaceSize ? regularFaceSize * f : faceOffsets[f]; }
  int faceSize(Index f) const {
    return regularFaceSize ? regularFaceSize : faceOffsets[f + 1] - faceOffsets[f];
  }
  std::span<const Index> faceVerticesOf(Index f) const {
    return {faceVertices.data() + faceBegin(f), static_cast<size_t>(faceSize(f))};
  }
  std::span<const Index> faceEdgesOf(Index f) const {
    return {faceEdges.data() + faceBegin(f), static_cast<size_t>(faceSize(f))};
  }
  // Levels of triangles (regularFaceSize 3): face f's corners and edges.
  std::span<const Index, 3> triangleVertices(Index f) const {
    return std::span<const Index, 3>(faceVertices.data() + 3 * f, 3);
  }
  std::span<const Index, 3> triangleEdges(Index f) const {
    return std::span<const Index, 3>(faceEdges.data() + 3 * f, 3);
  }
  bool allTriangles() const { return regularFaceSize == 3; }
  bool allQuads() const { return regularFaceSize == 4; }

  int valence(Index v) const { return ringOffsets[v + 1] - ringOffsets[v]; }
  std::span<const Index> ringEdgesOf(Index v) const {
    return {ringEdges.data() + ringOffsets[v], static_cast<size_t>(valence(v))};
  }
  std::span<const Index> ringVerticesOf(Index v) const {
    return {ringVertices.data() + ringOffsets[v], static_cast<size_t>(valence(v))};
  }
  // Valence entries; the last is kNoIndex on a boundary.
  std::span<const Index> ringFacesOf(Index v) const {
    return {ringFaces.data() + ringOffsets[v], static_cast<size_t>(valence(v))};
  }
  bool isBoundaryVertex(Index v) const { return ringFaces[ringOffsets[v + 1] - 1] == kNoIndex; }
  bool isBoundaryEdge(Index e) const { return edgeFaces[e][1] == kNoIndex; }
  int numRingFaces(Index v) const { return valence(v) - (isBoundaryVertex(v) ? 1 : 0); }

  // The end of edge e that is not v.
  Index otherVertex(Index e, Index v) const { return edgeVertices[e][0] ^ edgeVertices[e][1] ^ v; }
  // v's corner in face f, or -1 when f does not use v.
  int vertexInFace(Index f, Index v) const {
    if (regularFaceSize == 3) {
      const Index* t = faceVertices.data() + 3 * f;
      return t[0] == v ? 0 : (t[1] == v ? 1 : (t[2] == v ? 2 : -1));
    }
    const std::span<const Index> fv = faceVerticesOf(f);
    for (int j = 0; j < static_cast<int>(fv.size()); ++j) {
      if (fv[j] == v) return j;
    }
    return -1;
  }

  // Sharpness of the ring edges of v, in ring order, into `out` (size >=
  // valence); an absent edge (kNoIndex, at an incomplete vertex of a sparse
  // level, core/hierarchy/sparse_level.h) is smooth.
  void ringSharpness(Index v, float* out) const;
  int computeMaxValence() const;
  // Rules from the current sharpness (after tags change at this level).
  void recomputeVertexRules();
};

}  // namespace tessera::topology

namespace tessera {

// The Loop code, the sparse hierarchy, the documents and the schemes name
// these unqualified in several hundred places; they are the one index type,
// sentinel and level of topology/ (docs/ARCHITECTURE.md).
using topology::Index;
using topology::kNoIndex;
using topology::Level;
using topology::LocalIndex;

}  // namespace tessera
