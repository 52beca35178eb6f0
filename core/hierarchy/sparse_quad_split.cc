// Catmull-Clark's quad split of a sparse level (sparse_level.h), in the
// numbering of core/catmark/quad_split.h restricted to what is present:
// a refined face of n corners has n children, one per corner, around the
// vertex put in it; every vertex and edge it touches is split.
#include <algorithm>
#include <cassert>

#include "core/hierarchy/sparse_split.h"
#include "core/loop/sharpness_inheritance.h"
#include "core/topology/quad_split_parts.h"
#include "core/util/buffer.h"

namespace tessera {

namespace {

using topology::quadChildSlot;

constexpr auto kFromVertex = static_cast<uint8_t>(LevelCounts::Origin::kVertex);
constexpr auto kFromEdge = static_cast<uint8_t>(LevelCounts::Origin::kEdge);
constexpr auto kFromFace = static_cast<uint8_t>(LevelCounts::Origin::kFace);

// Local indices of everything the refined faces of a parent produce, as
// the split's parts read them (quad_split_parts.h).
// Of the parent's links' type, so that they are moved there once the level
// is built, not copied.
struct QuadChildMap {
  Buffer<Index> vertexChildOf;  // parent vertex -> child vertex
  Buffer<Index> faceVertexOf;   // parent face -> the vertex in it
  Buffer<Index> edgeVertexOf;   // parent edge -> the vertex on it
  Buffer<Index> edgeHalves;     // parent edge -> first of its two halves
  Buffer<Index> interiorOf;     // parent face -> first of its interior edges
  Buffer<Index> firstFaceOf;    // parent face -> first of its children
  Index vertexChild(Index v) const { return vertexChildOf[v]; }
  Index faceVertex(Index f) const { return faceVertexOf[f]; }
  Index edgeVertex(Index e) const { return edgeVertexOf[e]; }
  Index halves(Index e) const { return edgeHalves[e]; }
  Index firstFace(Index f) const { return sparse_split::firstChildOrAbsent(firstFaceOf, f); }
  Index interior(Index f) const { return interiorOf[f]; }
};

// The same numbering as the parent's links hold it once a level is built.
struct QuadParentLinks {
  const SparseLevel& parent;
  const Level& child;
  Index vertexChild(Index v) const { return parent.childOfVertex[v]; }
  Index faceVertex(Index f) const { return parent.childOfFace[f]; }
  Index edgeVertex(Index e) const { return parent.childOfEdge[e]; }
  Index halves(Index e) const { return parent.halvesOfEdge[e]; }
  Index firstFace(Index f) const { return sparse_split::firstChildOrAbsent(parent.firstChildFace, f); }
  // Interior edge 0 of a refined face is its child 0's edge at slot 1.
  Index interior(Index f) const {
    const Index first = parent.firstChildFace[f];
    return child.faceEdges[4 * first + quadChildSlot(parent.mesh.faceSize(f), 0, 1)];
  }
};

// While face `face` is split in place its children's edges are not written
// yet: its interior edges are where they were numbered.
struct SplittingLinks : QuadParentLinks {
  Index face, firstInterior;
  Index interior(Index f) const { return f == face ? firstInterior : QuadParentLinks::interior(f); }
};

// The ring rules of the quad split (sparse_split.h).
struct QuadRules {
  template <typename Links>
  static int completeValence(const Level& p, const SparseLevel& child, const Links& links, Index v) {
    const Index o = child.origin[v];
    switch (child.originKind[v]) {
      case kFromVertex:
        for (Index f : p.ringFacesOf(o)) {
          if (f != kNoIndex && links.firstFace(f) < 0) return 0;
        }
        return p.valence(o);
      case kFromFace:
        return p.faceSize(o);  // its ring is its face's children, present with it
      default: {
        const auto& ef = p.edgeFaces[o];
        if (links.firstFace(ef[0]) < 0) return 0;
        if (ef[1] == kNoIndex) return 3;
        return links.firstFace(ef[1]) >= 0 ? 4 : 0;
      }
    }
  }
  static int wholeValence(const Level& p, const SparseLevel& child, Index v) {
    const Index o = child.origin[v];
    switch (child.originKind[v]) {
      case kFromVertex:
        return p.valence(o);
      case kFromFace:
        return p.faceSize(o);
      default:
        return topology::quadEdgeVertexValence(p, o);
    }
  }
  template <typename Links>
  static void writeCompleteRing(const Level& p, const SparseLevel& child, const Links& links, Index v,
                                Index* ringE, Index* ringV, Index* ringF, LocalIndex* ringL) {
    const Index o = child.origin[v];
    switch (child.originKind[v]) {
      case kFromVertex:
        topology::writeQuadVertexChildRing(p, o, links, ringE, ringV, ringF, ringL);
        return;
      case kFromFace:
        topology::writeQuadFaceVertexRing(p, o, links, ringE, ringV, ringF, ringL);
        return;
      default:
        topology::writeQuadEdgeVertexRing(p, o, links, ringE, ringV, ringF, ringL);
    }
  }
};

// Vertices, edges and faces of the child, with their canonical ids, in the
// order of sparse_level.h.
QuadChildMap numberChildren(const SparseLevel& parent, std::span<const uint8_t> refine,
                            const LevelCounts& counts, SparseLevel& child) {
  const Level& p = parent.mesh;
  QuadChildMap map;
  map.vertexChildOf.assign(p.numVertices, kNoIndex);
  map.faceVertexOf.assign(p.numFaces(), kNoIndex);
  map.edgeVertexOf.assign(p.numEdges(), kNoIndex);
  map.edgeHalves.assign(p.numEdges(), kNoIndex);
  map.interiorOf.assign(p.numFaces(), kNoIndex);
  map.firstFaceOf.assign(p.numFaces(), kNoIndex);
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (!refine[f]) continue;
    for (Index v : p.faceVerticesOf(f)) {
      assert(parent.isComplete(v) && "a refined face needs complete vertices");
      map.vertexChildOf[v] = 0;
    }
    for (Index e : p.faceEdgesOf(f)) map.edgeVertexOf[e] = 0;
  }
  const int d = parent.depth;
  const uint64_t parentVertices = counts.vertices(d), parentFaces = counts.faces(d),
                 parentCorners = counts.corners(d);
  Index nv = 0, ne = 0, nf = 0;
  for (Index v = 0; v < p.numVertices; ++v) {
    if (map.vertexChildOf[v] == 0) map.vertexChildOf[v] = nv++;
  }
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (refine[f]) map.faceVertexOf[f] = nv++;
  }
  for (Index e = 0; e < p.numEdges(); ++e) {
    if (map.edgeVertexOf[e] == 0) map.edgeVertexOf[e] = nv++;
  }
  bool fours = true;
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (!refine[f]) continue;
    const int n = p.faceSize(f);
    map.interiorOf[f] = ne, ne += n;
    map.firstFaceOf[f] = nf, nf += n;
    fours = fours && n == 4;
  }
  for (Index e = 0; e < p.numEdges(); ++e) {
    if (map.edgeVertexOf[e] >= 0) map.edgeHalves[e] = ne, ne += 2;
  }

  child.depth = d + 1;
  child.vertexIds.resize(nv);
  child.origin.resize(nv);
  child.originKind.resize(nv);
  child.edgeIds.resize(ne);
  child.faceIds.resize(nf);
  child.facesPerParent = fours ? 4 : 1;
  child.faceParent.resize(fours ? nf / 4 : nf);
  for (Index v = 0; v < p.numVertices; ++v) {
    if (const Index c = map.vertexChildOf[v]; c >= 0) {
      child.vertexIds[c] = parent.vertexIds[v], child.origin[c] = v, child.originKind[c] = kFromVertex;
    }
  }
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (!refine[f]) continue;
    const Index c = map.faceVertexOf[f];
    child.vertexIds[c] = parentVertices + parent.faceIds[f];
    child.origin[c] = f, child.originKind[c] = kFromFace;
    const uint64_t first = counts.firstChildFace(FaceId(d, parent.faceIds[f]));
    for (int j = 0; j < p.faceSize(f); ++j) {
      child.edgeIds[map.interiorOf[f] + j] = first + j;
      child.faceIds[map.firstFaceOf[f] + j] = first + j;
      if (!fours) child.faceParent[map.firstFaceOf[f] + j] = f;
    }
    if (fours) child.faceParent[map.firstFaceOf[f] / 4] = f;
  }
  for (Index e = 0; e < p.numEdges(); ++e) {
    const Index c = map.edgeVertexOf[e];
    if (c < 0) continue;
    child.vertexIds[c] = parentVertices + parentFaces + parent.edgeIds[e];
    child.origin[c] = e, child.originKind[c] = kFromEdge;
    child.edgeIds[map.edgeHalves[e]] = parentCorners + 2 * parent.edgeIds[e];
    child.edgeIds[map.edgeHalves[e] + 1] = parentCorners + 2 * parent.edgeIds[e] + 1;
  }
  return map;
}

