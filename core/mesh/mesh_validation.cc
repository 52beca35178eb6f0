// Validation of untrusted polygon soups into a BaseMesh.
//
// The checks run in a fixed order (elements, then faces one by one, then the
// edge and vertex neighbourhoods) so that the first error reported is the most
// local one: a face with a repeated index is reported as degenerate rather than
// as the non-manifold edge it would also create. Every message has the form
// "<source>: <element>: <reason>" with 0-based indices.
#include "core/mesh/mesh_validation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <sstream>
#include <unordered_map>
#include <vector>

#include <OpenMesh/Core/System/omstream.hh>

#include "core/mesh/polygon_triangulation.h"

namespace tessera {
namespace {

// Faces whose doubled area |(b-a) x (c-a)| is at most this fraction of the
// squared bounding-box diagonal are zero-area. Relative, so that the unit of
// the file does not matter; small enough that only true slivers (collinear
// corners up to rounding) are rejected.
constexpr double kRelativeAreaEpsilon = 1e-12;

struct Triangle {
  std::array<int, 3> v;
  int sourceFace;    // index of the polygon in the soup
  bool fromPolygon;  // one of the triangles of a triangulated polygon
};

std::string joinIndices(const int* begin, const int* end) {
  std::string out;
  for (const int* it = begin; it != end; ++it) {
    if (it != begin) out += ", ";
    out += std::to_string(*it);
  }
  return out;
}

std::string faceName(const PolygonSoup& soup, int f) {
  const int* begin = soup.indices.data() + soup.faceOffsets[f];
  const int* end = soup.indices.data() + soup.faceOffsets[f + 1];
  return "face " + std::to_string(f) + " (vertices " + joinIndices(begin, end) + ")";
}

std::string triangleName(const PolygonSoup& soup, const Triangle& t) {
  if (!t.fromPolygon) return faceName(soup, t.sourceFace);
  return faceName(soup, t.sourceFace) + ", its triangle (" + joinIndices(t.v.data(), t.v.data() + 3) + ")";
}

uint64_t edgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

std::string formatPoint(const Vec3& p) {
  std::ostringstream out;
  out << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return out.str();
}

// Checks per face: arity, index range, repeated indices. Produces triangles.
Status collectTriangles(const PolygonSoup& soup, const BuildOptions& options, const std::string& src,
                        std::vector<Triangle>& triangles) {
  const int numPoints = static_cast<int>(soup.points.size());
  std::vector<std::array<int, 3>> pieces;
  for (int f = 0; f < soup.numFaces(); ++f) {
    const int begin = soup.faceOffsets[f];
    const int n = soup.faceOffsets[f + 1] - begin;
    const int* idx = soup.indices.data() + begin;
    if (n < 3) {
      return invalidMesh(src + ": " + faceName(soup, f) + ": has " + std::to_string(n) +
                         " vertices, a face needs at least 3");
    }
    for (int k = 0; k < n; ++k) {
      if (idx[k] < 0 || idx[k] >= numPoints) {
        return invalidMesh(src + ": " + faceName(soup, f) + ": vertex index " + std::to_string(idx[k]) +
                           " is out of range (the mesh has " + std::to_string(numPoints) + " vertices)");
      }
    }
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b) {
        if (idx[a] == idx[b]) {
          return invalidMesh(src + ": " + faceName(soup, f) + ": degenerate, repeats vertex " +
                             std::to_string(idx[a]));
        }
      }
    }
    if (n > 3 && !options.triangulate) {
      return unsupported(
          src + ": " + faceName(soup, f) + ": has " + std::to_string(n) +
          " vertices; only triangles are accepted (use --triangulate to triangulate polygons)");
    }
    pieces.clear();
    const Status split = triangulatePolygon(soup.points, std::span<const int>(idx, n), pieces);
    if (!split.isOk()) return Status(split.code(), src + ": " + faceName(soup, f) + ": " + split.message());
    for (const std::array<int, 3>& t : pieces) triangles.push_back({t, f, n > 3});
  }
  return Status::ok();
}

