// Loop's 1-to-4 triangle split of a sparse level (sparse_level.h), in the
// numbering of core/loop/refinement.h restricted to what is present.
#include <algorithm>
#include <cassert>

#include "core/hierarchy/sparse_split.h"
#include "core/loop/refinement.h"
#include "core/loop/sharpness_inheritance.h"

namespace tessera {

namespace {

// Local indices of everything the refined faces of a parent produce.
struct ChildMap {
  std::vector<Index> vertexChildOf;  // parent vertex -> child vertex
  std::vector<Index> edgeVertex;     // parent edge -> child vertex on it
  std::vector<Index> edgeHalves;     // parent edge -> first of its two halves
  std::vector<Index> interiorOf;     // parent face -> first of its 3 interior edges
  std::vector<Index> firstFaceOf;    // parent face -> first of its 4 children
  Index faceChild(Index f) const { return sparse_split::firstChildOrAbsent(firstFaceOf, f); }
  // The child numbering, as writeCompleteRing reads it.
  Index vertexChild(Index v) const { return vertexChildOf[v]; }
  Index onEdge(Index e) const { return edgeVertex[e]; }
  Index halves(Index e) const { return edgeHalves[e]; }
  Index firstFace(Index f) const { return firstFaceOf[f]; }
  Index interior(Index f) const { return interiorOf[f]; }
};

// Vertices, edges and faces of the child, with their canonical ids, in the
// order described in the header.
ChildMap numberChildren(const SparseLevel& parent, std::span<const uint8_t> refine, const LevelCounts& counts,
                        SparseLevel& child) {
  const Level& p = parent.mesh;
  ChildMap map;
  map.vertexChildOf.assign(p.numVertices, kNoIndex);
  map.edgeVertex.assign(p.numEdges(), kNoIndex);
  map.edgeHalves.assign(p.numEdges(), kNoIndex);
  map.interiorOf.assign(p.numFaces(), kNoIndex);
  map.firstFaceOf.assign(p.numFaces(), kNoIndex);
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (!refine[f]) continue;
    const auto fv = p.triangleVertices(f);
    const auto fe = p.triangleEdges(f);
    for (int k = 0; k < 3; ++k) {
      assert(parent.isComplete(fv[k]) && "a refined face needs complete vertices");
      map.vertexChildOf[fv[k]] = 0;
      map.edgeVertex[fe[k]] = 0;
    }
  }
  const int d = parent.depth;
  const uint64_t parentVertices = counts.vertices(d), parentEdges = counts.edges(d);
  Index nv = 0, ne = 0, nf = 0;
  for (Index v = 0; v < p.numVertices; ++v) {
    if (map.vertexChildOf[v] == 0) map.vertexChildOf[v] = nv++;
  }
  const Index numVertexChildren = nv;
  for (Index e = 0; e < p.numEdges(); ++e) {
    if (map.edgeVertex[e] == 0) map.edgeVertex[e] = nv++, map.edgeHalves[e] = ne, ne += 2;
  }
  const Index numHalves = ne;
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (refine[f]) map.interiorOf[f] = ne, ne += 3, map.firstFaceOf[f] = nf, nf += 4;
  }

  child.depth = d + 1;
  child.vertexIds.resize(nv);
  child.origin.resize(nv);
  child.originKind.assign(nv, static_cast<uint8_t>(LevelCounts::Origin::kVertex));
  std::fill(child.originKind.begin() + numVertexChildren, child.originKind.end(),
            static_cast<uint8_t>(LevelCounts::Origin::kEdge));
  child.edgeIds.resize(ne);
  child.faceIds.resize(nf);
  child.faceParent.resize(nf / 4);
  for (Index v = 0; v < p.numVertices; ++v) {
    if (Index c = map.vertexChildOf[v]; c >= 0) child.vertexIds[c] = parent.vertexIds[v], child.origin[c] = v;
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
      child.edgeIds[map.interiorOf[f] + j] = 2 * parentEdges + 3 * parent.faceIds[f] + j;
    for (int k = 0; k < 4; ++k) child.faceIds[map.firstFaceOf[f] + k] = 4 * parent.faceIds[f] + k;
    child.faceParent[map.firstFaceOf[f] / 4] = f;
  }
  assert(numHalves <= ne);
  (void)numHalves;
  return map;
}

