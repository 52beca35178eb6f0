#include "client/python/numpy_arrays.h"

#include <algorithm>
#include <string>

namespace tessera::python {

namespace {

std::string shapeText(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) text += (d ? ", " : "") + std::to_string(a.shape(d));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace

py::array_t<double> pointsArray(const std::vector<Vec3>& points) {
  py::array_t<double> a({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  auto out = a.mutable_unchecked<2>();
  for (size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k) out(static_cast<py::ssize_t>(i), k) = points[i][k];
  return a;
}

py::array_t<int32_t> trianglesArray(const std::vector<std::array<int, 3>>& triangles) {
  py::array_t<int32_t> a({static_cast<py::ssize_t>(triangles.size()), py::ssize_t{3}});
  auto out = a.mutable_unchecked<2>();
  for (size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) out(static_cast<py::ssize_t>(i), k) = triangles[i][k];
  return a;
}

py::array_t<uint64_t> idsArray(const std::vector<uint64_t>& ids) {
  py::array_t<uint64_t> a(static_cast<py::ssize_t>(ids.size()));
  std::copy(ids.begin(), ids.end(), a.mutable_data());
  return a;
}

std::vector<Vec3> pointsFrom(const py::handle& points) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if (!a || a.ndim() != 2 || a.shape(1) != 3) {
    throw py::value_error("points must be an (N, 3) array of numbers, got shape " +
                          (a ? shapeText(a) : std::string("none (not numbers)")));
  }
  std::vector<Vec3> out(static_cast<size_t>(a.shape(0)));
  auto in = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) out[static_cast<size_t>(i)] = {in(i, 0), in(i, 1), in(i, 2)};
  return out;
}

void addFaces(const py::handle& faces, PolygonSoup& soup) {
  if (py::isinstance<py::array>(faces)) {
    auto a = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(faces);
    if (!a || a.ndim() != 2 || a.shape(1) < 3) {
      throw py::value_error("faces must be an (M, k) integer array with k >= 3, got shape " +
                            (a ? shapeText(a) : std::string("none (not integers)")));
    }
    auto in = a.unchecked<2>();
    std::vector<int> face(static_cast<size_t>(a.shape(1)));
    for (py::ssize_t f = 0; f < a.shape(0); ++f) {
      for (py::ssize_t k = 0; k < a.shape(1); ++k) face[static_cast<size_t>(k)] = static_cast<int>(in(f, k));
      soup.addFace(face);
    }
    return;
  }
  // Element by element: this file does without pybind11/stl.h's casters,
  // whose absence made a list of lists fail to cast at all.
  for (const py::handle& polygon : py::iter(faces)) {
    std::vector<int> face;
    for (const py::handle& corner : py::iter(polygon)) face.push_back(corner.cast<int>());
    soup.addFace(face);
  }
}

static py::array_t<int32_t> intArray(const std::vector<int>& values) {
  py::array_t<int32_t> a(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

MeshArrays meshArrays(const SurfaceMesh& surface) {
  MeshArrays mesh;
  mesh.positions = pointsArray(surface.positions);
  mesh.normals = surface.normals.empty() ? py::object(py::none()) : py::object(pointsArray(surface.normals));
  mesh.triangles = trianglesArray(surface.triangles);
  mesh.polygonOffsets = py::none();
  mesh.polygonCorners = py::none();
  if (surface.numPolygons() > 0) {
    mesh.polygonOffsets = intArray(surface.polygonOffsets);
    mesh.polygonCorners = intArray(surface.polygonCorners);
  }
  return mesh;
}

void bindMesh(py::module_& m) {
  py::class_<MeshArrays>(m, "Mesh",
                         "A surface as NumPy arrays: a refined or limit surface computed offline,\n"
                         "or the surface a DocumentView holds. Every array is a copy.")
      .def_readonly("positions", &MeshArrays::positions, "(N, 3) float64 vertex positions.")
      .def_readonly("normals", &MeshArrays::normals, "(N, 3) float64 unit normals, or None (control points).")
      .def_readonly("triangles", &MeshArrays::triangles,
                    "(M, 3) int32 vertex indices per triangle, counter-clockwise.")
      .def_readonly("polygon_offsets", &MeshArrays::polygonOffsets,
                    "For a polygon surface, (F + 1,) int32: face f's corners are\n"
                    "polygon_corners[polygon_offsets[f]:polygon_offsets[f + 1]]. None otherwise.")
      .def_readonly("polygon_corners", &MeshArrays::polygonCorners,
                    "For a polygon surface, the corners of every face, int32. None otherwise.")
      .def("__repr__", [](const MeshArrays& mesh) {
        return "<tessera.Mesh " + std::to_string(mesh.positions.shape(0)) + " vertices, " +
               std::to_string(mesh.triangles.shape(0)) + " triangles>";
      });
}

}  // namespace tessera::python
