#include "core/loop/refinement.h"

#include <algorithm>
#include <vector>

#include "core/loop/sharpness_inheritance.h"

namespace tessera {

namespace {

// Parent face f's split in the uniform numbering (the header's).
FaceSplit uniformSplit(const Level& parent, Index f) {
  const Index nV = parent.numVertices;
  const auto& fe = parent.faceEdges[f];
  FaceSplit split;
  split.corners = parent.faceVertices[f];
  for (int j = 0; j < 3; ++j) {
    split.midpoints[j] = nV + fe[j];
    split.halves[j] = 2 * fe[j];
  }
  split.firstInterior = 2 * parent.numEdges() + 3 * f;
  split.firstFace = 4 * f;
  split.sides = parent.faceEdgeSides[f];
  return split;
}

// Child numbering and orientation (see level.h): child 2e runs
// (edgeVertices[e][0], m) and child 2e+1 runs (m, edgeVertices[e][1]), so
// the "edgeFaces[0] runs [0] to [1]" invariant holds at every level and no
// refinement step has to search a face for a vertex or an edge.
void refineFacesAndEdges(const Level& parent, Level& child) {
  const Index nV = parent.numVertices;
  const Index nE = parent.numEdges();
  const Index nF = parent.numFaces();

  child.numVertices = nV + nE;
  child.faceVertices.resize(4 * nF);
  child.faceEdges.resize(4 * nF);
  child.faceEdgeSides.resize(4 * nF);
  child.edgeVertices.resize(2 * nE + 3 * nF);
  child.edgeFaces.resize(2 * nE + 3 * nF);
  child.edgeFaceLocal.resize(2 * nE + 3 * nF);

  for (Index e = 0; e < nE; ++e) {
    const auto& ev = parent.edgeVertices[e];
    const auto& ef = parent.edgeFaces[e];
    splitEdge(2 * e, ev[0], nV + e, ev[1], {4 * ef[0], ef[1] == kInvalidIndex ? kInvalidIndex : 4 * ef[1]},
              parent.edgeFaceLocal[e], child);
  }
  for (Index f = 0; f < nF; ++f) splitFace(uniformSplit(parent, f), child);
}

// Faces only, for a last level that is interpolated and drawn, not refined.
void refineFaceVertices(const Level& parent, Level& child) {
  const Index nF = parent.numFaces();
  child.numVertices = parent.numVertices + parent.numEdges();
  child.faceVertices.resize(4 * nF);
  for (Index f = 0; f < nF; ++f) {
    FaceSplit split;
    split.corners = parent.faceVertices[f];
    for (int j = 0; j < 3; ++j) split.midpoints[j] = parent.numVertices + parent.faceEdges[f][j];
    split.firstFace = 4 * f;
    splitFaceVertices(split, child);
  }
}

void refineRings(const Level& parent, Level& child) {
  const Index nV = parent.numVertices;
  const Index nE = parent.numEdges();
  const Index firstInterior = 2 * nE;

  child.ringOffsets.resize(child.numVertices + 1);
  child.ringOffsets[0] = 0;
  for (Index v = 0; v < nV; ++v) child.ringOffsets[v + 1] = child.ringOffsets[v] + parent.valence(v);
  for (Index e = 0; e < nE; ++e) {
    child.ringOffsets[nV + e + 1] = child.ringOffsets[nV + e] + (parent.isBoundaryEdge(e) ? 4 : 6);
  }
  const Index total = child.ringOffsets[child.numVertices];
  child.ringEdges.resize(total);
  child.ringVertices.resize(total);
  child.ringFaces.resize(total);
  child.ringFaceLocal.resize(total);

  // A vertex keeps its ring order; each entry becomes the child at v, and v
  // keeps its corner index in the corner child of each face.
  for (Index v = 0; v < nV; ++v) {
    const Index from = parent.ringOffsets[v], to = parent.ringOffsets[v + 1];
    const Index out = child.ringOffsets[v];
    for (Index k = from; k < to; ++k) {
      const Index e = parent.ringEdges[k];
      const Index f = parent.ringFaces[k];
      child.ringEdges[out + k - from] = childEdgeAtEnd(parent, e, v);
      child.ringVertices[out + k - from] = nV + e;
      child.ringFaces[out + k - from] = f == kInvalidIndex ? kInvalidIndex : 4 * f + parent.ringFaceLocal[k];
      child.ringFaceLocal[out + k - from] = parent.ringFaceLocal[k];
    }
  }

  // A new edge vertex m: its ring starts in the edge's face 0 (which runs the
  // edge from its vertex 0 to 1, locals j to j+1) at the half towards vertex
  // 1, crosses that face's three children, then those of face 1 -- the order
  // OpenSubdiv's TriRefinement produces.
  for (Index e = 0; e < nE; ++e) {
    const Index o = child.ringOffsets[nV + e];
    Index* ringE = child.ringEdges.data() + o;
    Index* ringV = child.ringVertices.data() + o;
    Index* ringF = child.ringFaces.data() + o;
    uint8_t* ringL = child.ringFaceLocal.data() + o;
    const auto& ev = parent.edgeVertices[e];
    const Index fA = parent.edgeFaces[e][0];
    const int j = parent.edgeFaceLocal[e][0];
    const int jn = (j + 1) % 3, jp = (j + 2) % 3;
    const Index iA = firstInterior + 3 * fA;
    const auto& feA = parent.faceEdges[fA];
    ringE[0] = 2 * e + 1, ringV[0] = ev[1], ringF[0] = 4 * fA + jn, ringL[0] = static_cast<uint8_t>(j);
    ringE[1] = iA + jn, ringV[1] = nV + feA[jn], ringF[1] = 4 * fA + 3, ringL[1] = static_cast<uint8_t>(jp);
    ringE[2] = iA + j, ringV[2] = nV + feA[jp], ringF[2] = 4 * fA + j, ringL[2] = static_cast<uint8_t>(jn);
    ringE[3] = 2 * e, ringV[3] = ev[0];
    const Index fB = parent.edgeFaces[e][1];
    if (fB == kInvalidIndex) {
      ringF[3] = kInvalidIndex, ringL[3] = 0;
      continue;
    }
    const int k = parent.edgeFaceLocal[e][1];
    const int kn = (k + 1) % 3, kp = (k + 2) % 3;
    const Index iB = firstInterior + 3 * fB;
    const auto& feB = parent.faceEdges[fB];
    ringF[3] = 4 * fB + kn, ringL[3] = static_cast<uint8_t>(k);
    ringE[4] = iB + kn, ringV[4] = nV + feB[kn], ringF[4] = 4 * fB + 3, ringL[4] = static_cast<uint8_t>(kp);
    ringE[5] = iB + k, ringV[5] = nV + feB[kp], ringF[5] = 4 * fB + k, ringL[5] = static_cast<uint8_t>(kn);
  }
  child.maxValence = std::max(parent.maxValence, 6);
}

void refineSharpness(const Level& parent, const LoopOptions& options, Level& child) {
  const Index nV = parent.numVertices;
  const Index nE = parent.numEdges();
  // Halves of parent edges come first; interior edges are always smooth.
  child.edgeSharpness.assign(child.fullTopology ? child.numEdges() : 2 * nE, kSharpnessSmooth);
  child.vertexSharpness.resize(child.numVertices);
  child.vertexRules.resize(child.numVertices);

  SharpnessInheritance inherit(parent, options);
  for (Index e = 0; e < nE; ++e) {
    child.vertexSharpness[nV + e] = kSharpnessSmooth;
    child.vertexRules[nV + e] = inherit.edgeChildRule(e);
    if (isSmooth(parent.edgeSharpness[e])) continue;
    for (int end = 0; end < 2; ++end) child.edgeSharpness[2 * e + end] = inherit.halfSharpness(e, end);
  }
  for (Index v = 0; v < nV; ++v) {
    child.vertexSharpness[v] = inherit.vertexChildSharpness(v);
    child.vertexRules[v] = inherit.vertexChildRule(v);
  }
}

}  // namespace

Level refineLevel(const Level& parent, const LoopOptions& options, RefineDetail detail) {
  Level child;
  if (detail == RefineDetail::kFull) {
    refineFacesAndEdges(parent, child);
    refineRings(parent, child);
  } else {
    child.fullTopology = false;
    refineFaceVertices(parent, child);
    child.maxValence = std::max(parent.maxValence, 6);
  }
  refineSharpness(parent, options, child);
  return child;
}

}  // namespace tessera