// Sharpness and rules of the new elements: halves and the children of
// parent vertices inherit theirs (Sdc semantics, sharpness_inheritance.h),
// the vertex on an edge takes its rule from the halves, and everything
// inside a face is smooth.
struct QuadSharpness {
  SharpnessInheritance inherit;
  void vertex(const SparseLevel& child, Index v, Level& c) {
    const Index o = child.origin[v];
    switch (child.originKind[v]) {
      case kFromVertex:
        c.vertexSharpness[v] = inherit.vertexChildSharpness(o);
        c.vertexRules[v] = inherit.vertexChildRule(o);
        return;
      case kFromFace:
        c.vertexSharpness[v] = kSharpnessSmooth;
        c.vertexRules[v] = VertexRule::kSmooth;
        return;
      default:
        c.vertexSharpness[v] = kSharpnessSmooth;
        c.vertexRules[v] = inherit.edgeChildRule(o);
    }
  }
  void halves(const Level& p, Index e, Index h, Level& c) {
    const bool smooth = isSmooth(p.edgeSharpness[e]);
    c.edgeSharpness[h] = smooth ? kSharpnessSmooth : inherit.halfSharpness(e, 0);
    c.edgeSharpness[h + 1] = smooth ? kSharpnessSmooth : inherit.halfSharpness(e, 1);
  }
};

