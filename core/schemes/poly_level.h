// PolyLevel: the topology of one level of a polygon mesh as flat index
// arrays, in the manner of OpenSubdiv's Vtr::Level, for the quad-splitting
// schemes (Catmull-Clark, bilinear). Faces may have any number of corners.
//
// Conventions (OpenSubdiv's, so that limit tangents and crease sides agree):
//  * Face edge j joins face corners j and j+1.
//  * A vertex has an ordered ring of n edges e_0..e_{n-1} and faces, counter-
//    clockwise, face f_k lying between e_k (v's outgoing edge in f_k) and
//    e_{k+1} (its incoming edge). A boundary ring starts at the boundary edge
//    that leaves v and has n-1 faces; an interior ring of a base vertex starts
//    at its lowest-numbered face.
//  * Edge faces are listed in the order OpenSubdiv lists them (face index
//    order at level 0, see quad_split.cc for the children).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/loop/crease.h"
#include "core/util/buffer.h"

namespace tessera::schemes {

using Index = int32_t;
using LocalIndex = uint16_t;
inline constexpr Index kNoIndex = -1;
// Corners per face are stored as 16-bit local indices.
inline constexpr int kMaxFaceSize = 65535;

struct PolyLevel {
  int numVertices = 0;
  int maxValence = 0;
  int maxFaceSize = 0;

  // Faces in compressed rows: corners faceOffsets[f] .. faceOffsets[f+1].
  Buffer<Index> faceOffsets;
  Buffer<Index> faceVertices;
  Buffer<Index> faceEdges;  // parallel to faceVertices

  Buffer<std::array<Index, 2>> edgeVertices;
  Buffer<std::array<Index, 2>> edgeFaces;           // [1] is kNoIndex on a boundary
  Buffer<std::array<LocalIndex, 2>> edgeFaceLocal;  // position of the edge in each face

  // Rings in compressed rows: ringOffsets[v] .. ringOffsets[v+1]. ringVertices[k]
  // is the far end of ringEdges[k]; ringFaceLocal[k] is v's corner in ringFaces[k]
  // (the last face of a boundary ring is kNoIndex).
  Buffer<Index> ringOffsets;
  Buffer<Index> ringEdges;
  Buffer<Index> ringVertices;
  Buffer<Index> ringFaces;
  Buffer<LocalIndex> ringFaceLocal;

  Buffer<float> edgeSharpness;
  Buffer<float> vertexSharpness;
  Buffer<VertexRule> vertexRules;

  int numFaces() const { return static_cast<int>(faceOffsets.size()) - 1; }
  int numEdges() const { return static_cast<int>(edgeVertices.size()); }
  int faceSize(Index f) const { return faceOffsets[f + 1] - faceOffsets[f]; }
  std::span<const Index> faceVerticesOf(Index f) const {
    return {faceVertices.data() + faceOffsets[f], static_cast<size_t>(faceSize(f))};
  }
  std::span<const Index> faceEdgesOf(Index f) const {
    return {faceEdges.data() + faceOffsets[f], static_cast<size_t>(faceSize(f))};
  }
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
  bool allQuads() const { return faceVertices.size() == 4 * static_cast<size_t>(numFaces()); }

  // Sharpness of v's ring edges in ring order, into out[0 .. valence).
  void ringSharpness(Index v, float* out) const {
    const Index o = ringOffsets[v];
    for (int k = 0, n = valence(v); k < n; ++k) out[k] = edgeSharpness[ringEdges[o + k]];
  }
};

}  // namespace tessera::schemes