// The split of refined parent face f in the child numbering `links` gives
// (a ChildMap, or the parent's links; see completeValence).
template <typename Links>
FaceSplit faceSplitOf(const Level& p, const Links& links, Index f, Index firstInterior) {
  const auto fv = p.triangleVertices(f);
  const auto fe = p.triangleEdges(f);
  FaceSplit split;
  for (int j = 0; j < 3; ++j) {
    split.corners[j] = links.vertexChild(fv[j]);
    split.midpoints[j] = links.onEdge(fe[j]);
    split.halves[j] = links.halves(fe[j]);
  }
  split.firstInterior = firstInterior;
  split.firstFace = links.firstFace(f);
  split.sides = p.faceEdgeSides[f];
  return split;
}

// As refinement.cc's uniform version, through the child map.
void refineFacesAndEdges(const Level& p, const ChildMap& map, std::span<const uint8_t> refine, Level& c) {
  for (Index e = 0; e < p.numEdges(); ++e) {
    const Index h = map.edgeHalves[e];
    if (h < 0) continue;
    const auto& ev = p.edgeVertices[e];
    const auto& ef = p.edgeFaces[e];
    splitEdge(h, map.vertexChildOf[ev[0]], map.edgeVertex[e], map.vertexChildOf[ev[1]],
              {map.faceChild(ef[0]), map.faceChild(ef[1])}, p.edgeFaceLocal[e], c);
  }
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (refine[f]) splitFace(faceSplitOf(p, map, f, map.interiorOf[f]), c);
  }
}

// The ring rules of the triangle split (sparse_split.h).
struct TriangleRules {
  // The valence of child vertex v once its ring is whole, 0 while a face of
  // it is missing (the parent face around it has no children). `links`
  // gives the child numbering: a ChildMap while building, the parent's child
  // links while growing in place.
  template <typename Links>
  static int completeValence(const Level& p, const SparseLevel& child, const Links& links, Index v) {
    const Index o = child.origin[v];
    if (child.isVertexChild(v)) {
      for (Index f : p.ringFacesOf(o)) {
        if (f != kNoIndex && links.firstFace(f) < 0) return 0;
      }
      return p.valence(o);
    }
    const auto& ef = p.edgeFaces[o];
    if (links.firstFace(ef[0]) < 0) return 0;
    if (ef[1] == kNoIndex) return 4;
    return ef[1] >= 0 && links.firstFace(ef[1]) >= 0 ? 6 : 0;
  }

  // The size of child vertex v's whole ring: its row's length, whether the
  // level holds the ring yet or not (an edge without a second face in the
  // parent level may gain one; only a boundary edge never does).
  static int wholeValence(const Level& p, const SparseLevel& child, Index v) {
    const Index o = child.origin[v];
    if (child.isVertexChild(v)) return p.valence(o);
    return p.edgeFaces[o][1] == kNoIndex ? 4 : 6;
  }

  // The ring of complete child vertex v, in the order refinement.cc gives the
  // uniform level (so frames and limit tangents agree with it exactly).
  template <typename Links>
  static void writeCompleteRing(const Level& p, const SparseLevel& child, const Links& links, Index v,
                                Index* ringE, Index* ringV, Index* ringF, LocalIndex* ringL) {
    const Index o = child.origin[v];
    if (child.isVertexChild(v)) {
      writeVertexChildRing(
          p, o, [&](Index e) { return links.halves(e); }, [&](Index e) { return links.onEdge(e); },
          [&](Index f) { return links.firstFace(f); }, ringE, ringV, ringF, ringL);
      return;
    }
    // On parent edge o: the uniform level's order (refinement.h,
    // EdgeVertexRing) in this level's numbering.
    auto side = [&](Index f, int j) -> EdgeVertexRing::Side {
      const auto fe = p.triangleEdges(f);
      return {links.firstFace(f),
              links.interior(f),
              j,
              {links.onEdge(fe[(j + 1) % 3]), links.onEdge(fe[(j + 2) % 3])}};
    };
    const auto& ef = p.edgeFaces[o];
    const auto& el = p.edgeFaceLocal[o];
    const EdgeVertexRing ring{
        links.halves(o),
        {links.vertexChild(p.edgeVertices[o][0]), links.vertexChild(p.edgeVertices[o][1])},
        {side(ef[0], el[0]), ef[1] == kNoIndex ? EdgeVertexRing::Side{} : side(ef[1], el[1])}};
    writeEdgeVertexRing(ring, ringE, ringV, ringF, ringL);
  }
};

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
  for (Index v = 0; v < c.numVertices; ++v) {
    if (!child.isVertexChild(v)) continue;
    const Index o = child.origin[v];
    c.vertexSharpness[v] = inherit.vertexChildSharpness(o);
    c.vertexRules[v] = inherit.vertexChildRule(o);
  }
}

}  // namespace

