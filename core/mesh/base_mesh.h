// The base mesh of a document: an OpenMesh TriMesh with per-edge and
// per-vertex sharpness properties (Pulli & Lounsbery, "Hierarchical Editing
// and Rendering of Subdivision Surfaces" §2.4: creases, corners, darts,
// cusps are all expressed through these two properties).
//
// A BaseMesh is always valid: a closed or bordered 2-manifold of
// non-degenerate triangles with finite coordinates. Only buildBaseMesh()
// (mesh_validation.h) creates one from untrusted data.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "core/mesh/sharpness.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera {

struct TriMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<TriMeshTraits>;

struct BoundingBox {
  Vec3 min{0, 0, 0};
  Vec3 max{0, 0, 0};
  double diagonal() const { return (max - min).norm(); }
};

class BaseMesh {
 public:
  BaseMesh();
  BaseMesh(const BaseMesh& other);
  BaseMesh& operator=(const BaseMesh& other);
  BaseMesh(BaseMesh&&) = default;
  BaseMesh& operator=(BaseMesh&&) = default;

  TriMesh& mesh() { return mesh_; }
  const TriMesh& mesh() const { return mesh_; }

  int numVertices() const { return static_cast<int>(mesh_.n_vertices()); }
  int numFaces() const { return static_cast<int>(mesh_.n_faces()); }
  int numEdges() const { return static_cast<int>(mesh_.n_edges()); }

  // Sharpness accessors by OpenMesh handle.
  float edgeSharpness(OpenMesh::EdgeHandle e) const { return mesh_.property(edgeSharpness_, e); }
  float vertexSharpness(OpenMesh::VertexHandle v) const { return mesh_.property(vertexSharpness_, v); }
  void setEdgeSharpness(OpenMesh::EdgeHandle e, float s) {
    mesh_.property(edgeSharpness_, e) = canonicalSharpness(s);
  }
  void setVertexSharpness(OpenMesh::VertexHandle v, float s) {
    mesh_.property(vertexSharpness_, v) = canonicalSharpness(s);
  }

  // Tags by vertex indices, as tag files and glTF extras name them.
  // Errors name the missing edge or vertex.
  Status setCreaseByVertices(int v0, int v1, float sharpness);
  Status setCornerByVertex(int v, float sharpness);

  // Triangles as vertex-index triples in face order, counter-clockwise.
  std::vector<std::array<int, 3>> faceVertexIndices() const;
  std::vector<Vec3> positions() const;

  BoundingBox boundingBox() const;

  struct TagCounts {
    int infiniteCreases = 0;
    int semiSharpCreases = 0;
    int sharpVertices = 0;
  };
  TagCounts tagCounts() const;

 private:
  void addProperties();

  TriMesh mesh_;
  OpenMesh::EPropHandleT<float> edgeSharpness_;
  OpenMesh::VPropHandleT<float> vertexSharpness_;
};

}  // namespace tessera
