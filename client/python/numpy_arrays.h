// Core's arrays as NumPy arrays and back (docs/PYTHON.md "Arrays"): every
// array returned is a copy the caller owns, so it stays valid after the
// view or mesh it came from changes.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/polygon_soup.h"
#include "core/mesh/surface_mesh.h"
#include "core/util/vec3.h"

namespace tessera::python {

namespace py = pybind11;

py::array_t<double> pointsArray(const std::vector<Vec3>& points);                       // (N, 3) float64
py::array_t<int32_t> trianglesArray(const std::vector<std::array<int, 3>>& triangles);  // (M, 3) int32
py::array_t<uint64_t> idsArray(const std::vector<uint64_t>& ids);                       // (N,) uint64

// (N, 3) numbers as points; ValueError naming the shape otherwise.
std::vector<Vec3> pointsFrom(const py::handle& points);
// Faces as an (M, k) integer array (k >= 3: triangles, quads, ...) or a
// sequence of index sequences of any lengths, appended to `soup`.
void addFaces(const py::handle& faces, PolygonSoup& soup);

// A surface as Python sees it (tessera.Mesh): arrays, copied once.
struct MeshArrays {
  py::array_t<double> positions;   // (N, 3)
  py::object normals;              // (N, 3) float64, or None
  py::array_t<int32_t> triangles;  // (M, 3)
  // Polygon surfaces only (a Catmull-Clark level): face f's corners are
  // polygon_corners[polygon_offsets[f]:polygon_offsets[f + 1]]; else None.
  py::object polygonOffsets, polygonCorners;
};
MeshArrays meshArrays(const SurfaceMesh& surface);
void bindMesh(py::module_& m);

}  // namespace tessera::python
