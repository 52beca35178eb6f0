#include "core/topology/level_builder.h"

#include <algorithm>
#include <string>
#include <vector>

namespace tessera::topology {

namespace {

std::string faceName(Index f) {
  return "face " + std::to_string(f);
}
std::string vertexName(Index v) {
  return "vertex " + std::to_string(v);
}
std::string edgeName(Index a, Index b) {
  return "edge " + std::to_string(a) + "-" + std::to_string(b);
}

// Whether a face's corners are in range and all different.
[[gnu::always_inline]] inline bool validCorners(const Index* corners, int n, int numVertices) {
  for (int k = 0; k < n; ++k) {
    if (static_cast<uint32_t>(corners[k]) >= static_cast<uint32_t>(numVertices)) return false;
    for (int j = 0; j < k; ++j) {
      if (corners[j] == corners[k]) return false;
    }
  }
  return true;
}

// What is wrong with face f, whose corners validCorners refused.
Status invalidFace(Index f, const Index* corners, int n, int numVertices) {
  for (int k = 0; k < n; ++k) {
    const Index v = corners[k];
    if (v < 0 || v >= numVertices) {
      return invalidMesh(faceName(f) + " names vertex " + std::to_string(v) + ", out of range 0.." +
                         std::to_string(numVertices - 1));
    }
    for (int j = 0; j < k; ++j) {
      if (corners[j] == v) {
        return invalidMesh(faceName(f) + " uses vertex " + std::to_string(v) + " twice (degenerate)");
      }
    }
  }
  return Status::ok();
}

// Sizes, ranges and repeated corners of every face; moves the rows into the
// level, keeping offsets only when the face sizes differ.
Status takeFaces(FaceRows& faces, Level& level) {
  const int nV = faces.numVertices;
  const int nF = faces.numFaces();
  if (nF <= 0) return invalidMesh("mesh is empty: no faces");
  if (nV <= 0) return invalidMesh("mesh is empty: no vertices");
  const Index* corners = faces.corners.data();
  int smallest = kMaxFaceSize + 1, largest = 0;
  if (faces.regularSize == 3) {
    // Triangles (every Loop base level): the same checks, unrolled.
    for (Index f = 0; f < nF; ++f) {
      if (!validCorners(corners + 3 * f, 3, nV)) return invalidFace(f, corners + 3 * f, 3, nV);
    }
    smallest = largest = 3;
  } else {
    for (Index f = 0; f < nF; ++f) {
      const Index from = faces.regularSize ? faces.regularSize * f : faces.offsets[f];
      const int n = faces.regularSize ? faces.regularSize : faces.offsets[f + 1] - from;
      if (n < 3)
        return invalidMesh(faceName(f) + " has " + std::to_string(n) + " corners (3 or more needed)");
      if (n > kMaxFaceSize) return invalidMesh(faceName(f) + " has more than 65535 corners");
      if (!validCorners(corners + from, n, nV)) return invalidFace(f, corners + from, n, nV);
      smallest = std::min(smallest, n);
      largest = std::max(largest, n);
    }
  }
  level.numVertices = nV;
  level.maxFaceSize = largest;
  level.regularFaceSize = smallest == largest ? largest : 0;
  if (level.regularFaceSize == 0) level.faceOffsets = std::move(faces.offsets);
  level.faceVertices = std::move(faces.corners);
  return Status::ok();
}

// Faces at each vertex in face order; an unused vertex is an error
// (OpenSubdiv would leave it without a ring).
struct VertexFaces {
  std::vector<Index> offsets;  // numVertices + 1
  std::vector<Index> faces;
};

template <int kSize>
Expected<VertexFaces> facesAtVertices(const Level& level) {
  const int nV = level.numVertices;
  VertexFaces at;
  at.offsets.assign(nV + 1, 0);
  for (Index v : level.faceVertices) ++at.offsets[v + 1];
  for (Index v = 0; v < nV; ++v) {
    if (at.offsets[v + 1] == 0) {
      // The Loop and the polygon builders this one replaced each had a
      // wording; the message keeps both, which users and tests know.
      return invalidMesh(vertexName(v) + " is not used: " + vertexName(v) + " is used by no face");
    }
    at.offsets[v + 1] += at.offsets[v];
  }
  at.faces.resize(at.offsets[nV]);
  std::vector<Index> fill(at.offsets.begin(), at.offsets.end() - 1);
  const Index* corners = level.faceVertices.data();
  for (Index f = 0, nF = level.numFaces(); f < nF; ++f) {
    if constexpr (kSize > 0) {
      for (int j = 0; j < kSize; ++j) at.faces[fill[corners[kSize * f + j]]++] = f;
    } else {
      for (Index v : level.faceVerticesOf(f)) at.faces[fill[v]++] = f;
    }
  }
  return at;
}

// Edges in order of first use, edge faces in face order (as Vtr builds them).
// A consistently oriented neighbour runs a shared edge the other way.
// kSize is the size of every face (3: a level of triangles, whose loop over
// corners the compiler unrolls) or 0 (read per face).
template <int kSize>
Status buildEdges(const VertexFaces& at, Level& level) {
  const int nV = level.numVertices;
  const int nF = level.numFaces();
  // Two edges per face corner at most: no hash table needed.
  std::vector<Index> edgesAtOffset(nV + 1, 0);
  for (Index v = 0; v < nV; ++v)
    edgesAtOffset[v + 1] = edgesAtOffset[v] + 2 * (at.offsets[v + 1] - at.offsets[v]);
  std::vector<Index> edgesAt(edgesAtOffset[nV]);
  std::vector<Index> edgesAtCount(nV, 0);

  level.faceEdges.resize(level.faceVertices.size());
  if (kSize == 3) level.faceEdgeSides.assign(nF, 0);
  // A closed mesh has corners / 2 edges; an open one grows the arrays. They
  // are sized, written by index and cut to the count at the end: a
  // push_back per edge was not inlined here and cost a call per edge (perf:
  // 13 % of refining fandisk to level 1).
  Index numEdges = 0;
  auto sizeEdges = [&level](size_t n) {
    level.edgeVertices.resize(n);
    level.edgeFaces.resize(n);
    level.edgeFaceLocal.resize(n);
  };
  sizeEdges(level.faceVertices.size() / 2 + 3);
  for (Index f = 0; f < nF; ++f) {
    const Index o = kSize ? kSize * f : level.faceBegin(f);
    const int n = kSize ? kSize : level.faceSize(f);
    for (int j = 0; j < n; ++j) {
      const Index a = level.faceVertices[o + j], b = level.faceVertices[o + (j + 1 < n ? j + 1 : 0)];
      Index e = kNoIndex;
      for (Index k = edgesAtOffset[a], end = k + edgesAtCount[a]; k < end; ++k) {
        if (level.otherVertex(edgesAt[k], a) == b) {
          e = edgesAt[k];
          break;
        }
      }
      if (e == kNoIndex) {
        e = numEdges++;
        if (static_cast<size_t>(e) == level.edgeVertices.size()) sizeEdges(2 * level.edgeVertices.size());
        level.edgeVertices[e] = {a, b};
        level.edgeFaces[e] = {f, kNoIndex};
        level.edgeFaceLocal[e] = {static_cast<LocalIndex>(j), 0};
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
        if (kSize == 3) level.faceEdgeSides[f] |= static_cast<uint8_t>(1u << j);
      }
      level.faceEdges[o + j] = e;
    }
  }
  sizeEdges(numEdges);
  return Status::ok();
}

// v's corner in the face whose corners start at fv (v is one of them). A
// triangle's corner is picked without a loop, whose branch would mispredict
// about every other time.
template <int kSize>
[[gnu::always_inline]] inline int cornerOf(const Index* fv, Index v) {
  if (kSize == 3) return fv[0] == v ? 0 : (fv[1] == v ? 1 : 2);
  int c = 0;
  while (fv[c] != v) ++c;
  return c;
}

// Orders each vertex's faces and edges counter-clockwise (Vtr's
// orderVertexFacesAndEdges; conventions in level.h). A manifold vertex has
// as many edges as faces (interior) or one more (boundary), all in one fan.
// kSize as for buildEdges.
template <int kSize>
Status orderRings(const VertexFaces& at, Level& level) {
  const int nV = level.numVertices;
  std::vector<Index> edgeCount(nV, 0);
  for (const auto& ev : level.edgeVertices) {
    ++edgeCount[ev[0]];
    ++edgeCount[ev[1]];
  }
  level.ringOffsets.resize(nV + 1);
  level.ringOffsets[0] = 0;
  for (Index v = 0; v < nV; ++v) level.ringOffsets[v + 1] = level.ringOffsets[v] + edgeCount[v];
  const Index total = level.ringOffsets[nV];
  level.ringEdges.resize(total);
  level.ringVertices.resize(total);
  level.ringFaces.resize(total);
  level.ringFaceLocal.resize(total);
  level.maxValence = 0;
  auto nonManifold = [](Index v) {
    return invalidMesh(vertexName(v) + " is non-manifold: its faces do not form one fan");
  };
  // Face rows read through locals: the ring arrays written below are Index
  // arrays too, which the compiler would otherwise assume may change the
  // level's fields.
  const int regular = kSize ? kSize : level.regularFaceSize;
  const Index* offsets = level.faceOffsets.data();
  const Index* faceVertices = level.faceVertices.data();
  const Index* faceEdges = level.faceEdges.data();
  auto faceBegin = [&](Index f) { return regular ? regular * f : offsets[f]; };
  auto faceSize = [&](Index f) { return regular ? regular : offsets[f + 1] - offsets[f]; };
  for (Index v = 0; v < nV; ++v) {
    const int n = edgeCount[v];
    const int faces = at.offsets[v + 1] - at.offsets[v];
    const bool boundary = n != faces;
    if (boundary && n != faces + 1) return nonManifold(v);
    level.maxValence = std::max(level.maxValence, n);
    // Interior: the lowest-numbered face (OpenSubdiv's choice). Boundary:
    // the face whose edge leaving v is a boundary edge.
    Index f = at.faces[at.offsets[v]];
    if (boundary) {
      f = kNoIndex;
      for (Index k = at.offsets[v]; k < at.offsets[v + 1] && f == kNoIndex; ++k) {
        const Index g = at.faces[k];
        const Index begin = faceBegin(g);
        if (level.isBoundaryEdge(faceEdges[begin + cornerOf<kSize>(faceVertices + begin, v)])) f = g;
      }
      if (f == kNoIndex) return nonManifold(v);
    }
    const Index o = level.ringOffsets[v];
    Index* ringE = level.ringEdges.data() + o;
    Index* ringV = level.ringVertices.data() + o;
    Index* ringF = level.ringFaces.data() + o;
    LocalIndex* ringL = level.ringFaceLocal.data() + o;
    Index begin = faceBegin(f);
    int c = cornerOf<kSize>(faceVertices + begin, v);
    Index e = faceEdges[begin + c];
    const Index first = e;
    // The far end of the edge last entered, read from the face rows (which
    // the walk reads anyway) rather than from the edge's vertices.
    Index previousCorner = kNoIndex;
    for (int k = 0; k < n; ++k) {
      ringE[k] = e;
      if (f == kNoIndex) {
        if (k != n - 1) return nonManifold(v);
        ringV[k] = previousCorner;
        ringF[k] = kNoIndex;
        ringL[k] = 0;
        break;
      }
      const int size = faceSize(f);
      ringV[k] = faceVertices[begin + (c + 1 < size ? c + 1 : 0)];
      ringF[k] = f;
      ringL[k] = static_cast<LocalIndex>(c);
      const int before = c ? c - 1 : size - 1;
      previousCorner = faceVertices[begin + before];
      const Index incoming = faceEdges[begin + before];
      if (k + 1 < n && incoming == first) return nonManifold(v);
      e = incoming;
      const auto& ef = level.edgeFaces[e];
      f = ef[0] == f ? ef[1] : ef[0];
      if (f != kNoIndex) {
        // v is a corner of the face across its incoming edge.
        begin = faceBegin(f);
        c = cornerOf<kSize>(faceVertices + begin, v);
      }
    }
    if (!boundary && e != first) return nonManifold(v);
  }
  return Status::ok();
}

// The level's faces all have kSize corners (3) or any number (0).
template <int kSize>
Status completeTopology(Level& level) {
  TESSERA_ASSIGN_OR_RETURN(VertexFaces at, facesAtVertices<kSize>(level));
  TESSERA_RETURN_IF_ERROR(buildEdges<kSize>(at, level));
  return orderRings<kSize>(at, level);
}

}  // namespace

Expected<Level> buildLevel(FaceRows faces) {
  Level level;
  TESSERA_RETURN_IF_ERROR(takeFaces(faces, level));
  // Triangles (every Loop base level) take the unrolled path; quads and
  // mixed faces the general one.
  TESSERA_RETURN_IF_ERROR(level.allTriangles() ? completeTopology<3>(level) : completeTopology<0>(level));
  return level;
}

}  // namespace tessera::topology