void sizeQuadLevel(SparseLevel& child, Index numVertices) {
  Level& c = child.mesh;
  c.numVertices = numVertices;
  c.regularFaceSize = 4;
  c.maxFaceSize = 4;
  const size_t nf = child.faceIds.size(), ne = child.edgeIds.size();
  c.faceVertices.resize(4 * nf);
  c.faceEdges.resize(4 * nf);
  c.edgeVertices.resize(ne);
  c.edgeFaces.resize(ne);
  c.edgeFaceLocal.resize(ne);
  c.edgeSharpness.resize(ne, kSharpnessSmooth);
  c.vertexSharpness.resize(numVertices);
  c.vertexRules.resize(numVertices);
}

}  // namespace

SparseLevel refineSparseQuads(SparseLevel& parent, std::span<const uint8_t> refine, const LevelCounts& counts,
                              const LoopOptions& options) {
  SparseLevel child;
  QuadChildMap map = numberChildren(parent, refine, counts, child);
  const Level& p = parent.mesh;
  Level& c = child.mesh;
  sizeQuadLevel(child, static_cast<Index>(child.vertexIds.size()));
  for (Index f = 0; f < p.numFaces(); ++f) {
    if (!refine[f]) continue;
    topology::splitQuadFace(p, f, map, true, c);
    topology::splitQuadFaceEdges(p, f, map, c);
  }
  for (Index e = 0; e < p.numEdges(); ++e) {
    if (map.edgeHalves[e] >= 0) topology::splitQuadEdge(p, e, map, kAbsentFace, c);
  }
  sparse_split::writeRings(parent, map, QuadRules{}, child);
  c.maxValence = std::max({p.maxValence, p.maxFaceSize, 4});
  QuadSharpness sharpness{SharpnessInheritance(p, options)};
  for (Index v = 0; v < c.numVertices; ++v) sharpness.vertex(child, v, c);
  for (Index e = 0; e < p.numEdges(); ++e) {
    if (map.edgeHalves[e] >= 0) sharpness.halves(p, e, map.edgeHalves[e], c);
  }
  child.firstChildFace.assign(child.faceIds.size(), kNoIndex);
  parent.firstChildFace = std::move(map.firstFaceOf);
  parent.childOfVertex = std::move(map.vertexChildOf);
  parent.childOfEdge = std::move(map.edgeVertexOf);
  parent.childOfFace = std::move(map.faceVertexOf);
  parent.halvesOfEdge = std::move(map.edgeHalves);
  sparse_split::orderIfUnsorted(child.vertexIds, child.vertexOrder);
  sparse_split::orderIfUnsorted(child.edgeIds, child.edgeOrder);
  sparse_split::orderIfUnsorted(child.faceIds, child.faceOrder);
  return child;
}

