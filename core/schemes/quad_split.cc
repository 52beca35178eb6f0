#include "core/schemes/quad_split.h"

#include <algorithm>
#include <vector>

#include "core/loop/crease.h"

namespace tessera::schemes {

namespace {

// Child face j of a face: its corner vertex, the vertex of the edge leaving
// it, the face vertex, the vertex of the edge arriving. A quad's children are
// rotated so that the corner vertex keeps its position j (as Vtr does).
inline int childSlot(int size, int j, int k) {
  return size == 4 ? (j + k) & 3 : k;
}

void splitFaces(const Level& parent, Level& child, bool withEdges) {
  const Index nV = parent.numVertices;
  const Index nF = parent.numFaces();
  const Index corners = static_cast<Index>(parent.faceVertices.size());
  const Index firstEdgeVertex = nV + nF;
  child.faceVertices.resize(4 * corners);
  if (withEdges) child.faceEdges.resize(4 * corners);
  for (Index f = 0; f < nF; ++f) {
    const Index o = parent.faceBegin(f);
    const int n = parent.faceSize(f);
    const Index* fv = parent.faceVertices.data() + o;
    const Index* fe = parent.faceEdges.data() + o;
    for (int j = 0; j < n; ++j) {
      const int jPrev = j ? j - 1 : n - 1;
      Index* cv = child.faceVertices.data() + 4 * (o + j);
      cv[childSlot(n, j, 0)] = fv[j];
      cv[childSlot(n, j, 1)] = firstEdgeVertex + fe[j];
      cv[childSlot(n, j, 2)] = nV + f;
      cv[childSlot(n, j, 3)] = firstEdgeVertex + fe[jPrev];
      if (!withEdges) continue;
      Index* ce = child.faceEdges.data() + 4 * (o + j);
      const int nextEnd = parent.edgeVertices[fe[j]][0] == fv[j] ? 0 : 1;
      const int prevEnd = parent.edgeVertices[fe[jPrev]][0] == fv[j] ? 0 : 1;
      ce[childSlot(n, j, 0)] = corners + 2 * fe[j] + nextEnd;
      ce[childSlot(n, j, 1)] = o + j;
      ce[childSlot(n, j, 2)] = o + jPrev;
      ce[childSlot(n, j, 3)] = corners + 2 * fe[jPrev] + prevEnd;
    }
  }
}

void splitEdges(const Level& parent, Level& child) {
  const Index nV = parent.numVertices;
  const Index nF = parent.numFaces();
  const Index nE = parent.numEdges();
  const Index corners = static_cast<Index>(parent.faceVertices.size());
  const Index firstEdgeVertex = nV + nF;
  child.edgeVertices.resize(corners + 2 * nE);
  child.edgeFaces.resize(corners + 2 * nE);
  child.edgeFaceLocal.resize(corners + 2 * nE);
  // Edges inside a face: between child j and child j+1.
  for (Index f = 0; f < nF; ++f) {
    const Index o = parent.faceBegin(f);
    const int n = parent.faceSize(f);
    for (int j = 0; j < n; ++j) {
      const int jNext = j + 1 < n ? j + 1 : 0;
      child.edgeVertices[o + j] = {nV + f, firstEdgeVertex + parent.faceEdges[o + j]};
      child.edgeFaces[o + j] = {o + j, o + jNext};
      child.edgeFaceLocal[o + j] = {static_cast<LocalIndex>(n == 4 ? jNext : 1),
                                    static_cast<LocalIndex>(n == 4 ? (jNext + 2) & 3 : 2)};
    }
  }
  // Halves of parent edges: the child face at each parent face's end corner.
  for (Index e = 0; e < nE; ++e) {
    const auto& ev = parent.edgeVertices[e];
    const auto& ef = parent.edgeFaces[e];
    const auto& el = parent.edgeFaceLocal[e];
    for (int end = 0; end < 2; ++end) {
      const Index c = corners + 2 * e + end;
      child.edgeVertices[c] = {firstEdgeVertex + e, ev[end]};
      child.edgeFaces[c] = {kNoIndex, kNoIndex};
      for (int i = 0; i < 2 && ef[i] != kNoIndex; ++i) {
        const Index o = parent.faceBegin(ef[i]);
        const int n = parent.faceSize(ef[i]);
        const int edgeInFace = el[i];
        const int childOfEdge = parent.faceVertices[o + edgeInFace] != ev[end] ? 1 : 0;
        int childInFace = edgeInFace + childOfEdge;
        if (childInFace == n) childInFace = 0;
        child.edgeFaces[c][i] = o + childInFace;
        child.edgeFaceLocal[c][i] = static_cast<LocalIndex>(n == 4 ? edgeInFace : (childOfEdge ? 3 : 0));
      }
    }
  }
}

void splitRings(const Level& parent, Level& child) {
  const Index nV = parent.numVertices;
  const Index nF = parent.numFaces();
  const Index nE = parent.numEdges();
  const Index corners = static_cast<Index>(parent.faceVertices.size());
  const Index firstEdgeVertex = nV + nF;

  child.ringOffsets.resize(child.numVertices + 1);
  Index* offsets = child.ringOffsets.data();
  offsets[0] = 0;
  for (Index v = 0; v < nV; ++v) offsets[v + 1] = offsets[v] + parent.valence(v);
  for (Index f = 0; f < nF; ++f) offsets[nV + f + 1] = offsets[nV + f] + parent.faceSize(f);
  for (Index e = 0; e < nE; ++e) {
    offsets[firstEdgeVertex + e + 1] = offsets[firstEdgeVertex + e] + (parent.isBoundaryEdge(e) ? 3 : 4);
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

  // A vertex keeps its ring order: the halves at v and v's corner children.
  for (Index v = 0; v < nV; ++v) {
    const Index from = parent.ringOffsets[v], to = parent.ringOffsets[v + 1];
    const Index out = offsets[v] - from;
    for (Index k = from; k < to; ++k) {
      const Index e = parent.ringEdges[k];
      rE[out + k] = corners + 2 * e + (parent.edgeVertices[e][0] == v ? 0 : 1);
      rV[out + k] = firstEdgeVertex + e;
      const Index f = parent.ringFaces[k];
      if (f == kNoIndex) {
        rF[out + k] = kNoIndex, rL[out + k] = 0;
      } else {
        const int c = parent.ringFaceLocal[k];
        rF[out + k] = parent.faceBegin(f) + c;
        rL[out + k] = static_cast<LocalIndex>(parent.faceSize(f) == 4 ? c : 0);
      }
    }
  }
  // A face vertex: child k lies between the edges to edge k-1's and edge k's vertices.
  for (Index f = 0; f < nF; ++f) {
    const Index o = parent.faceBegin(f);
    const int n = parent.faceSize(f);
    const Index out = offsets[nV + f];
    for (int k = 0; k < n; ++k) {
      const int kPrev = k ? k - 1 : n - 1;
      rE[out + k] = o + kPrev;
      rV[out + k] = firstEdgeVertex + parent.faceEdges[o + kPrev];
      rF[out + k] = o + k;
      rL[out + k] = static_cast<LocalIndex>(n == 4 ? (k + 2) & 3 : 2);
    }
  }
  // An edge vertex: face 0 runs the edge from a to b; the ring starts with
  // the half towards b, crosses face 0's two children, then face 1's.
  for (Index e = 0; e < nE; ++e) {
    const Index out = offsets[firstEdgeVertex + e];
    const auto& ev = parent.edgeVertices[e];
    const auto& ef = parent.edgeFaces[e];
    const auto& el = parent.edgeFaceLocal[e];
    const Index o0 = parent.faceBegin(ef[0]);
    const int n0 = parent.faceSize(ef[0]);
    const int j0 = el[0];
    const int j0Next = j0 + 1 < n0 ? j0 + 1 : 0;
    const int b = parent.faceVertices[o0 + j0] == ev[0] ? 1 : 0;  // end of the edge face 0 runs to
    rE[out + 0] = corners + 2 * e + b;
    rV[out + 0] = ev[b];
    rF[out + 0] = o0 + j0Next;
    rL[out + 0] = static_cast<LocalIndex>(n0 == 4 ? j0 : 3);
    rE[out + 1] = o0 + j0;
    rV[out + 1] = nV + ef[0];
    rF[out + 1] = o0 + j0;
    rL[out + 1] = static_cast<LocalIndex>(n0 == 4 ? j0Next : 1);
    rE[out + 2] = corners + 2 * e + (1 - b);
    rV[out + 2] = ev[1 - b];
    if (ef[1] == kNoIndex) {
      rF[out + 2] = kNoIndex, rL[out + 2] = 0;
      continue;
    }
    const Index o1 = parent.faceBegin(ef[1]);
    const int n1 = parent.faceSize(ef[1]);
    const int j1 = el[1];
    const int j1Next = j1 + 1 < n1 ? j1 + 1 : 0;
    rF[out + 2] = o1 + j1Next;
    rL[out + 2] = static_cast<LocalIndex>(n1 == 4 ? j1 : 3);
    rE[out + 3] = o1 + j1;
    rV[out + 3] = nV + ef[1];
    rF[out + 3] = o1 + j1;
    rL[out + 3] = static_cast<LocalIndex>(n1 == 4 ? j1Next : 1);
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

}  // namespace tessera::schemes
