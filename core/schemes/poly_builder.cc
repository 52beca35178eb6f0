#include "core/schemes/poly_builder.h"

#include <algorithm>
#include <string>

namespace tessera::schemes {

PolyTopology PolyTopology::fromBaseMesh(const BaseMesh& mesh) {
  PolyTopology topology;
  topology.numVertices = mesh.numVertices();
  for (const auto& t : mesh.faceVertexIndices()) topology.addFace(t);
  const TriMesh& m = mesh.mesh();
  for (auto eh : m.edges()) {
    const float s = mesh.edgeSharpness(eh);
    if (!isSharp(s)) continue;
    auto heh = m.halfedge_handle(eh, 0);
    topology.creases.push_back({m.from_vertex_handle(heh).idx(), m.to_vertex_handle(heh).idx(), s});
  }
  topology.vertexSharpness.resize(topology.numVertices);
  for (auto vh : m.vertices()) topology.vertexSharpness[vh.idx()] = mesh.vertexSharpness(vh);
  return topology;
}

PolyTopology PolyTopology::fromSoup(const PolygonSoup& soup) {
  PolyTopology topology;
  topology.numVertices = static_cast<int>(soup.points.size());
  topology.faceOffsets.assign(soup.faceOffsets.begin(), soup.faceOffsets.end());
  topology.indices = soup.indices;
  return topology;
}

namespace {

std::string edgeName(Index a, Index b) {
  return "edge " + std::to_string(a) + "-" + std::to_string(b);
}

Status checkFaces(const PolyTopology& t, PolyLevel& level) {
  const int nF = t.numFaces();
  if (nF <= 0) return invalidMesh("no faces");
  if (t.numVertices <= 0) return invalidMesh("no vertices");
  level.faceOffsets.resize(nF + 1);
  level.faceOffsets[0] = 0;
  level.maxFaceSize = 0;
  for (int f = 0; f < nF; ++f) {
    const int from = t.faceOffsets[f], to = t.faceOffsets[f + 1];
    const int n = to - from;
    if (n < 3)
      return invalidMesh("face " + std::to_string(f) + " has " + std::to_string(n) +
                         " corners (3 or more needed)");
    if (n > kMaxFaceSize) return invalidMesh("face " + std::to_string(f) + " has more than 65535 corners");
    for (int k = from; k < to; ++k) {
      const int v = t.indices[k];
      if (v < 0 || v >= t.numVertices) {
        return invalidMesh("face " + std::to_string(f) + " names vertex " + std::to_string(v) +
                           ", out of range 0.." + std::to_string(t.numVertices - 1));
      }
      for (int j = from; j < k; ++j) {
        if (t.indices[j] == v) {
          return invalidMesh("face " + std::to_string(f) + " uses vertex " + std::to_string(v) +
                             " twice (degenerate)");
        }
      }
    }
    level.faceOffsets[f + 1] = to;
    level.maxFaceSize = std::max(level.maxFaceSize, n);
  }
  level.faceVertices.assign(t.indices.begin(), t.indices.end());
  return Status::ok();
}

// Edges in order of first use, edge faces in face order (as Vtr builds them).
Status buildEdges(const PolyTopology& t, PolyLevel& level, std::vector<Index>& edgesAtOffset,
                  std::vector<Index>& edgesAt, std::vector<Index>& edgesAtCount) {
  const int nV = t.numVertices;
  const int nF = level.numFaces();
  std::vector<Index> corners(nV + 1, 0);
  for (Index v : level.faceVertices) ++corners[v + 1];
  // Two edges per face corner at most: no hash table needed.
  edgesAtOffset.assign(nV + 1, 0);
  for (int v = 0; v < nV; ++v) edgesAtOffset[v + 1] = edgesAtOffset[v] + 2 * corners[v + 1];
  edgesAt.assign(edgesAtOffset[nV], kNoIndex);
  edgesAtCount.assign(nV, 0);
  level.faceEdges.resize(level.faceVertices.size());
  // A closed mesh has corners / 2 edges, an open one at most corners: no regrowth.
  const size_t maxEdges = level.faceVertices.size();
  level.edgeVertices.reserve(maxEdges);
  level.edgeFaces.reserve(maxEdges);
  level.edgeFaceLocal.reserve(maxEdges);
  for (Index f = 0; f < nF; ++f) {
    const Index o = level.faceOffsets[f];
    const int n = level.faceSize(f);
    for (int j = 0; j < n; ++j) {
      const Index a = level.faceVertices[o + j], b = level.faceVertices[o + (j + 1) % n];
      Index e = kNoIndex;
      for (Index k = 0; k < edgesAtCount[a]; ++k) {
        const Index c = edgesAt[edgesAtOffset[a] + k];
        if ((level.edgeVertices[c][0] ^ level.edgeVertices[c][1] ^ a) == b) {
          e = c;
          break;
        }
      }
      if (e == kNoIndex) {
        e = level.numEdges();
        level.edgeVertices.push_back({a, b});
        level.edgeFaces.push_back({f, kNoIndex});
        level.edgeFaceLocal.push_back({static_cast<LocalIndex>(j), 0});
        edgesAt[edgesAtOffset[a] + edgesAtCount[a]++] = e;
        edgesAt[edgesAtOffset[b] + edgesAtCount[b]++] = e;
      } else {
        auto& ef = level.edgeFaces[e];
        if (ef[1] != kNoIndex || ef[0] == f) {
          return invalidMesh(edgeName(a, b) + " is non-manifold: used by faces " + std::to_string(ef[0]) +
                             ", " + std::to_string(ef[1] == kNoIndex ? f : ef[1]) + " and " +
                             std::to_string(f));
        }
        if (level.edgeVertices[e][0] == a) {
          return invalidMesh("faces " + std::to_string(ef[0]) + " and " + std::to_string(f) +
                             " are inconsistently oriented across " + edgeName(a, b));
        }
        ef[1] = f;
        level.edgeFaceLocal[e][1] = static_cast<LocalIndex>(j);
      }
      level.faceEdges[o + j] = e;
    }
  }
  return Status::ok();
}

// Orders each vertex's faces and edges counter-clockwise (Vtr's
// orderVertexFacesAndEdges); a vertex whose faces do not form one fan is
// non-manifold.
Status buildRings(const PolyTopology& t, PolyLevel& level, const std::vector<Index>& edgesAtCount) {
  const int nV = t.numVertices;
  const int nF = level.numFaces();
  // Faces at each vertex in face order, with v's corner in each.
  std::vector<Index> facesAtOffset(nV + 1, 0);
  for (Index v : level.faceVertices) ++facesAtOffset[v + 1];
  for (int v = 0; v < nV; ++v) facesAtOffset[v + 1] += facesAtOffset[v];
  std::vector<Index> facesAt(facesAtOffset[nV]), cornersAt(facesAtOffset[nV]);
  {
    std::vector<Index> fill(facesAtOffset.begin(), facesAtOffset.end() - 1);
    for (Index f = 0; f < nF; ++f) {
      auto fv = level.faceVerticesOf(f);
      for (int c = 0; c < static_cast<int>(fv.size()); ++c) {
        facesAt[fill[fv[c]]] = f;
        cornersAt[fill[fv[c]]++] = c;
      }
    }
  }
  auto cornerOf = [&](Index f, Index v) {
    for (Index k = facesAtOffset[v]; k < facesAtOffset[v + 1]; ++k) {
      if (facesAt[k] == f) return static_cast<int>(cornersAt[k]);
    }
    return -1;
  };

  level.ringOffsets.resize(nV + 1);
  level.ringOffsets[0] = 0;
  for (int v = 0; v < nV; ++v) {
    if (edgesAtCount[v] == 0) {
      return invalidMesh("vertex " + std::to_string(v) + " is used by no face (unused vertex)");
    }
    level.ringOffsets[v + 1] = level.ringOffsets[v] + edgesAtCount[v];
  }
  const Index total = level.ringOffsets[nV];
  level.ringEdges.resize(total);
  level.ringVertices.resize(total);
  level.ringFaces.resize(total);
  level.ringFaceLocal.resize(total);
  level.maxValence = 0;
  auto nonManifold = [](Index v) {
    return invalidMesh("vertex " + std::to_string(v) + " is non-manifold (its faces do not form one fan)");
  };
  for (Index v = 0; v < nV; ++v) {
    const int n = edgesAtCount[v];
    const int faces = facesAtOffset[v + 1] - facesAtOffset[v];
    const bool boundary = n != faces;
    if (boundary && n != faces + 1) return nonManifold(v);
    level.maxValence = std::max(level.maxValence, n);
    Index f = facesAt[facesAtOffset[v]];
    int c = cornersAt[facesAtOffset[v]];
    if (boundary) {
      // Start at the boundary edge that leaves v in its face.
      f = kNoIndex;
      for (Index k = facesAtOffset[v]; k < facesAtOffset[v + 1] && f == kNoIndex; ++k) {
        const Index e = level.faceEdges[level.faceOffsets[facesAt[k]] + cornersAt[k]];
        if (level.isBoundaryEdge(e)) f = facesAt[k], c = cornersAt[k];
      }
      if (f == kNoIndex) return nonManifold(v);
    }
    const Index o = level.ringOffsets[v];
    Index e = level.faceEdges[level.faceOffsets[f] + c];
    const Index first = e;
    for (int k = 0; k < n; ++k) {
      level.ringEdges[o + k] = e;
      level.ringVertices[o + k] = level.edgeVertices[e][0] ^ level.edgeVertices[e][1] ^ v;
      if (f == kNoIndex) {
        if (k != n - 1) return nonManifold(v);
        level.ringFaces[o + k] = kNoIndex;
        level.ringFaceLocal[o + k] = 0;
        break;
      }
      level.ringFaces[o + k] = f;
      level.ringFaceLocal[o + k] = static_cast<LocalIndex>(c);
      const int size = level.faceSize(f);
      const Index next = level.faceEdges[level.faceOffsets[f] + (c + size - 1) % size];
      if (k + 1 < n && next == first) return nonManifold(v);
      e = next;
      const auto& ef = level.edgeFaces[e];
      f = ef[0] == f ? ef[1] : ef[0];
      if (f != kNoIndex) c = cornerOf(f, v);
    }
    if (!boundary && e != first) return nonManifold(v);
  }
  return Status::ok();
}

Index findEdge(const PolyLevel& level, Index a, Index b) {
  for (Index e : level.ringEdgesOf(a)) {
    if ((level.edgeVertices[e][0] ^ level.edgeVertices[e][1] ^ a) == b) return e;
  }
  return kNoIndex;
}

Status applySharpness(const PolyTopology& t, const CreaseOptions& options, PolyLevel& level) {
  const int nV = t.numVertices;
  level.edgeSharpness.assign(level.numEdges(), kSharpnessSmooth);
  level.vertexSharpness.assign(nV, kSharpnessSmooth);
  for (size_t i = 0; i < t.creases.size(); ++i) {
    const auto& c = t.creases[i];
    if (c.v0 < 0 || c.v0 >= nV || c.v1 < 0 || c.v1 >= nV) {
      return invalidMesh("crease " + std::to_string(i) + " names " + edgeName(c.v0, c.v1) + ", out of range");
    }
    const Index e = findEdge(level, c.v0, c.v1);
    if (e == kNoIndex)
      return invalidMesh("crease " + std::to_string(i) + ": " + edgeName(c.v0, c.v1) + " does not exist");
    level.edgeSharpness[e] = canonicalSharpness(c.sharpness);
  }
  if (!t.vertexSharpness.empty()) {
    if (static_cast<int>(t.vertexSharpness.size()) != nV) {
      return invalidArgument("vertex sharpness given for " + std::to_string(t.vertexSharpness.size()) +
                             " vertices, the mesh has " + std::to_string(nV));
    }
    for (int v = 0; v < nV; ++v) level.vertexSharpness[v] = canonicalSharpness(t.vertexSharpness[v]);
  }
  for (Index e = 0; e < level.numEdges(); ++e) {
    if (level.isBoundaryEdge(e)) level.edgeSharpness[e] = kSharpnessInfinite;
  }
  level.vertexRules.resize(nV);
  for (Index v = 0; v < nV; ++v) {
    if (options.boundary == BoundaryInterpolation::kEdgeAndCorner && level.valence(v) == 2 &&
        level.isBoundaryVertex(v)) {
      level.vertexSharpness[v] = kSharpnessInfinite;
    }
    int sharp = 0;
    for (Index e : level.ringEdgesOf(v)) sharp += isSharp(level.edgeSharpness[e]) ? 1 : 0;
    level.vertexRules[v] = vertexRule(level.vertexSharpness[v], sharp);
  }
  return Status::ok();
}

}  // namespace

Expected<PolyLevel> buildPolyLevel(const PolyTopology& topology, const CreaseOptions& options) {
  PolyLevel level;
  level.numVertices = topology.numVertices;
  TESSERA_RETURN_IF_ERROR(checkFaces(topology, level));
  std::vector<Index> edgesAtOffset, edgesAt, edgesAtCount;
  TESSERA_RETURN_IF_ERROR(buildEdges(topology, level, edgesAtOffset, edgesAt, edgesAtCount));
  TESSERA_RETURN_IF_ERROR(buildRings(topology, level, edgesAtCount));
  TESSERA_RETURN_IF_ERROR(applySharpness(topology, options, level));
  return level;
}

}  // namespace tessera::schemes