Status checkAreas(const PolygonSoup& soup, const std::vector<Triangle>& triangles, const std::string& src) {
  Vec3 lo = soup.points.front();
  Vec3 hi = lo;
  for (const Vec3& p : soup.points) {
    lo.minimize(p);
    hi.maximize(p);
  }
  const double diagonal = (hi - lo).norm();
  const double threshold = kRelativeAreaEpsilon * diagonal * diagonal;
  for (const Triangle& t : triangles) {
    const Vec3& a = soup.points[t.v[0]];
    const Vec3 cross = (soup.points[t.v[1]] - a) % (soup.points[t.v[2]] - a);
    if (!(cross.norm() > threshold)) {
      return invalidMesh(src + ": " + triangleName(soup, t) +
                         ": degenerate, zero area (|cross product| <= 1e-12 * bounding-box diagonal^2)");
    }
  }
  return Status::ok();
}

Status checkDuplicates(const PolygonSoup& soup, const std::vector<Triangle>& triangles,
                       const std::string& src) {
  // Sorted corner triple -> first triangle; catches any rotation and either
  // orientation.
  struct Hash {
    size_t operator()(const std::array<int, 3>& k) const {
      return std::hash<uint64_t>()(edgeKey(k[0], k[1]) * 1000003u ^ static_cast<uint32_t>(k[2]));
    }
  };
  std::unordered_map<std::array<int, 3>, int, Hash> seen;
  seen.reserve(triangles.size());
  for (int i = 0; i < static_cast<int>(triangles.size()); ++i) {
    std::array<int, 3> key = triangles[i].v;
    std::sort(key.begin(), key.end());
    auto [it, inserted] = seen.emplace(key, i);
    if (!inserted) {
      return invalidMesh(src + ": " + triangleName(soup, triangles[i]) + ": duplicates " +
                         triangleName(soup, triangles[it->second]));
    }
  }
  return Status::ok();
}

// An edge may be used by at most two faces, and then in opposite directions.
Status checkEdges(const PolygonSoup& soup, const std::vector<Triangle>& triangles, const std::string& src) {
  struct Use {
    int triangle;
    int from;
  };
  std::unordered_map<uint64_t, std::vector<Use>> uses;
  uses.reserve(triangles.size() * 2);
  for (int i = 0; i < static_cast<int>(triangles.size()); ++i) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[i].v[k];
      const int b = triangles[i].v[(k + 1) % 3];
      uses[edgeKey(a, b)].push_back({i, a});
    }
  }
  // Report in triangle order so the message is deterministic.
  for (int i = 0; i < static_cast<int>(triangles.size()); ++i) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[i].v[k];
      const int b = triangles[i].v[(k + 1) % 3];
      const std::vector<Use>& list = uses[edgeKey(a, b)];
      const std::string edge =
          "edge " + std::to_string(std::min(a, b)) + "-" + std::to_string(std::max(a, b));
      if (list.size() > 2) {
        std::string faces;
        for (const Use& u : list)
          faces += (faces.empty() ? "" : "; ") + triangleName(soup, triangles[u.triangle]);
        return invalidMesh(src + ": " + edge + ": non-manifold, used by " + std::to_string(list.size()) +
                           " faces: " + faces);
      }
      if (list.size() == 2 && list[0].from == list[1].from) {
        return invalidMesh(src + ": " + edge + ": inconsistent orientation, " +
                           triangleName(soup, triangles[list[0].triangle]) + " and " +
                           triangleName(soup, triangles[list[1].triangle]) + " both run from vertex " +
                           std::to_string(list[0].from) + " (flip one of them)");
      }
    }
  }
  return Status::ok();
}

