#include "core/loop/refinement.h"

#include <algorithm>
#include <vector>

#include "core/loop/sharpness_inheritance.h"

namespace tessera {

namespace {

// Child numbering and orientation (see level.h): child 2e runs
// (edgeVertices[e][0], m) and child 2e+1 runs (m, edgeVertices[e][1]), so
// the "edgeFaces[0] runs [0] to [1]" invariant holds at every level and no
// refinement step has to search a face for a vertex or an edge.
void refineFacesAndEdges(const Level& parent, Level& child) {
  const Index nV = parent.numVertices;
  const Index nE = parent.numEdges();
  const Index nF = parent.numFaces();
  const Index firstInterior = 2 * nE;

  child.numVertices = nV + nE;
  child.faceVertices.resize(4 * nF);
  child.faceEdges.resize(4 * nF);
  child.faceEdgeSides.resize(4 * nF);
  child.edgeVertices.resize(2 * nE + 3 * nF);
  child.edgeFaces.resize(2 * nE + 3 * nF);
  child.edgeFaceLocal.resize(2 * nE + 3 * nF);

  for (Index e = 0; e < nE; ++e) {
    const Index m = nV + e;
    const auto& ev = parent.edgeVertices[e];
    const auto& ef = parent.edgeFaces[e];
    const auto& el = parent.edgeFaceLocal[e];
    child.edgeVertices[2 * e] = {ev[0], m};
    child.edgeVertices[2 * e + 1] = {m, ev[1]};
    // A half keeps its parent's slot in the corner child at its end: the
    // corner at end 0 is local j in face 0 and local k+1 in face 1.
    for (int end = 0; end < 2; ++end) {
      auto& cf = child.edgeFaces[2 * e + end];
      cf[0] = 4 * ef[0] + (el[0] + end) % 3;
      cf[1] = ef[1] == kInvalidIndex ? kInvalidIndex : 4 * ef[1] + (el[1] + 1 - end) % 3;
      child.edgeFaceLocal[2 * e + end] = el;
    }
  }

  for (Index f = 0; f < nF; ++f) {
    const auto& fv = parent.faceVertices[f];
    const auto& fe = parent.faceEdges[f];
    const uint8_t sides = parent.faceEdgeSides[f];
    const Index m0 = nV + fe[0], m1 = nV + fe[1], m2 = nV + fe[2];
    const Index i0 = firstInterior + 3 * f, i1 = i0 + 1, i2 = i0 + 2;
    const Index c = 4 * f;
    // Halves of face edge j at its start (vertex j) and end (vertex j+1).
    auto atStart = [&](int j) { return 2 * fe[j] + ((sides >> j) & 1); };
    auto atEnd = [&](int j) { return 2 * fe[j] + 1 - ((sides >> j) & 1); };

    child.faceVertices[c + 0] = {fv[0], m0, m2};
    child.faceVertices[c + 1] = {m0, fv[1], m1};
    child.faceVertices[c + 2] = {m2, m1, fv[2]};
    child.faceVertices[c + 3] = {m1, m2, m0};

    child.faceEdges[c + 0] = {atStart(0), i0, atEnd(2)};
    child.faceEdges[c + 1] = {atEnd(0), atStart(1), i1};
    child.faceEdges[c + 2] = {i2, atEnd(1), atStart(2)};
    child.faceEdges[c + 3] = {i2, i0, i1};

    // Corner children are face 0 of the interior edges, the middle is face 1.
    child.faceEdgeSides[c + 0] = sides & 0b101;
    child.faceEdgeSides[c + 1] = sides & 0b011;
    child.faceEdgeSides[c + 2] = sides & 0b110;
    child.faceEdgeSides[c + 3] = 0b111;

    // Interior edge j joins the midpoints of face edges j and j-1.
    child.edgeVertices[i0] = {m0, m2};
    child.edgeVertices[i1] = {m1, m0};
    child.edgeVertices[i2] = {m2, m1};
    child.edgeFaces[i0] = {c + 0, c + 3};
    child.edgeFaces[i1] = {c + 1, c + 3};
    child.edgeFaces[i2] = {c + 2, c + 3};
    child.edgeFaceLocal[i0] = {1, 1};
    child.edgeFaceLocal[i1] = {2, 2};
    child.edgeFaceLocal[i2] = {0, 0};
  }
}

// Faces only, for a last level that is interpolated and drawn, not refined.
void refineFaceVertices(const Level& parent, Level& child) {
  const Index nV = parent.numVertices;
  const Index nF = parent.numFaces();
  child.numVertices = nV + parent.numEdges();
  child.faceVertices.resize(4 * nF);
  for (Index f = 0; f < nF; ++f) {
    const auto& fv = parent.faceVertices[f];
    const auto& fe = parent.faceEdges[f];
    const Index m0 = nV + fe[0], m1 = nV + fe[1], m2 = nV + fe[2];
    child.faceVertices[4 * f + 0] = {fv[0], m0, m2};
    child.faceVertices[4 * f + 1] = {m0, fv[1], m1};
    child.faceVertices[4 * f + 2] = {m2, m1, fv[2]};
    child.faceVertices[4 * f + 3] = {m1, m2, m0};
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
