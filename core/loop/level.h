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

namespace tessera {

using Index = int32_t;
inline constexpr Index kInvalidIndex = -1;

struct Level {
  int numVertices = 0;

  std::vector<std::array<Index, 3>> faceVertices;
  std::vector<std::array<Index, 3>> faceEdges;
  std::vector<std::array<Index, 2>> edgeVertices;
  std::vector<std::array<Index, 2>> edgeFaces;  // [1] is kInvalidIndex on a boundary

  std::vector<Index> ringOffsets;  // numVertices + 1
  std::vector<Index> ringEdges;
  std::vector<Index> ringFaces;    // parallel to ringEdges

  std::vector<float> edgeSharpness;
  std::vector<float> vertexSharpness;
  std::vector<VertexRule> vertexRules;

  int numFaces() const { return static_cast<int>(faceVertices.size()); }
  int numEdges() const { return static_cast<int>(edgeVertices.size()); }

  int valence(Index v) const { return ringOffsets[v + 1] - ringOffsets[v]; }
  std::span<const Index> ringEdgesOf(Index v) const {
    return {ringEdges.data() + ringOffsets[v], static_cast<size_t>(valence(v))};
  }
  std::span<const Index> ringFacesOf(Index v) const {
    return {ringFaces.data() + ringOffsets[v], static_cast<size_t>(valence(v))};
  }
  bool isBoundaryVertex(Index v) const { return ringFaces[ringOffsets[v + 1] - 1] == kInvalidIndex; }
  bool isBoundaryEdge(Index e) const { return edgeFaces[e][1] == kInvalidIndex; }

  // The end of edge e that is not v.
  Index otherVertex(Index e, Index v) const { return edgeVertices[e][0] ^ edgeVertices[e][1] ^ v; }
  // Local index (0..2) of edge e within face f.
  int edgeInFace(Index f, Index e) const {
    const auto& fe = faceEdges[f];
    return fe[0] == e ? 0 : (fe[1] == e ? 1 : 2);
  }
  // Local index (0..2) of vertex v within face f.
  int vertexInFace(Index f, Index v) const {
    const auto& fv = faceVertices[f];
    return fv[0] == v ? 0 : (fv[1] == v ? 1 : 2);
  }

  // Sharpness of the ring edges of v, in ring order, into `out` (size >= valence).
  void ringSharpness(Index v, float* out) const;
  int maxValence() const;
};

}  // namespace tessera
