#include "core/hierarchy/sparse_level.h"

#include <algorithm>
#include <cassert>

#include "core/loop/refinement.h"
#include "core/loop/sharpness_inheritance.h"

namespace tessera {

namespace {

template <typename T>
size_t bytesOf(const Buffer<T>& b) {
  return b.capacity() * sizeof(T);
}

Index findIn(const Buffer<uint64_t>& ids, uint64_t canonical) {
  auto it = std::lower_bound(ids.begin(), ids.end(), canonical);
  return it != ids.end() && *it == canonical ? static_cast<Index>(it - ids.begin()) : kNoIndex;
}

// Local indices of everything the refined faces of a parent produce.
struct ChildMap {
  std::vector<Index> vertexChild;  // parent vertex -> child vertex
  std::vector<Index> edgeVertex;   // parent edge -> child vertex on it
  std::vector<Index> edgeHalves;   // parent edge -> first of its two halves
  std::vector<Index> interior;     // parent face -> first of its 3 interior edges
  std::vector<Index> firstFace;    // parent face -> first of its 4 children
  Index faceChild(Index f) const { return f < 0 ? f : (firstFace[f] < 0 ? kAbsentFace : firstFace[f]); }
};

}  // namespace

Index SparseLevel::findVertex(uint64_t canonical) const {
  return findIn(vertexIds, canonical);
}
Index SparseLevel::findEdge(uint64_t canonical) const {
  return findIn(edgeIds, canonical);
}
Index SparseLevel::findFace(uint64_t canonical) const {
  return findIn(faceIds, canonical);
}

size_t SparseLevel::memoryBytes() const {
  const Level& m = mesh;
  return bytesOf(m.faceVertices) + bytesOf(m.faceEdges) + bytesOf(m.edgeVertices) + bytesOf(m.edgeFaces) +
         bytesOf(m.edgeFaceLocal) + bytesOf(m.faceEdgeSides) + bytesOf(m.ringOffsets) + bytesOf(m.ringEdges) +
         bytesOf(m.ringVertices) + bytesOf(m.ringFaces) + bytesOf(m.ringFaceLocal) +
         bytesOf(m.edgeSharpness) + bytesOf(m.vertexSharpness) + bytesOf(m.vertexRules) + bytesOf(vertexIds) +
         bytesOf(edgeIds) + bytesOf(faceIds) + bytesOf(complete) + bytesOf(origin) + bytesOf(faceParent) +
         bytesOf(firstChildFace) + bytesOf(childOfVertex) + bytesOf(childOfEdge) + bytesOf(halvesOfEdge);
}

SparseLevel sparseBaseLevel(Level base) {
  SparseLevel level;
  level.mesh = std::move(base);
  const Level& m = level.mesh;
  level.vertexIds.resize(m.numVertices);
  level.edgeIds.resize(m.numEdges());
  level.faceIds.resize(m.numFaces());
  for (Index v = 0; v < m.numVertices; ++v) level.vertexIds[v] = static_cast<uint64_t>(v);
  for (Index e = 0; e < m.numEdges(); ++e) level.edgeIds[e] = static_cast<uint64_t>(e);
  for (Index f = 0; f < m.numFaces(); ++f) level.faceIds[f] = static_cast<uint64_t>(f);
  level.complete.assign(m.numVertices, 1);
  level.numVertexChildren = m.numVertices;
  level.firstChildFace.assign(m.numFaces(), kNoIndex);
  return level;
}

namespace {

// Vertices, edges and faces of the child, with their canonical ids, in the
// order described in the header.
ChildMap numberChildren(const SparseLevel& parent, std::span<const uint8_t> refine, const LevelCounts& counts,
                        SparseLevel& child) {
  const Level& p = parent.mesh;
  ChildMap map;
  map.vertexChild.assign(p.numVertices, kNoIndex);
  map.edgeVertex.assign(p.numEdges(), kNoIndex);
  map.edgeHalves.assign(p.numEdges(), kNoIndex);
  map.interior.assign(p.numFaces(), kNoIndex);
  map.firstFace.assign(p.numFaces(), kNoIndex);
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (!refine[f]) continue;
    const auto fv = p.triangleVertices(f);
    const auto fe = p.triangleEdges(f);
    for (int k = 0; k < 3; ++k) {
      assert(parent.isComplete(fv[k]) && "a refined face needs complete vertices");
      map.vertexChild[fv[k]] = 0;
      map.edgeVertex[fe[k]] = 0;
    }
  }
  const int d = parent.depth;
  const uint64_t parentVertices = counts.vertices(d), parentEdges = counts.edges(d);
  Index nv = 0, ne = 0, nf = 0;
  for (Index v = 0; v < p.numVertices; ++v) {
    if (map.vertexChild[v] == 0) map.vertexChild[v] = nv++;
  }
  child.numVertexChildren = nv;
  for (Index e = 0; e < p.numEdges(); ++e) {
    if (map.edgeVertex[e] == 0) map.edgeVertex[e] = nv++, map.edgeHalves[e] = ne, ne += 2;
  }
  const Index numHalves = ne;
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (refine[f]) map.interior[f] = ne, ne += 3, map.firstFace[f] = nf, nf += 4;
  }

