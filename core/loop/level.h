// Level: the topology of one subdivision level as flat index arrays, in the
// manner of OpenSubdiv's Vtr::Level -- topology kept apart from positions, so
// moving points re-evaluates and never rebuilds it.
//
// Conventions (identical to OpenSubdiv's, so limit tangents agree):
//  * Face edge j joins face vertices j and j+1.
//  * Each vertex has an ordered ring of valence n: edges e_0..e_{n-1} and
//    faces f_0..f_{n-1}, counter-clockwise, where face f_k lies between e_k
//    and e_{k+1} and reads (v, other(e_k), other(e_{k+1})). On a boundary,
//    e_0 and e_{n-1} are the boundary edges and f_{n-1} is kInvalidIndex.
//  * An interior ring of a base vertex starts at its lowest-numbered face.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/loop/crease.h"
#include "core/util/buffer.h"

namespace tessera {

using Index = int32_t;
inline constexpr Index kInvalidIndex = -1;

struct Level {
  int numVertices = 0;
  int maxValence = 0;
  // False for a last level refined with RefineDetail::kFacesOnly: only
  // faceVertices, sharpness and rules are present.
  bool fullTopology = true;

  Buffer<std::array<Index, 3>> faceVertices;
  Buffer<std::array<Index, 3>> faceEdges;
  Buffer<std::array<Index, 2>> edgeVertices;
  Buffer<std::array<Index, 2>> edgeFaces;        // [1] is kInvalidIndex on a boundary
  Buffer<std::array<uint8_t, 2>> edgeFaceLocal;  // position of the edge in each face
  // Bit j set: this face is edgeFaces[1] of its edge j, so it runs that edge
  // from edgeVertices[1] to [0]. (edgeFaces[0] runs it from [0] to [1].)
  Buffer<uint8_t> faceEdgeSides;

  // Rings, in compressed rows: entries ringOffsets[v] .. ringOffsets[v+1].
  // ringVertices[k] is the far end of ringEdges[k], stored because the
  // interpolation and limit loops read it for every vertex; ringFaceLocal[k]
  // is the corner of v within ringFaces[k].
  Buffer<Index> ringOffsets;  // numVertices + 1
  Buffer<Index> ringEdges;
  Buffer<Index> ringVertices;
  Buffer<Index> ringFaces;
  Buffer<uint8_t> ringFaceLocal;

  Buffer<float> edgeSharpness;
  Buffer<float> vertexSharpness;
  Buffer<VertexRule> vertexRules;

  int numFaces() const { return static_cast<int>(faceVertices.size()); }
  int numEdges() const { return static_cast<int>(edgeVertices.size()); }

  int valence(Index v) const { return ringOffsets[v + 1] - ringOffsets[v]; }
  std::span<const Index> ringEdgesOf(Index v) const {
    return {ringEdges.data() + ringOffsets[v], static_cast<size_t>(valence(v))};
  }
  std::span<const Index> ringVerticesOf(Index v) const {
    return {ringVertices.data() + ringOffsets[v], static_cast<size_t>(valence(v))};
  }
  std::span<const Index> ringFacesOf(Index v) const {
    return {ringFaces.data() + ringOffsets[v], static_cast<size_t>(valence(v))};
  }
  bool isBoundaryVertex(Index v) const { return ringFaces[ringOffsets[v + 1] - 1] == kInvalidIndex; }
  bool isBoundaryEdge(Index e) const { return edgeFaces[e][1] == kInvalidIndex; }

  // The end of edge e that is not v.
  Index otherVertex(Index e, Index v) const { return edgeVertices[e][0] ^ edgeVertices[e][1] ^ v; }
  // Local index (0..2) of vertex v within face f.
  int vertexInFace(Index f, Index v) const {
    const auto& fv = faceVertices[f];
    return fv[0] == v ? 0 : (fv[1] == v ? 1 : 2);
  }

  // Sharpness of the ring edges of v, in ring order, into `out` (size >= valence);
  // an absent edge (kInvalidIndex, at an incomplete vertex of a sparse level) is smooth.
  void ringSharpness(Index v, float* out) const;
  int computeMaxValence() const;
  // Rules from the current sharpness (after tags change at this level).
  void recomputeVertexRules();
};

}  // namespace tessera
