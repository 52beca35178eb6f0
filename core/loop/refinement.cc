#include "core/loop/refinement.h"

#include <algorithm>
#include <vector>

#include "core/loop/sharpness_inheritance.h"

namespace tessera {

namespace {

// Parent face f's split in the uniform numbering (the header's).
FaceSplit uniformSplit(const Level& parent, Index f) {
  const Index nV = parent.numVertices;
  const auto fe = parent.triangleEdges(f);
  const auto fv = parent.triangleVertices(f);
  FaceSplit split;
  for (int j = 0; j < 3; ++j) {
    split.corners[j] = fv[j];
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
  child.faceVertices.resize(12 * nF);
  child.faceEdges.resize(12 * nF);
  child.faceEdgeSides.resize(4 * nF);
  child.edgeVertices.resize(2 * nE + 3 * nF);
  child.edgeFaces.resize(2 * nE + 3 * nF);
  child.edgeFaceLocal.resize(2 * nE + 3 * nF);

  for (Index e = 0; e < nE; ++e) {
    const auto& ev = parent.edgeVertices[e];
    const auto& ef = parent.edgeFaces[e];
    splitEdge(2 * e, ev[0], nV + e, ev[1], {4 * ef[0], ef[1] == kNoIndex ? kNoIndex : 4 * ef[1]},
              parent.edgeFaceLocal[e], child);
  }
  for (Index f = 0; f < nF; ++f) splitFace(uniformSplit(parent, f), child);
}

// Faces only, for a last level that is interpolated and drawn, not refined
// (RefineDetail::kFacesOnly). Corners and midpoints go straight from the
// parent's rows to writeChildTriangles: gathered into a FaceSplit first,
// they went through the stack and this loop ran about a quarter slower
// (perf, fandisk level 2 to 3).
void refineFaceVertices(const Level& parent, Level& child) {
  const Index nF = parent.numFaces();
  const Index nV = parent.numVertices;
  child.numVertices = nV + parent.numEdges();
  child.faceVertices.resize(12 * nF);
  const Index* fv = parent.faceVertices.data();
  const Index* fe = parent.faceEdges.data();
  Index* out = child.faceVertices.data();
  for (Index f = 0; f < nF; ++f, fv += 3, fe += 3, out += 12) {
    writeChildTriangles(out, fv[0], fv[1], fv[2], nV + fe[0], nV + fe[1], nV + fe[2]);
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

  // A vertex keeps its ring order (refinement.h, writeVertexChildRing).
  for (Index v = 0; v < nV; ++v) {
    const Index o = child.ringOffsets[v];
    writeVertexChildRing(
        parent, v, [](Index e) { return 2 * e; }, [nV](Index e) { return nV + e; },
        [](Index f) { return 4 * f; }, child.ringEdges.data() + o, child.ringVertices.data() + o,
        child.ringFaces.data() + o, child.ringFaceLocal.data() + o);
  }

  // A new edge vertex: its ring crosses the children of the edge's faces
  // (refinement.h, EdgeVertexRing).
  for (Index e = 0; e < nE; ++e) {
    const Index o = child.ringOffsets[nV + e];
    // No loop over the two faces: indexed by a variable, the sides would
    // live in memory, and this loop ran about a fifth slower (perf).
    auto side = [&](Index f, int j) -> EdgeVertexRing::Side {
      const auto fe = parent.triangleEdges(f);
      return {4 * f, firstInterior + 3 * f, j, {nV + fe[(j + 1) % 3], nV + fe[(j + 2) % 3]}};
    };
    const auto& ef = parent.edgeFaces[e];
    const auto& el = parent.edgeFaceLocal[e];
    const EdgeVertexRing ring{
        2 * e,
        parent.edgeVertices[e],
        {side(ef[0], el[0]), ef[1] == kNoIndex ? EdgeVertexRing::Side{} : side(ef[1], el[1])}};
    writeEdgeVertexRing(ring, child.ringEdges.data() + o, child.ringVertices.data() + o,
                        child.ringFaces.data() + o, child.ringFaceLocal.data() + o);
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
  child.regularFaceSize = 3;
  child.maxFaceSize = 3;
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