  child.depth = d + 1;
  child.vertexIds.resize(nv);
  child.origin.resize(nv);
  child.edgeIds.resize(ne);
  child.faceIds.resize(nf);
  child.faceParent.resize(nf / 4);
  for (Index v = 0; v < p.numVertices; ++v) {
    if (Index c = map.vertexChild[v]; c >= 0) child.vertexIds[c] = parent.vertexIds[v], child.origin[c] = v;
  }
  for (Index e = 0; e < p.numEdges(); ++e) {
    const Index c = map.edgeVertex[e];
    if (c < 0) continue;
    child.vertexIds[c] = parentVertices + parent.edgeIds[e];
    child.origin[c] = e;
    child.edgeIds[map.edgeHalves[e]] = 2 * parent.edgeIds[e];
    child.edgeIds[map.edgeHalves[e] + 1] = 2 * parent.edgeIds[e] + 1;
  }
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (!refine[f]) continue;
    for (int j = 0; j < 3; ++j)
      child.edgeIds[map.interior[f] + j] = 2 * parentEdges + 3 * parent.faceIds[f] + j;
    for (int k = 0; k < 4; ++k) child.faceIds[map.firstFace[f] + k] = 4 * parent.faceIds[f] + k;
    child.faceParent[map.firstFace[f] / 4] = f;
  }
  assert(numHalves <= ne);
  (void)numHalves;
  return map;
}

// As refinement.cc's uniform version, through the child map.
void refineFacesAndEdges(const Level& p, const ChildMap& map, std::span<const uint8_t> refine, Level& c) {
  for (Index e = 0; e < p.numEdges(); ++e) {
    const Index h = map.edgeHalves[e];
    if (h < 0) continue;
    const auto& ev = p.edgeVertices[e];
    const auto& ef = p.edgeFaces[e];
    splitEdge(h, map.vertexChild[ev[0]], map.edgeVertex[e], map.vertexChild[ev[1]],
              {map.faceChild(ef[0]), map.faceChild(ef[1])}, p.edgeFaceLocal[e], c);
  }
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (!refine[f]) continue;
    const auto fv = p.triangleVertices(f);
    const auto fe = p.triangleEdges(f);
    FaceSplit split;
    for (int j = 0; j < 3; ++j) {
      split.corners[j] = map.vertexChild[fv[j]];
      split.midpoints[j] = map.edgeVertex[fe[j]];
      split.halves[j] = map.edgeHalves[fe[j]];
    }
    split.firstInterior = map.interior[f];
    split.firstFace = map.firstFace[f];
    split.sides = p.faceEdgeSides[f];
    splitFace(split, c);
  }
}

bool isPresentChild(const ChildMap& map, Index f) {
  return f == kNoIndex || map.firstFace[f] >= 0;
}

