// SoupImporter: an OpenMesh::IO::BaseImporter that records what a reader
// produces -- points and faces as raw indices, in file order -- into a
// PolygonSoup, instead of letting OpenMesh build a TriMesh (whose builder
// silently duplicates vertices of non-manifold faces and drops faces it cannot
// add). Attributes (normals, colours, texture coordinates) are ignored.
// Internal to core/io; used by mesh_import.cc.
#pragma once

#include <string>
#include <vector>

#include <OpenMesh/Core/IO/importer/BaseImporter.hh>

#include "core/mesh/polygon_soup.h"

namespace tessera {

class SoupImporter : public OpenMesh::IO::BaseImporter {
 public:
  using VertexHandle = OpenMesh::VertexHandle;
  using HalfedgeHandle = OpenMesh::HalfedgeHandle;
  using FaceHandle = OpenMesh::FaceHandle;
  using EdgeHandle = OpenMesh::EdgeHandle;
  using StatusInfo = OpenMesh::Attributes::StatusInfo;
  using Vec2f = OpenMesh::Vec2f;
  using Vec3f = OpenMesh::Vec3f;
  using Vec3d = OpenMesh::Vec3d;
  using Vec4f = OpenMesh::Vec4f;
  using Vec3uc = OpenMesh::Vec3uc;
  using Vec4uc = OpenMesh::Vec4uc;

  explicit SoupImporter(PolygonSoup& soup) : soup_(soup) {}

  VertexHandle add_vertex(const Vec3f& p) override { return addPoint(Vec3(p[0], p[1], p[2])); }
  VertexHandle add_vertex(const Vec3d& p) override { return addPoint(p); }
  VertexHandle add_vertex() override { return addPoint(Vec3(0, 0, 0)); }
  void set_point(VertexHandle v, const Vec3f& p) override {
    if (v.idx() >= 0 && v.idx() < static_cast<int>(soup_.points.size())) soup_.points[v.idx()] = Vec3(p[0], p[1], p[2]);
  }

  // Indices are recorded exactly, even out of range: validation reports them.
  FaceHandle add_face(const VHandles& corners) override {
    std::vector<int> face;
    face.reserve(corners.size());
    for (VertexHandle v : corners) face.push_back(v.idx());
    soup_.addFace(face);
    return FaceHandle(soup_.numFaces() - 1);
  }

  size_t n_vertices() const override { return soup_.points.size(); }
  size_t n_faces() const override { return static_cast<size_t>(soup_.numFaces()); }
  size_t n_edges() const override { return 0; }

  // Connectivity-level construction (used only by the OM format) is not supported.
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }

  // Attributes Tessera does not import.
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_normal(VertexHandle, const Vec3f&) override {}
  void set_normal(VertexHandle, const Vec3d&) override {}
  void set_color(VertexHandle, const Vec3uc&) override {}
  void set_color(VertexHandle, const Vec4uc&) override {}
  void set_color(VertexHandle, const Vec3f&) override {}
  void set_color(VertexHandle, const Vec4f&) override {}
  void set_texcoord(VertexHandle, const Vec2f&) override {}
  void set_status(VertexHandle, const StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const Vec2f&) override {}
  void set_texcoord(VertexHandle, const Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const Vec3f&) override {}
  void set_status(HalfedgeHandle, const StatusInfo&) override {}
  void set_color(EdgeHandle, const Vec3uc&) override {}
  void set_color(EdgeHandle, const Vec4uc&) override {}
  void set_color(EdgeHandle, const Vec3f&) override {}
  void set_color(EdgeHandle, const Vec4f&) override {}
  void set_status(EdgeHandle, const StatusInfo&) override {}
  void set_normal(FaceHandle, const Vec3f&) override {}
  void set_normal(FaceHandle, const Vec3d&) override {}
  void set_color(FaceHandle, const Vec3uc&) override {}
  void set_color(FaceHandle, const Vec4uc&) override {}
  void set_color(FaceHandle, const Vec3f&) override {}
  void set_color(FaceHandle, const Vec4f&) override {}
  void set_status(FaceHandle, const StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  VertexHandle addPoint(const Vec3& p) {
    soup_.points.push_back(p);
    return VertexHandle(static_cast<int>(soup_.points.size()) - 1);
  }

  PolygonSoup& soup_;
};

}  // namespace tessera