LevelExtension extendSparseQuads(SparseLevel& parent, SparseLevel& child, std::span<const Index> faces,
                                 const LevelCounts& counts, const LoopOptions& options) {
  const Level& p = parent.mesh;
  Level& c = child.mesh;
  LevelExtension ext;
  const Index oldVertices = c.numVertices, oldEdges = c.numEdges(), oldFaces = c.numFaces();
  ext.firstNewVertex = oldVertices;
  if (faces.empty()) return ext;
  parent.childOfFace.resize(p.numFaces(), kNoIndex);

  // Number what the new faces add, each kind appended: vertices, then
  // interior edges and halves, then faces.
  const int d = parent.depth;
  const uint64_t parentVertices = counts.vertices(d), parentFaces = counts.faces(d),
                 parentCorners = counts.corners(d);
  std::vector<Index> splitEdges;
  auto addVertex = [&](uint64_t id, Index origin, uint8_t kind) {
    child.vertexIds.push_back(id);
    child.origin.push_back(origin);
    child.originKind.push_back(kind);
    return static_cast<Index>(child.vertexIds.size()) - 1;
  };
  auto addHalves = [&](Index e) {
    parent.halvesOfEdge[e] = static_cast<Index>(child.edgeIds.size());
    child.edgeIds.push_back(parentCorners + 2 * parent.edgeIds[e]);
    child.edgeIds.push_back(parentCorners + 2 * parent.edgeIds[e] + 1);
  };
  for (Index f : faces) {
    for (Index v : p.faceVerticesOf(f)) {
      assert(parent.isComplete(v) && "a refined face needs complete vertices");
      if (parent.childOfVertex[v] == kNoIndex)
        parent.childOfVertex[v] = addVertex(parent.vertexIds[v], v, kFromVertex);
    }
    parent.childOfFace[f] = addVertex(parentVertices + parent.faceIds[f], f, kFromFace);
    for (Index e : p.faceEdgesOf(f)) {
      splitEdges.push_back(e);
      if (parent.childOfEdge[e] != kNoIndex) continue;
      parent.childOfEdge[e] = addVertex(parentVertices + parentFaces + parent.edgeIds[e], e, kFromEdge);
      addHalves(e);
    }
  }
  bool fours = child.facesPerParent == 4;
  for (Index f : faces) fours = fours && p.faceSize(f) == 4;
  if (!fours && child.facesPerParent == 4) {
    // A base level's other polygon arrives: one parent entry per child from now on.
    Buffer<Index> perChild(child.faceIds.size());
    for (size_t k = 0; k < perChild.size(); ++k) perChild[k] = child.faceParent[k / 4];
    child.faceParent = std::move(perChild);
    child.facesPerParent = 1;
  }
  std::vector<Index> firstInterior;
  for (Index f : faces) {
    const int n = p.faceSize(f);
    const uint64_t first = counts.firstChildFace(FaceId(d, parent.faceIds[f]));
    firstInterior.push_back(static_cast<Index>(child.edgeIds.size()));
    for (int j = 0; j < n; ++j) child.edgeIds.push_back(first + j);
    parent.firstChildFace[f] = static_cast<Index>(child.faceIds.size());
    for (int j = 0; j < n; ++j) {
      child.faceIds.push_back(first + j);
      if (!fours) child.faceParent.push_back(f);
    }
    if (fours) child.faceParent.push_back(f);
  }
  sizeQuadLevel(child, static_cast<Index>(child.vertexIds.size()));
  const Index nv = c.numVertices, ne = static_cast<Index>(child.edgeIds.size()),
              nf = static_cast<Index>(child.faceIds.size());
  child.firstChildFace.resize(nf, kNoIndex);
  child.childOfVertex.resize(nv, kNoIndex);
  child.childOfEdge.resize(ne, kNoIndex);
  child.halvesOfEdge.resize(ne, kNoIndex);
  child.childOfFace.resize(nf, kNoIndex);

  // The new faces (their edges first, so that interior() reads them), and
  // every half along their edges: a half that was there gains the face's
  // child on its new side.
  const QuadParentLinks links{parent, c};
  for (size_t i = 0; i < faces.size(); ++i)
    topology::splitQuadFace(p, faces[i], SplittingLinks{links, faces[i], firstInterior[i]}, true, c);
  for (Index f : faces) topology::splitQuadFaceEdges(p, f, links, c);
  std::sort(splitEdges.begin(), splitEdges.end());
  splitEdges.erase(std::unique(splitEdges.begin(), splitEdges.end()), splitEdges.end());
  for (Index e : splitEdges) topology::splitQuadEdge(p, e, links, kAbsentFace, c);

  QuadSharpness sharpness{SharpnessInheritance(p, options)};
  for (Index v = oldVertices; v < nv; ++v) sharpness.vertex(child, v, c);
  for (Index e : splitEdges) {
    if (parent.halvesOfEdge[e] >= oldEdges) sharpness.halves(p, e, parent.halvesOfEdge[e], c);
  }
  sparse_split::growRings(parent, links, QuadRules{}, oldVertices, oldFaces, child, ext.completed);
  c.maxValence = std::max({c.maxValence, p.maxValence, p.maxFaceSize, 4});

  sparse_split::mergeOrder(child.vertexIds, oldVertices, child.vertexOrder);
  sparse_split::mergeOrder(child.edgeIds, oldEdges, child.edgeOrder);
  sparse_split::mergeOrder(child.faceIds, oldFaces, child.faceOrder);
  return ext;
}

}  // namespace tessera
