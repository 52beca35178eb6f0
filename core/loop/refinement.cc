#include "core/loop/refinement.h"

#include <vector>

namespace tessera {

namespace {

// Child edge of parent edge e at its end vertex x.
inline Index childEdgeAt(const Level& parent, Index e, Index x) {
  return 2 * e + (parent.edgeVertices[e][0] == x ? 0 : 1);
}

void refineFacesAndEdges(const Level& parent, Level& child) {
  const Index nV = parent.numVertices;
  const Index nE = parent.numEdges();
  const Index nF = parent.numFaces();
  const Index firstInterior = 2 * nE;

  child.numVertices = nV + nE;
  child.faceVertices.resize(4 * nF);
  child.faceEdges.resize(4 * nF);
  child.edgeVertices.resize(2 * nE + 3 * nF);
  child.edgeFaces.resize(2 * nE + 3 * nF);

  for (Index e = 0; e < nE; ++e) {
    const Index m = nV + e;
    child.edgeVertices[2 * e] = {m, parent.edgeVertices[e][0]};
    child.edgeVertices[2 * e + 1] = {m, parent.edgeVertices[e][1]};
    // Each half is bounded by the corner children, at its end, of the parent's faces.
    for (int end = 0; end < 2; ++end) {
      const Index x = parent.edgeVertices[e][end];
      auto& ef = child.edgeFaces[2 * e + end];
      for (int side = 0; side < 2; ++side) {
        const Index f = parent.edgeFaces[e][side];
        ef[side] = (f == kInvalidIndex) ? kInvalidIndex : 4 * f + parent.vertexInFace(f, x);
      }
    }
  }

  for (Index f = 0; f < nF; ++f) {
    const auto& fv = parent.faceVertices[f];
    const auto& fe = parent.faceEdges[f];
    const Index m0 = nV + fe[0], m1 = nV + fe[1], m2 = nV + fe[2];
    const Index i0 = firstInterior + 3 * f, i1 = i0 + 1, i2 = i0 + 2;
    const Index c = 4 * f;

    child.faceVertices[c + 0] = {fv[0], m0, m2};
    child.faceVertices[c + 1] = {m0, fv[1], m1};
    child.faceVertices[c + 2] = {m2, m1, fv[2]};
    child.faceVertices[c + 3] = {m1, m2, m0};

    child.faceEdges[c + 0] = {childEdgeAt(parent, fe[0], fv[0]), i0, childEdgeAt(parent, fe[2], fv[0])};
    child.faceEdges[c + 1] = {childEdgeAt(parent, fe[0], fv[1]), childEdgeAt(parent, fe[1], fv[1]), i1};
    child.faceEdges[c + 2] = {i2, childEdgeAt(parent, fe[1], fv[2]), childEdgeAt(parent, fe[2], fv[2])};
    child.faceEdges[c + 3] = {i2, i0, i1};

    // Interior edge j joins the midpoints of face edges j and j-1, shared by
    // the corner child j and the middle child.
    child.edgeVertices[i0] = {m0, m2};
    child.edgeVertices[i1] = {m1, m0};
    child.edgeVertices[i2] = {m2, m1};
    child.edgeFaces[i0] = {c + 0, c + 3};
    child.edgeFaces[i1] = {c + 1, c + 3};
    child.edgeFaces[i2] = {c + 2, c + 3};
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
  child.ringEdges.resize(child.ringOffsets[child.numVertices]);
  child.ringFaces.resize(child.ringOffsets[child.numVertices]);

  // A vertex keeps its ring order; each entry becomes the child at v.
  for (Index v = 0; v < nV; ++v) {
    Index* ringE = child.ringEdges.data() + child.ringOffsets[v];
    Index* ringF = child.ringFaces.data() + child.ringOffsets[v];
    auto pe = parent.ringEdgesOf(v);
    auto pf = parent.ringFacesOf(v);
    for (size_t k = 0; k < pe.size(); ++k) {
      ringE[k] = childEdgeAt(parent, pe[k], v);
      ringF[k] = pf[k] == kInvalidIndex ? kInvalidIndex : 4 * pf[k] + parent.vertexInFace(pf[k], v);
    }
  }

  // A new edge vertex: its ring starts in the edge's first face, at the half
  // towards that face's next corner, then crosses that face's children.
  for (Index e = 0; e < nE; ++e) {
    Index* ringE = child.ringEdges.data() + child.ringOffsets[nV + e];
    Index* ringF = child.ringFaces.data() + child.ringOffsets[nV + e];
    const Index fA = parent.edgeFaces[e][0];
    const int j = parent.edgeInFace(fA, e);
    const int jn = (j + 1) % 3;
    const Index iA = firstInterior + 3 * fA;
    ringE[0] = childEdgeAt(parent, e, parent.faceVertices[fA][jn]);
    ringE[1] = iA + jn;
    ringE[2] = iA + j;
    ringE[3] = childEdgeAt(parent, e, parent.faceVertices[fA][j]);
    ringF[0] = 4 * fA + jn;
    ringF[1] = 4 * fA + 3;
    ringF[2] = 4 * fA + j;
    const Index fB = parent.edgeFaces[e][1];
    if (fB == kInvalidIndex) {
      ringF[3] = kInvalidIndex;
      continue;
    }
    const int k = parent.edgeInFace(fB, e);
    const int kn = (k + 1) % 3;
    const Index iB = firstInterior + 3 * fB;
    ringF[3] = 4 * fB + kn;
    ringE[4] = iB + kn;
    ringF[4] = 4 * fB + 3;
    ringE[5] = iB + k;
    ringF[5] = 4 * fB + k;
  }
}

void refineSharpness(const Level& parent, const LoopOptions& options, Level& child) {
  const Index nV = parent.numVertices;
  const Index nE = parent.numEdges();
  child.edgeSharpness.assign(child.numEdges(), kSharpnessSmooth);
  child.vertexSharpness.assign(child.numVertices, kSharpnessSmooth);
  child.vertexRules.assign(child.numVertices, VertexRule::kSmooth);

  std::vector<float> ring(parent.maxValence());
  for (Index e = 0; e < nE; ++e) {
    const float s = parent.edgeSharpness[e];
    if (isSmooth(s)) continue;
    for (int end = 0; end < 2; ++end) {
      float cs = decrementSharpness(s);
      if (options.creaseMethod == CreaseMethod::kChaikin && isSemiSharp(s)) {
        const Index x = parent.edgeVertices[e][end];
        parent.ringSharpness(x, ring.data());
        cs = subdivideEdgeSharpnessAtVertex(options.creaseMethod, s, std::span(ring.data(), parent.valence(x)));
      }
      child.edgeSharpness[2 * e + end] = cs;
    }
    // The edge vertex: a crease if both halves stay sharp, a dart if one does.
    int sharpHalves = isSharp(child.edgeSharpness[2 * e]) + isSharp(child.edgeSharpness[2 * e + 1]);
    child.vertexRules[nV + e] = vertexRule(kSharpnessSmooth, sharpHalves);
  }
  for (Index v = 0; v < nV; ++v) {
    child.vertexSharpness[v] = decrementSharpness(parent.vertexSharpness[v]);
    int sharpEdges = 0;
    for (Index ce : child.ringEdgesOf(v)) sharpEdges += isSharp(child.edgeSharpness[ce]);
    child.vertexRules[v] = vertexRule(child.vertexSharpness[v], sharpEdges);
  }
}

}  // namespace

Level refineLevel(const Level& parent, const LoopOptions& options) {
  Level child;
  refineFacesAndEdges(parent, child);
  refineRings(parent, child);
  refineSharpness(parent, options, child);
  return child;
}

}  // namespace tessera