SparseLevel refineSparseTriangles(SparseLevel& parent, std::span<const uint8_t> refine,
                                  const LevelCounts& counts, const LoopOptions& options) {
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
  sparse_split::writeRings(parent, map, TriangleRules{}, child);
  c.maxValence = std::max(parent.mesh.maxValence, 6);
  inheritSharpness(parent, map, options, child);
  child.firstChildFace.assign(nf, kNoIndex);
  parent.firstChildFace.assign(map.firstFaceOf.begin(), map.firstFaceOf.end());
  parent.childOfVertex.assign(map.vertexChildOf.begin(), map.vertexChildOf.end());
  parent.childOfEdge.assign(map.edgeVertex.begin(), map.edgeVertex.end());
  parent.halvesOfEdge.assign(map.edgeHalves.begin(), map.edgeHalves.end());
  sparse_split::orderIfUnsorted(child.vertexIds, child.vertexOrder);
  sparse_split::orderIfUnsorted(child.edgeIds, child.edgeOrder);
  sparse_split::orderIfUnsorted(child.faceIds, child.faceOrder);
  return child;
}

namespace {

// The child numbering as the parent's links hold it, once a level is built:
// what writeCompleteRing reads while the level grows in place.
struct ParentLinks {
  const SparseLevel& parent;
  const Level& child;
  Index vertexChild(Index v) const { return parent.childOfVertex[v]; }
  Index onEdge(Index e) const { return parent.childOfEdge[e]; }
  Index halves(Index e) const { return parent.halvesOfEdge[e]; }
  Index firstFace(Index f) const { return f < 0 ? f : parent.firstChildFace[f]; }
  // Interior edge 0 of a refined face is the second edge of its middle
  // child (refinement.h, splitFace).
  Index interior(Index f) const { return child.faceEdges[3 * (parent.firstChildFace[f] + 3) + 1]; }
  Index faceChild(Index f) const { return sparse_split::firstChildOrAbsent(parent.firstChildFace, f); }
};

}  // namespace

