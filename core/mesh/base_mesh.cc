#include "core/mesh/base_mesh.h"

#include <algorithm>
#include <limits>

namespace tessera {

BaseMesh::BaseMesh() {
  addProperties();
}

BaseMesh::BaseMesh(const BaseMesh& other) : mesh_(other.mesh_) {
  // OpenMesh copies properties with the mesh; re-find the handles by name.
  mesh_.get_property_handle(edgeSharpness_, "tessera:edge_sharpness");
  mesh_.get_property_handle(vertexSharpness_, "tessera:vertex_sharpness");
}

BaseMesh& BaseMesh::operator=(const BaseMesh& other) {
  if (this != &other) {
    mesh_ = other.mesh_;
    mesh_.get_property_handle(edgeSharpness_, "tessera:edge_sharpness");
    mesh_.get_property_handle(vertexSharpness_, "tessera:vertex_sharpness");
  }
  return *this;
}

void BaseMesh::addProperties() {
  mesh_.add_property(edgeSharpness_, "tessera:edge_sharpness");
  mesh_.add_property(vertexSharpness_, "tessera:vertex_sharpness");
}

Status BaseMesh::setCreaseByVertices(int v0, int v1, float sharpness) {
  const int n = numVertices();
  if (v0 < 0 || v0 >= n || v1 < 0 || v1 >= n) {
    return notFound("crease names vertex " + std::to_string(v0 < 0 || v0 >= n ? v0 : v1) +
                    " but the mesh has " + std::to_string(n) + " vertices");
  }
  if (!(sharpness >= 0.0f)) {  // also rejects NaN
    return invalidArgument("crease " + std::to_string(v0) + " " + std::to_string(v1) +
                           ": sharpness must be >= 0");
  }
  auto heh = mesh_.find_halfedge(mesh_.vertex_handle(v0), mesh_.vertex_handle(v1));
  if (!heh.is_valid()) {
    return notFound("crease names edge " + std::to_string(v0) + "-" + std::to_string(v1) +
                    " but those vertices share no edge");
  }
  setEdgeSharpness(mesh_.edge_handle(heh), sharpness);
  return Status::ok();
}

Status BaseMesh::setCornerByVertex(int v, float sharpness) {
  if (v < 0 || v >= numVertices()) {
    return notFound("corner names vertex " + std::to_string(v) + " but the mesh has " +
                    std::to_string(numVertices()) + " vertices");
  }
  if (!(sharpness >= 0.0f)) {
    return invalidArgument("corner " + std::to_string(v) + ": sharpness must be >= 0");
  }
  setVertexSharpness(mesh_.vertex_handle(v), sharpness);
  return Status::ok();
}

std::vector<std::array<int, 3>> BaseMesh::faceVertexIndices() const {
  std::vector<std::array<int, 3>> faces;
  faces.reserve(mesh_.n_faces());
  for (auto fh : mesh_.faces()) {
    std::array<int, 3> tri{};
    int k = 0;
    for (auto vh : mesh_.fv_ccw_range(fh)) {
      if (k < 3) tri[k] = vh.idx();
      ++k;
    }
    faces.push_back(tri);
  }
  return faces;
}

std::vector<Vec3> BaseMesh::positions() const {
  std::vector<Vec3> points;
  points.reserve(mesh_.n_vertices());
  for (auto vh : mesh_.vertices()) points.push_back(mesh_.point(vh));
  return points;
}

BoundingBox BaseMesh::boundingBox() const {
  BoundingBox box;
  if (mesh_.n_vertices() == 0) return box;
  const double inf = std::numeric_limits<double>::infinity();
  box.min = Vec3(inf, inf, inf);
  box.max = Vec3(-inf, -inf, -inf);
  for (auto vh : mesh_.vertices()) {
    box.min.minimize(mesh_.point(vh));
    box.max.maximize(mesh_.point(vh));
  }
  return box;
}

BaseMesh::TagCounts BaseMesh::tagCounts() const {
  TagCounts counts;
  for (auto eh : mesh_.edges()) {
    float s = edgeSharpness(eh);
    if (isInfinite(s))
      ++counts.infiniteCreases;
    else if (isSharp(s))
      ++counts.semiSharpCreases;
  }
  for (auto vh : mesh_.vertices()) {
    if (isSharp(vertexSharpness(vh))) ++counts.sharpVertices;
  }
  return counts;
}

}  // namespace tessera
