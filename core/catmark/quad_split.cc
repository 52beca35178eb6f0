#include "core/catmark/quad_split.h"

#include <algorithm>
#include <vector>

#include "core/loop/crease.h"
#include "core/topology/quad_split_parts.h"

namespace tessera {

namespace {

using topology::quadEdgeVertexValence;
using topology::splitQuadEdge;
using topology::splitQuadFace;
using topology::splitQuadFaceEdges;
using topology::writeQuadEdgeVertexRing;
using topology::writeQuadFaceVertexRing;
using topology::writeQuadVertexChildRing;

// The uniform numbering of quad_split.h, arithmetic.
struct UniformQuadLinks {
  Index numVertices, numFaces, corners;
  const Level& parent;
  Index vertexChild(Index v) const { return v; }
  Index faceVertex(Index f) const { return numVertices + f; }
  Index edgeVertex(Index e) const { return numVertices + numFaces + e; }
  Index halves(Index e) const { return corners + 2 * e; }
  Index firstFace(Index f) const { return parent.faceBegin(f); }
  Index interior(Index f) const { return parent.faceBegin(f); }
};

UniformQuadLinks uniformLinks(const Level& parent) {
  return {parent.numVertices, parent.numFaces(), static_cast<Index>(parent.faceVertices.size()), parent};
}

void splitFaces(const Level& parent, Level& child, bool withEdges) {
  const UniformQuadLinks links = uniformLinks(parent);
  child.faceVertices.resize(4 * static_cast<size_t>(links.corners));
  if (withEdges) child.faceEdges.resize(4 * static_cast<size_t>(links.corners));
  for (Index f = 0; f < links.numFaces; ++f) splitQuadFace(parent, f, links, withEdges, child);
}

void splitEdges(const Level& parent, Level& child) {
  const UniformQuadLinks links = uniformLinks(parent);
  const Index nE = parent.numEdges();
  child.edgeVertices.resize(links.corners + 2 * nE);
  child.edgeFaces.resize(links.corners + 2 * nE);
  child.edgeFaceLocal.resize(links.corners + 2 * nE);
  for (Index f = 0; f < links.numFaces; ++f) splitQuadFaceEdges(parent, f, links, child);
  for (Index e = 0; e < nE; ++e) splitQuadEdge(parent, e, links, kNoIndex, child);
}

void splitRings(const Level& parent, Level& child) {
  const UniformQuadLinks links = uniformLinks(parent);
  const Index nV = parent.numVertices;
  const Index nF = parent.numFaces();
  const Index nE = parent.numEdges();
  const Index firstEdgeVertex = nV + nF;

  child.ringOffsets.resize(child.numVertices + 1);
  Index* offsets = child.ringOffsets.data();
  offsets[0] = 0;
  for (Index v = 0; v < nV; ++v) offsets[v + 1] = offsets[v] + parent.valence(v);
  for (Index f = 0; f < nF; ++f) offsets[nV + f + 1] = offsets[nV + f] + parent.faceSize(f);
  for (Index e = 0; e < nE; ++e) {
    offsets[firstEdgeVertex + e + 1] = offsets[firstEdgeVertex + e] + quadEdgeVertexValence(parent, e);
  }
  const Index total = offsets[child.numVertices];
  child.ringEdges.resize(total);
  child.ringVertices.resize(total);
  child.ringFaces.resize(total);
  child.ringFaceLocal.resize(total);
  Index* rE = child.ringEdges.data();
  Index* rV = child.ringVertices.data();
  Index* rF = child.ringFaces.data();
  LocalIndex* rL = child.ringFaceLocal.data();
  for (Index v = 0; v < nV; ++v) {
    const Index at = offsets[v];
    writeQuadVertexChildRing(parent, v, links, rE + at, rV + at, rF + at, rL + at);
  }
  for (Index f = 0; f < nF; ++f) {
    const Index at = offsets[nV + f];
    writeQuadFaceVertexRing(parent, f, links, rE + at, rV + at, rF + at, rL + at);
  }
  for (Index e = 0; e < nE; ++e) {
    const Index at = offsets[firstEdgeVertex + e];
    writeQuadEdgeVertexRing(parent, e, links, rE + at, rV + at, rF + at, rL + at);
  }
}

// Sharpness and rules of the child (Vtr's subdivideEdgeSharpness,
// subdivideVertexSharpness and reclassifySemisharpVertices).
void splitSharpness(const Level& parent, const CreaseOptions& options, Level& child) {
  const Index nV = parent.numVertices;
  const Index nF = parent.numFaces();
  const Index nE = parent.numEdges();
  const Index corners = static_cast<Index>(parent.faceVertices.size());
  child.edgeSharpness.resize(corners + 2 * nE);
  std::fill(child.edgeSharpness.begin(), child.edgeSharpness.begin() + corners, kSharpnessSmooth);
  child.vertexSharpness.resize(child.numVertices);
  child.vertexRules.resize(child.numVertices);

  std::vector<float> ring(static_cast<size_t>(parent.maxValence));
  const bool chaikin = options.creaseMethod == CreaseMethod::kChaikin;
  for (Index e = 0; e < nE; ++e) {
    const float s = parent.edgeSharpness[e];
    float halves[2] = {kSharpnessSmooth, kSharpnessSmooth};
    if (isSharp(s)) {
      for (int end = 0; end < 2; ++end) {
        if (chaikin && isSemiSharp(s)) {
          const Index x = parent.edgeVertices[e][end];
          parent.ringSharpness(x, ring.data());
          halves[end] = subdivideEdgeSharpnessAtVertex(options.creaseMethod, s,
                                                       std::span(ring.data(), parent.valence(x)));
        } else {
          halves[end] = decrementSharpness(s);
        }
      }
    }
    child.edgeSharpness[corners + 2 * e] = halves[0];
    child.edgeSharpness[corners + 2 * e + 1] = halves[1];
    const Index m = nV + nF + e;
    child.vertexSharpness[m] = kSharpnessSmooth;
    child.vertexRules[m] =
        isSharp(s) ? vertexRule(kSharpnessSmooth, (isSharp(halves[0]) ? 1 : 0) + (isSharp(halves[1]) ? 1 : 0))
                   : VertexRule::kSmooth;
  }
  for (Index f = 0; f < nF; ++f) {
    child.vertexSharpness[nV + f] = kSharpnessSmooth;
    child.vertexRules[nV + f] = VertexRule::kSmooth;
  }
  for (Index v = 0; v < nV; ++v) {
    const float s = decrementSharpness(parent.vertexSharpness[v]);
    child.vertexSharpness[v] = s;
    if (parent.vertexRules[v] == VertexRule::kSmooth) {
      child.vertexRules[v] = VertexRule::kSmooth;
      continue;
    }
    int sharp = 0;
    for (Index e : parent.ringEdgesOf(v)) {
      sharp +=
          isSharp(child.edgeSharpness[corners + 2 * e + (parent.edgeVertices[e][0] == v ? 0 : 1)]) ? 1 : 0;
    }
    child.vertexRules[v] = vertexRule(s, sharp);
  }
}

}  // namespace

Level splitToQuads(const Level& parent, const CreaseOptions& options, SplitDetail detail) {
  Level child;
  child.numVertices = parent.numVertices + parent.numFaces() + parent.numEdges();
  child.maxFaceSize = 4;
  child.regularFaceSize = 4;  // no face offsets (core/topology/level.h)
  child.maxValence = std::max({parent.maxValence, parent.maxFaceSize, 4});
  const bool full = detail == SplitDetail::kFull;
  child.fullTopology = full;
  splitFaces(parent, child, full);
  if (full) {
    splitEdges(parent, child);
    splitRings(parent, child);
  }
  splitSharpness(parent, options, child);
  return child;
}

}  // namespace tessera