// Rings of the complete child vertices, in the order refinement.cc gives the
// uniform level (so frames and limit tangents agree with it exactly); an
// incomplete vertex lists just its present faces, for the incremental update.
void refineRings(const SparseLevel& parent, const ChildMap& map, SparseLevel& child) {
  const Level& p = parent.mesh;
  Level& c = child.mesh;
  child.complete.assign(c.numVertices, 0);
  std::vector<Index> presentFaces(c.numVertices, 0);
  for (Index v : c.faceVertices) ++presentFaces[v];
  c.ringOffsets.resize(c.numVertices + 1);
  c.ringOffsets[0] = 0;
  for (Index v = 0; v < c.numVertices; ++v) {
    int valence = 0;
    const Index o = child.origin[v];
    if (v < child.numVertexChildren) {
      bool all = true;
      for (Index f : p.ringFacesOf(o)) all = all && isPresentChild(map, f);
      if (all) valence = p.valence(o);
    } else {
      const auto& ef = p.edgeFaces[o];
      if (map.firstFace[ef[0]] >= 0 && (ef[1] == kNoIndex || (ef[1] >= 0 && map.firstFace[ef[1]] >= 0))) {
        valence = ef[1] == kNoIndex ? 4 : 6;
      }
    }
    child.complete[v] = valence > 0;
    c.ringOffsets[v + 1] = c.ringOffsets[v] + (valence > 0 ? valence : presentFaces[v]);
  }
  const Index total = c.ringOffsets[c.numVertices];
  c.ringEdges.resize(total);
  c.ringVertices.resize(total);
  c.ringFaces.resize(total);
  c.ringFaceLocal.resize(total);

  for (Index f = 0; f < c.numFaces(); ++f) {
    const auto fv = c.triangleVertices(f);
    for (int k = 0; k < 3; ++k) {
      const Index v = fv[k];
      if (child.complete[v]) continue;
      const Index slot = c.ringOffsets[v] + --presentFaces[v];
      c.ringEdges[slot] = c.ringVertices[slot] = kNoIndex;
      c.ringFaces[slot] = f;
      c.ringFaceLocal[slot] = static_cast<LocalIndex>(k);
    }
  }
  for (Index v = 0; v < c.numVertices; ++v) {
    if (!child.complete[v]) continue;
    const Index o = child.origin[v];
    Index* ringE = c.ringEdges.data() + c.ringOffsets[v];
    Index* ringV = c.ringVertices.data() + c.ringOffsets[v];
    Index* ringF = c.ringFaces.data() + c.ringOffsets[v];
    LocalIndex* ringL = c.ringFaceLocal.data() + c.ringOffsets[v];
    if (v < child.numVertexChildren) {
      writeVertexChildRing(
          p, o, [&](Index e) { return map.edgeHalves[e]; }, [&](Index e) { return map.edgeVertex[e]; },
          [&](Index f) { return map.firstFace[f]; }, ringE, ringV, ringF, ringL);
      continue;
    }
    // On parent edge o: the uniform level's order (refinement.h,
    // EdgeVertexRing) in this level's numbering.
    auto side = [&](Index f, int j) -> EdgeVertexRing::Side {
      const auto fe = p.triangleEdges(f);
      return {map.firstFace[f],
              map.interior[f],
              j,
              {map.edgeVertex[fe[(j + 1) % 3]], map.edgeVertex[fe[(j + 2) % 3]]}};
    };
    const auto& ef = p.edgeFaces[o];
    const auto& el = p.edgeFaceLocal[o];
    const EdgeVertexRing ring{
        map.edgeHalves[o],
        {map.vertexChild[p.edgeVertices[o][0]], map.vertexChild[p.edgeVertices[o][1]]},
        {side(ef[0], el[0]), ef[1] == kNoIndex ? EdgeVertexRing::Side{} : side(ef[1], el[1])}};
    writeEdgeVertexRing(ring, ringE, ringV, ringF, ringL);
  }
  c.maxValence = std::max(p.maxValence, 6);
}

void inheritSharpness(const SparseLevel& parent, const ChildMap& map, const LoopOptions& options,
                      SparseLevel& child) {
  const Level& p = parent.mesh;
  Level& c = child.mesh;
  SharpnessInheritance inherit(p, options);
  c.edgeSharpness.assign(c.numEdges(), kSharpnessSmooth);
  c.vertexSharpness.resize(c.numVertices);
  c.vertexRules.resize(c.numVertices);
  for (Index e = 0; e < p.numEdges(); ++e) {
    const Index h = map.edgeHalves[e];
    if (h < 0) continue;
    c.vertexSharpness[map.edgeVertex[e]] = kSharpnessSmooth;
    c.vertexRules[map.edgeVertex[e]] = inherit.edgeChildRule(e);
    if (isSmooth(p.edgeSharpness[e])) continue;
    c.edgeSharpness[h] = inherit.halfSharpness(e, 0);
    c.edgeSharpness[h + 1] = inherit.halfSharpness(e, 1);
  }
  for (Index v = 0; v < child.numVertexChildren; ++v) {
    const Index o = child.origin[v];
    c.vertexSharpness[v] = inherit.vertexChildSharpness(o);
    c.vertexRules[v] = inherit.vertexChildRule(o);
  }
}

}  // namespace

SparseLevel refineSparse(SparseLevel& parent, std::span<const uint8_t> refine, const LevelCounts& counts,
                         const LoopOptions& options) {
  SparseLevel child;
  const ChildMap map = numberChildren(parent, refine, counts, child);
  Level& c = child.mesh;
  c.numVertices = static_cast<int>(child.vertexIds.size());
  c.regularFaceSize = 3;
  c.maxFaceSize = 3;
  const size_t nf = child.faceIds.size(), ne = child.edgeIds.size();
  c.faceVertices.resize(3 * nf);
  c.faceEdges.resize(3 * nf);
  c.faceEdgeSides.resize(nf);
  c.edgeVertices.resize(ne);
  c.edgeFaces.resize(ne);
  c.edgeFaceLocal.resize(ne);
  refineFacesAndEdges(parent.mesh, map, refine, c);
  refineRings(parent, map, child);
  inheritSharpness(parent, map, options, child);
  child.firstChildFace.assign(nf, kNoIndex);
  parent.firstChildFace.assign(map.firstFace.begin(), map.firstFace.end());
  parent.childOfVertex.assign(map.vertexChild.begin(), map.vertexChild.end());
  parent.childOfEdge.assign(map.edgeVertex.begin(), map.edgeVertex.end());
  parent.halvesOfEdge.assign(map.edgeHalves.begin(), map.edgeHalves.end());
  return child;
}

}  // namespace tessera