int findRoot(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// Every vertex must be used, and its faces must form one fan: joining the
// faces around it across shared edges must give a single connected group.
Status checkVertices(const PolygonSoup& soup, const std::vector<Triangle>& triangles,
                     const std::string& src) {
  const int n = static_cast<int>(soup.points.size());
  std::vector<int> start(n + 1, 0);
  for (const Triangle& t : triangles) {
    for (int v : t.v) ++start[v + 1];
  }
  for (int v = 0; v < n; ++v) {
    if (start[v + 1] == 0) {
      return invalidMesh(
          src + ": vertex " + std::to_string(v) + " " + formatPoint(soup.points[v]) +
          ": not used by any face (isolated vertices are not accepted; --drop-unused drops them)");
    }
    start[v + 1] += start[v];
  }
  std::vector<int> incident(start[n]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int i = 0; i < static_cast<int>(triangles.size()); ++i) {
    for (int v : triangles[i].v) incident[fill[v]++] = i;
  }
  std::vector<int> parent;
  std::unordered_map<int, int> firstTriangleByNeighbour;
  for (int v = 0; v < n; ++v) {
    const int count = start[v + 1] - start[v];
    parent.resize(count);
    std::iota(parent.begin(), parent.end(), 0);
    firstTriangleByNeighbour.clear();
    // Two faces around v are joined when they share a neighbour of v (that
    // is, the edge v-neighbour); edges are already known to be manifold.
    for (int j = 0; j < count; ++j) {
      const Triangle& t = triangles[incident[start[v] + j]];
      for (int u : t.v) {
        if (u == v) continue;
        auto [it, inserted] = firstTriangleByNeighbour.emplace(u, j);
        if (!inserted) parent[findRoot(parent, j)] = findRoot(parent, it->second);
      }
    }
    for (int j = 1; j < count; ++j) {
      if (findRoot(parent, j) != findRoot(parent, 0)) {
        return invalidMesh(src + ": vertex " + std::to_string(v) +
                           ": non-manifold, its faces form more than one fan (e.g. " +
                           triangleName(soup, triangles[incident[start[v]]]) + " and " +
                           triangleName(soup, triangles[incident[start[v] + j]]) +
                           " touch only at this vertex)");
      }
    }
  }
  return Status::ok();
}

}  // namespace

Expected<BaseMesh> buildBaseMesh(const PolygonSoup& soup, const BuildOptions& options,
                                 const std::string& sourceName) {
  const std::string& src = sourceName;
  if (soup.points.empty()) return invalidMesh(src + ": mesh: empty, no vertices");
  if (soup.numFaces() <= 0) return invalidMesh(src + ": mesh: empty, no faces");
  if (soup.faceOffsets.empty() || soup.faceOffsets.back() != static_cast<int>(soup.indices.size())) {
    return internalError(src + ": polygon soup: face offsets do not match the index list");
  }
  for (size_t i = 0; i < soup.points.size(); ++i) {
    if (!isFinite(soup.points[i])) {
      const Vec3& p = soup.points[i];
      const bool nan = std::isnan(p[0]) || std::isnan(p[1]) || std::isnan(p[2]);
      return invalidMesh(src + ": vertex " + std::to_string(i) + " " + formatPoint(p) + ": coordinate is " +
                         (nan ? "NaN" : "infinite"));
    }
  }

  std::vector<Triangle> triangles;
  triangles.reserve(soup.indices.size());
  TESSERA_RETURN_IF_ERROR(collectTriangles(soup, options, src, triangles));
  TESSERA_RETURN_IF_ERROR(checkAreas(soup, triangles, src));
  TESSERA_RETURN_IF_ERROR(checkDuplicates(soup, triangles, src));
  TESSERA_RETURN_IF_ERROR(checkEdges(soup, triangles, src));
  TESSERA_RETURN_IF_ERROR(checkVertices(soup, triangles, src));

  BaseMesh base;
  TriMesh& mesh = base.mesh();
  mesh.reserve(soup.points.size(), triangles.size() * 3 / 2 + 3, triangles.size());
  for (const Vec3& p : soup.points) mesh.add_vertex(p);
  for (const Triangle& t : triangles) {
    const OpenMesh::VertexHandle v0(t.v[0]), v1(t.v[1]), v2(t.v[2]);
    // The checks above guarantee add_face succeeds; silence OpenMesh's own
    // complaint in case they ever disagree, and report it as our bug.
    ::omerr().disable();
    const OpenMesh::FaceHandle fh = mesh.add_face(v0, v1, v2);
    ::omerr().enable();
    if (!fh.is_valid()) {
      return internalError(src + ": " + triangleName(soup, t) +
                           ": OpenMesh rejected the face after validation");
    }
    // Face circulation starts at the to-vertex of the face's anchor halfedge;
    // anchor at the halfedge into v0 so that circulation yields v0, v1, v2,
    // keeping each face's corner order exactly as given.
    for (auto heh : mesh.fh_range(fh)) {
      if (mesh.to_vertex_handle(heh) == v0) {
        mesh.set_halfedge_handle(fh, heh);
        break;
      }
    }
  }
  return base;
}

}  // namespace tessera