LevelExtension extendSparseTriangles(SparseLevel& parent, SparseLevel& child, std::span<const Index> faces,
                                     const LevelCounts& counts, const LoopOptions& options) {
  const Level& p = parent.mesh;
  Level& c = child.mesh;
  LevelExtension ext;
  const Index oldVertices = c.numVertices, oldEdges = c.numEdges(), oldFaces = c.numFaces();
  ext.firstNewVertex = oldVertices;
  if (faces.empty()) return ext;

  // Number what the new faces add: vertices, then halves and interior
  // edges, then faces, each appended.
  const int d = parent.depth;
  const uint64_t parentVertices = counts.vertices(d), parentEdges = counts.edges(d);
  SharpnessInheritance inherit(p, options);
  std::vector<Index> splitEdges;
  auto addVertex = [&](uint64_t id, Index origin, bool onEdge, float sharpness, VertexRule rule) {
    child.vertexIds.push_back(id);
    child.origin.push_back(origin);
    child.originKind.push_back(
        static_cast<uint8_t>(onEdge ? LevelCounts::Origin::kEdge : LevelCounts::Origin::kVertex));
    c.vertexSharpness.push_back(sharpness);
    c.vertexRules.push_back(rule);
    return c.numVertices++;
  };
  for (Index f : faces) {
    for (Index v : p.triangleVertices(f)) {
      assert(parent.isComplete(v) && "a refined face needs complete vertices");
      if (parent.childOfVertex[v] != kNoIndex) continue;
      parent.childOfVertex[v] = addVertex(parent.vertexIds[v], v, false, inherit.vertexChildSharpness(v),
                                          inherit.vertexChildRule(v));
    }
    for (Index e : p.triangleEdges(f)) {
      splitEdges.push_back(e);
      if (parent.childOfEdge[e] != kNoIndex) continue;
      parent.childOfEdge[e] =
          addVertex(parentVertices + parent.edgeIds[e], e, true, kSharpnessSmooth, inherit.edgeChildRule(e));
      parent.halvesOfEdge[e] = static_cast<Index>(child.edgeIds.size());
      child.edgeIds.push_back(2 * parent.edgeIds[e]);
      child.edgeIds.push_back(2 * parent.edgeIds[e] + 1);
      const bool smooth = isSmooth(p.edgeSharpness[e]);
      c.edgeSharpness.push_back(smooth ? kSharpnessSmooth : inherit.halfSharpness(e, 0));
      c.edgeSharpness.push_back(smooth ? kSharpnessSmooth : inherit.halfSharpness(e, 1));
    }
  }
  std::vector<Index> firstInterior(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) {
    const Index f = faces[i];
    firstInterior[i] = static_cast<Index>(child.edgeIds.size());
    for (int j = 0; j < 3; ++j) {
      child.edgeIds.push_back(2 * parentEdges + 3 * parent.faceIds[f] + j);
      c.edgeSharpness.push_back(kSharpnessSmooth);
    }
    parent.firstChildFace[f] = static_cast<Index>(child.faceIds.size());
    for (int k = 0; k < 4; ++k) child.faceIds.push_back(4 * parent.faceIds[f] + k);
    child.faceParent.push_back(f);
  }
  const Index nv = c.numVertices, ne = static_cast<Index>(child.edgeIds.size()),
              nf = static_cast<Index>(child.faceIds.size());
  c.faceVertices.resize(3 * static_cast<size_t>(nf));
  c.faceEdges.resize(3 * static_cast<size_t>(nf));
  c.faceEdgeSides.resize(nf);
  c.edgeVertices.resize(ne);
  c.edgeFaces.resize(ne);
  c.edgeFaceLocal.resize(ne);
  child.firstChildFace.resize(nf, kNoIndex);
  child.childOfVertex.resize(nv, kNoIndex);
  child.childOfEdge.resize(ne, kNoIndex);
  child.halvesOfEdge.resize(ne, kNoIndex);

  // The new faces, and every half along their edges: a half that was
  // there gains the face's child on its new side.
  const ParentLinks links{parent, c};
  for (size_t i = 0; i < faces.size(); ++i) splitFace(faceSplitOf(p, links, faces[i], firstInterior[i]), c);
  std::sort(splitEdges.begin(), splitEdges.end());
  splitEdges.erase(std::unique(splitEdges.begin(), splitEdges.end()), splitEdges.end());
  for (Index e : splitEdges) {
    const auto& ev = p.edgeVertices[e];
    const auto& ef = p.edgeFaces[e];
    splitEdge(parent.halvesOfEdge[e], parent.childOfVertex[ev[0]], parent.childOfEdge[e],
              parent.childOfVertex[ev[1]], {links.faceChild(ef[0]), links.faceChild(ef[1])},
              p.edgeFaceLocal[e], c);
  }

  sparse_split::growRings(parent, links, TriangleRules{}, oldVertices, oldFaces, child, ext.completed);
  c.maxValence = std::max({c.maxValence, p.maxValence, 6});

  sparse_split::mergeOrder(child.vertexIds, oldVertices, child.vertexOrder);
  sparse_split::mergeOrder(child.edgeIds, oldEdges, child.edgeOrder);
  sparse_split::mergeOrder(child.faceIds, oldFaces, child.faceOrder);
  return ext;
}

}  // namespace tessera
