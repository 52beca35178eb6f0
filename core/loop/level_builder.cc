#include "core/loop/level_builder.h"

#include <string>

namespace tessera {

BaseTopology BaseTopology::fromBaseMesh(const BaseMesh& mesh) {
  BaseTopology topology;
  topology.numVertices = mesh.numVertices();
  topology.triangles = mesh.faceVertexIndices();
  const TriMesh& m = mesh.mesh();
  for (auto eh : m.edges()) {
    float s = mesh.edgeSharpness(eh);
    if (isSharp(s)) {
      auto heh = m.halfedge_handle(eh, 0);
      topology.creases.push_back({m.from_vertex_handle(heh).idx(), m.to_vertex_handle(heh).idx(), s});
    }
  }
  topology.vertexSharpness.resize(topology.numVertices);
  for (auto vh : m.vertices()) topology.vertexSharpness[vh.idx()] = mesh.vertexSharpness(vh);
  return topology;
}

namespace {

std::string vertexName(int v) {
  return "vertex " + std::to_string(v);
}

// Finds edge (a, b) among the edges already created at vertex a.
Index findEdge(const Level& level, const std::vector<Index>& edgesAt, const std::vector<Index>& edgesAtCount,
               const std::vector<Index>& edgesAtOffset, Index a, Index b) {
  for (Index k = 0; k < edgesAtCount[a]; ++k) {
    Index e = edgesAt[edgesAtOffset[a] + k];
    if (level.otherVertex(e, a) == b) return e;
  }
  return kInvalidIndex;
}

Status buildEdges(int numVertices, Level& level, const std::vector<Index>& facesAtCount) {
  // Each face contributes two edges at each of its corners, which bounds the
  // edges per vertex without a hash table.
  std::vector<Index> edgesAtOffset(numVertices + 1, 0);
  for (int v = 0; v < numVertices; ++v) edgesAtOffset[v + 1] = edgesAtOffset[v] + 2 * facesAtCount[v];
  std::vector<Index> edgesAt(edgesAtOffset[numVertices]);
  std::vector<Index> edgesAtCount(numVertices, 0);

  const int numFaces = level.numFaces();
  level.faceEdges.resize(numFaces);
  level.faceEdgeSides.assign(numFaces, 0);
  level.edgeVertices.reserve(numFaces * 3 / 2 + 3);
  level.edgeFaces.reserve(numFaces * 3 / 2 + 3);
  level.edgeFaceLocal.reserve(numFaces * 3 / 2 + 3);
  for (Index f = 0; f < numFaces; ++f) {
    const auto& fv = level.faceVertices[f];
    for (int j = 0; j < 3; ++j) {
      Index a = fv[j], b = fv[(j + 1) % 3];
      Index e = findEdge(level, edgesAt, edgesAtCount, edgesAtOffset, a, b);
      if (e == kInvalidIndex) {
        e = level.numEdges();
        level.edgeVertices.push_back({a, b});
        level.edgeFaces.push_back({f, kInvalidIndex});
        level.edgeFaceLocal.push_back({static_cast<uint8_t>(j), 0});
        edgesAt[edgesAtOffset[a] + edgesAtCount[a]++] = e;
        edgesAt[edgesAtOffset[b] + edgesAtCount[b]++] = e;
      } else {
        auto& ef = level.edgeFaces[e];
        if (ef[1] != kInvalidIndex) {
          return invalidMesh("edge " + std::to_string(a) + "-" + std::to_string(b) +
                             " is non-manifold: used by faces " + std::to_string(ef[0]) + ", " +
                             std::to_string(ef[1]) + " and " + std::to_string(f));
        }
        // A consistently oriented neighbour traverses the shared edge the other way.
        if (level.edgeVertices[e][0] == a) {
          return invalidMesh("faces " + std::to_string(ef[0]) + " and " + std::to_string(f) +
                             " are inconsistently oriented across edge " + std::to_string(a) + "-" +
                             std::to_string(b));
        }
        ef[1] = f;
        level.edgeFaceLocal[e][1] = static_cast<uint8_t>(j);
        level.faceEdgeSides[f] |= static_cast<uint8_t>(1u << j);
      }
      level.faceEdges[f][j] = e;
    }
  }
  return Status::ok();
}

// Orders the ring of every vertex counter-clockwise (see level.h).
Status orderRings(int numVertices, Level& level, const std::vector<Index>& facesAtOffset,
                  const std::vector<Index>& facesAt) {
  // A manifold vertex has as many edges as faces (interior) or one more (boundary).
  std::vector<Index> edgeCount(numVertices, 0);
  for (const auto& ev : level.edgeVertices) {
    ++edgeCount[ev[0]];
    ++edgeCount[ev[1]];
  }
  level.ringOffsets.assign(numVertices + 1, 0);
  for (int v = 0; v < numVertices; ++v) level.ringOffsets[v + 1] = level.ringOffsets[v] + edgeCount[v];
  level.ringEdges.resize(level.ringOffsets[numVertices]);
  level.ringVertices.resize(level.ringOffsets[numVertices]);
  level.ringFaces.resize(level.ringOffsets[numVertices]);
  level.ringFaceLocal.resize(level.ringOffsets[numVertices]);

  for (Index v = 0; v < numVertices; ++v) {
    const Index faceCount = facesAtOffset[v + 1] - facesAtOffset[v];
    const Index n = edgeCount[v];
    const bool boundary = (n == faceCount + 1);
    if (n != faceCount && !boundary) {
      return invalidMesh(vertexName(v) + " is non-manifold: its " + std::to_string(faceCount) +
                         " faces form more than one fan");
    }
    Index start = facesAt[facesAtOffset[v]];  // lowest-numbered face (OpenSubdiv's choice)
    if (boundary) {
      start = kInvalidIndex;
      for (Index k = facesAtOffset[v]; k < facesAtOffset[v + 1]; ++k) {
        Index f = facesAt[k];
        if (level.isBoundaryEdge(level.faceEdges[f][level.vertexInFace(f, v)])) {
          start = f;
          break;
        }
      }
      if (start == kInvalidIndex) {
        return invalidMesh(vertexName(v) + " is non-manifold: no leading boundary edge");
      }
    }
    Index* ringE = level.ringEdges.data() + level.ringOffsets[v];
    Index* ringV = level.ringVertices.data() + level.ringOffsets[v];
    Index* ringF = level.ringFaces.data() + level.ringOffsets[v];
    uint8_t* ringL = level.ringFaceLocal.data() + level.ringOffsets[v];
    Index f = start;
    Index k = 0;
    for (;;) {
      if (k >= n) {
        return invalidMesh(vertexName(v) + " is non-manifold: its faces do not form a single fan");
      }
      int j = level.vertexInFace(f, v);
      ringE[k] = level.faceEdges[f][j];
      ringV[k] = level.faceVertices[f][(j + 1) % 3];
      ringF[k] = f;
      ringL[k] = static_cast<uint8_t>(j);
      ++k;
      Index trailing = level.faceEdges[f][(j + 2) % 3];
      const auto& ef = level.edgeFaces[trailing];
      Index next = (ef[0] == f) ? ef[1] : ef[0];
      if (next == kInvalidIndex) {
        if (k >= n) return invalidMesh(vertexName(v) + " is non-manifold: its faces form more than one fan");
        ringE[k] = trailing;
        ringV[k] = level.faceVertices[f][(j + 2) % 3];
        ringF[k] = kInvalidIndex;
        ringL[k] = 0;
        ++k;
        break;
      }
      if (next == start) break;
      f = next;
    }
    if (k != n) {
      return invalidMesh(vertexName(v) + " is non-manifold: its faces form more than one fan");
    }
  }
  return Status::ok();
}

}  // namespace

Expected<Level> buildBaseLevel(const BaseTopology& topology, const LoopOptions& options) {
  const int numVertices = topology.numVertices;
  if (numVertices <= 0 || topology.triangles.empty()) return invalidMesh("mesh is empty");

  Level level;
  level.numVertices = numVertices;
  level.faceVertices.resize(topology.triangles.size());

  // Vertex -> faces in face order (the ring of an interior vertex starts at
  // its first face, as in OpenSubdiv).
  std::vector<Index> facesAtCount(numVertices, 0);
  for (size_t f = 0; f < topology.triangles.size(); ++f) {
    const auto& t = topology.triangles[f];
    for (int j = 0; j < 3; ++j) {
      if (t[j] < 0 || t[j] >= numVertices) {
        return invalidMesh("face " + std::to_string(f) + " names vertex " + std::to_string(t[j]) + " of " +
                           std::to_string(numVertices));
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      return invalidMesh("face " + std::to_string(f) + " is degenerate: it repeats a vertex");
    }
    level.faceVertices[f] = {t[0], t[1], t[2]};
    for (int j = 0; j < 3; ++j) ++facesAtCount[t[j]];
  }
  std::vector<Index> facesAtOffset(numVertices + 1, 0);
  for (int v = 0; v < numVertices; ++v) {
    if (facesAtCount[v] == 0) return invalidMesh(vertexName(v) + " is not used by any face");
    facesAtOffset[v + 1] = facesAtOffset[v] + facesAtCount[v];
  }
  std::vector<Index> facesAt(facesAtOffset[numVertices]);
  {
    std::vector<Index> fill(facesAtOffset.begin(), facesAtOffset.end() - 1);
    for (Index f = 0; f < level.numFaces(); ++f) {
      for (Index v : level.faceVertices[f]) facesAt[fill[v]++] = f;
    }
  }

  TESSERA_RETURN_IF_ERROR(buildEdges(numVertices, level, facesAtCount));
  TESSERA_RETURN_IF_ERROR(orderRings(numVertices, level, facesAtOffset, facesAt));

  // Sharpness: tags first, then the boundary rules.
  level.edgeSharpness.assign(level.numEdges(), kSharpnessSmooth);
  level.vertexSharpness.assign(numVertices, kSharpnessSmooth);
  for (const auto& crease : topology.creases) {
    if (crease.v0 < 0 || crease.v0 >= numVertices || crease.v1 < 0 || crease.v1 >= numVertices) {
      return notFound("crease names vertex outside 0.." + std::to_string(numVertices - 1));
    }
    Index found = kInvalidIndex;
    for (Index e : level.ringEdgesOf(crease.v0)) {
      if (level.otherVertex(e, crease.v0) == crease.v1) found = e;
    }
    if (found == kInvalidIndex) {
      return notFound("crease " + std::to_string(crease.v0) + "-" + std::to_string(crease.v1) +
                      ": those vertices share no edge");
    }
    level.edgeSharpness[found] = canonicalSharpness(crease.sharpness);
  }
  if (!topology.vertexSharpness.empty()) {
    if (static_cast<int>(topology.vertexSharpness.size()) != numVertices) {
      return invalidArgument("vertex sharpness count differs from the vertex count");
    }
    for (int v = 0; v < numVertices; ++v)
      level.vertexSharpness[v] = canonicalSharpness(topology.vertexSharpness[v]);
  }
  for (Index e = 0; e < level.numEdges(); ++e) {
    if (level.isBoundaryEdge(e)) level.edgeSharpness[e] = kSharpnessInfinite;
  }
  level.maxValence = level.computeMaxValence();
  if (options.boundary == BoundaryInterpolation::kEdgeAndCorner) {
    for (Index v = 0; v < numVertices; ++v) {
      const bool topologicalCorner = level.isBoundaryVertex(v) && level.valence(v) == 2;
      if (topologicalCorner) level.vertexSharpness[v] = kSharpnessInfinite;
    }
  }
  level.recomputeVertexRules();
  return level;
}

}  // namespace tessera
