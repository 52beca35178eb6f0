#include "core/schemes/doo_sabin.h"

#include <string>

#include "core/schemes/doo_sabin_masks.h"

namespace tessera::schemes {

PolygonRefinement dooSabinStep(const Level& parent, std::span<const Vec3> p) {
  PolygonRefinement out;
  const Index corners = static_cast<Index>(parent.faceVertices.size());
  out.points.resize(corners);
  std::vector<double> w(parent.maxFaceSize);
  for (Index f = 0; f < parent.numFaces(); ++f) {
    auto fv = parent.faceVerticesOf(f);
    const int n = static_cast<int>(fv.size());
    for (int d = 0; d < n; ++d) w[d] = doosabin::cornerWeight(n, d);
    for (int i = 0; i < n; ++i) {
      Vec3 sum(0, 0, 0);
      for (int j = 0; j < n; ++j) sum += w[(i - j + n) % n] * p[fv[j]];
      out.points[parent.faceBegin(f) + i] = sum;
    }
  }
  PolyTopology& t = out.topology;
  t.numVertices = corners;
  std::vector<int> face;
  // F-faces: the face's own corner points.
  for (Index f = 0; f < parent.numFaces(); ++f) {
    face.clear();
    for (Index k = parent.faceBegin(f), end = k + parent.faceSize(f); k < end; ++k) face.push_back(k);
    t.addFace(face);
  }
  // E-faces: the two faces' points at each end of an interior edge. Face 0
  // runs the edge from a to b (corner j to j+1), face 1 from b to a.
  for (Index e = 0; e < parent.numEdges(); ++e) {
    const auto& ef = parent.edgeFaces[e];
    if (ef[1] == kNoIndex) continue;
    const auto& el = parent.edgeFaceLocal[e];
    const Index o0 = parent.faceBegin(ef[0]), n0 = parent.faceSize(ef[0]);
    const Index o1 = parent.faceBegin(ef[1]), n1 = parent.faceSize(ef[1]);
    const Index a0 = o0 + el[0], b0 = o0 + (el[0] + 1) % n0;  // face 0's points at a and b
    const Index b1 = o1 + el[1], a1 = o1 + (el[1] + 1) % n1;  // face 1's points at b and a
    face.assign({a0, a1, b1, b0});
    t.addFace(face);
  }
  // V-faces: around each interior vertex, its faces' points in ring order
  // (counter-clockwise seen from outside, as the ring is).
  for (Index v = 0; v < parent.numVertices; ++v) {
    if (parent.isBoundaryVertex(v)) continue;
    face.clear();
    const Index o = parent.ringOffsets[v];
    for (int k = 0; k < parent.valence(v); ++k)
      face.push_back(parent.faceBegin(parent.ringFaces[o + k]) + parent.ringFaceLocal[o + k]);
    t.addFace(face);
  }
  return out;
}

Expected<PolygonRefinement> refineDooSabin(const PolyTopology& topology, std::span<const Vec3> points,
                                           int levels, long long maxFaces) {
  if (levels < 0) return invalidArgument("level must be 0 or more, got " + std::to_string(levels));
  PolygonRefinement current{topology, std::vector<Vec3>(points.begin(), points.end())};
  current.topology.creases.clear();
  current.topology.vertexSharpness.clear();
  TESSERA_ASSIGN_OR_RETURN(Level level, buildPolyLevel(current.topology, CreaseOptions{}));
  for (int l = 0; l < levels; ++l) {
    // Faces of the child: one per face, edge and vertex of the parent.
    const long long faces = static_cast<long long>(level.numFaces()) + level.numEdges() + level.numVertices;
    if (faces > maxFaces) {
      return invalidArgument("level " + std::to_string(levels) + " would make more than " +
                             std::to_string(maxFaces) + " faces; choose a lower level");
    }
    current = dooSabinStep(level, current.points);
    if (l + 1 < levels) {
      TESSERA_ASSIGN_OR_RETURN(Level next, buildPolyLevel(current.topology, CreaseOptions{}));
      level = std::move(next);
    }
  }
  return current;
}

void dooSabinFaceLimits(const PolyTopology& topology, std::span<const Vec3> points,
                        std::vector<Vec3>& positions, std::vector<Vec3>& normals) {
  positions.assign(topology.numFaces(), Vec3(0, 0, 0));
  normals.assign(topology.numFaces(), Vec3(0, 0, 0));
  for (int f = 0; f < topology.numFaces(); ++f) {
    const int from = topology.faceOffsets[f], n = topology.faceOffsets[f + 1] - from;
    Vec3 centroid(0, 0, 0), tc(0, 0, 0), ts(0, 0, 0);
    for (int k = 0; k < n; ++k) {
      const Vec3& q = points[topology.indices[from + k]];
      centroid += q;
      tc += doosabin::tangentCosWeight(n, k) * q;
      ts += doosabin::tangentSinWeight(n, k) * q;
    }
    positions[f] = (1.0 / n) * centroid;
    const Vec3 normal = tc % ts;
    const double len = normal.norm();
    normals[f] = len > 0.0 ? (1.0 / len) * normal : Vec3(0, 0, 0);
  }
}

}  // namespace tessera::schemes
