// Work without a server, straight on core (docs/PYTHON.md "Offline"): read
// a mesh as core imports it, refine it uniformly to control points or the
// limit surface as `tessera refine` does, write a surface as core's exporter
// writes it (core/io/mesh_export.h), and read and write tag files
// (docs/FORMATS.md "Tag sidecar files").
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>

#include "client/python/bindings.h"
#include "client/python/errors.h"
#include "client/python/numpy_arrays.h"
#include "client/python/offline_work.h"

namespace tessera::python {

namespace {

// What `source` (and `faces`) name: a file, or (points, faces) arrays.
SchemeSource sourceOf(const py::object& source, const py::object& faces) {
  SchemeSource from;
  if (py::isinstance<py::str>(source) || py::hasattr(source, "__fspath__")) {
    if (!faces.is_none()) throw py::value_error("faces are given with points, not with a file");
    from.path = py::str(py::module_::import("os").attr("fspath")(source)).cast<std::string>();
  } else {
    if (faces.is_none()) throw py::value_error("points need faces: refine(points, faces, level)");
    from.soup.points = pointsFrom(source);
    addFaces(faces, from.soup);
  }
  return from;
}

// A bad choice of rule is the caller's argument: ValueError.
LoopOptions loopOptions(const std::string& creaseMethod, const std::string& boundary) {
  auto options = loopOptionsNamed(creaseMethod, boundary);
  if (!options.isOk()) throw py::value_error(options.status().message());
  return *options;
}

std::string pathOf(const py::object& path) {
  return py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>();
}

// A tag file's tags as arrays (tessera.Tags): creases and corners apart,
// each in the file's order.
struct TagArrays {
  py::array_t<int32_t> creases;         // (K, 2)
  py::array_t<double> creaseSharpness;  // (K,)
  py::array_t<int32_t> corners;         // (C,)
  py::array_t<double> cornerSharpness;  // (C,)
};

TagArrays tagArrays(const std::vector<FeatureTag>& tags) {
  std::vector<const FeatureTag*> creases, corners;
  for (const FeatureTag& t : tags) (t.kind == FeatureTag::Kind::kCrease ? creases : corners).push_back(&t);
  TagArrays a{py::array_t<int32_t>({static_cast<py::ssize_t>(creases.size()), py::ssize_t{2}}),
              py::array_t<double>(static_cast<py::ssize_t>(creases.size())),
              py::array_t<int32_t>(static_cast<py::ssize_t>(corners.size())),
              py::array_t<double>(static_cast<py::ssize_t>(corners.size()))};
  auto ends = a.creases.mutable_unchecked<2>();
  for (size_t i = 0; i < creases.size(); ++i) {
    ends(static_cast<py::ssize_t>(i), 0) = creases[i]->v0;
    ends(static_cast<py::ssize_t>(i), 1) = creases[i]->v1;
    a.creaseSharpness.mutable_data()[i] = creases[i]->sharpness;
  }
  for (size_t i = 0; i < corners.size(); ++i) {
    a.corners.mutable_data()[i] = corners[i]->v0;
    a.cornerSharpness.mutable_data()[i] = corners[i]->sharpness;
  }
  return a;
}

template <typename T>
py::array_t<T> arrayOf(const py::object& values, const char* name, int ndim, py::ssize_t columns = 0) {
  if (values.is_none()) {
    if (ndim == 1) return py::array_t<T>(std::vector<py::ssize_t>{0});
    return py::array_t<T>(std::vector<py::ssize_t>{0, columns});
  }
  auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!a || a.ndim() != ndim || (ndim == 2 && a.shape(1) != columns))
    throw py::value_error(std::string(name) + (ndim == 1 ? " must be a (K,) array of numbers"
                                                         : " must be a (K, 2) array of vertex numbers"));
  return a;
}

// Vertex numbers: integers that fit an int, never a float cut short or a
// large number wrapped around into another vertex.
py::array_t<int32_t> vertexArrayOf(const py::object& values, const char* name, int ndim) {
  if (!values.is_none()) {
    const py::array raw = py::array::ensure(values);
    const char kind = raw ? raw.dtype().kind() : '?';
    if (raw && raw.size() > 0 && kind != 'i' && kind != 'u')
      throw py::value_error(std::string(name) + " must be integer vertex numbers");
    const auto wide = arrayOf<int64_t>(values, name, ndim, 2);
    for (py::ssize_t i = 0; i < wide.size(); ++i) {
      if (wide.data()[i] < INT32_MIN || wide.data()[i] > INT32_MAX)
        throw py::value_error(std::string(name) + ": vertex number " + std::to_string(wide.data()[i]) +
                              " is out of range");
    }
  }
  return arrayOf<int32_t>(values, name, ndim, 2);
}

TagArrays tagArraysFrom(const py::object& creases, const py::object& creaseSharpness,
                        const py::object& corners, const py::object& cornerSharpness) {
  TagArrays a{vertexArrayOf(creases, "creases", 2), arrayOf<double>(creaseSharpness, "crease_sharpness", 1),
              vertexArrayOf(corners, "corners", 1), arrayOf<double>(cornerSharpness, "corner_sharpness", 1)};
  if (a.creases.shape(0) != a.creaseSharpness.shape(0))
    throw py::value_error("creases and crease_sharpness differ in length");
  if (a.corners.shape(0) != a.cornerSharpness.shape(0))
    throw py::value_error("corners and corner_sharpness differ in length");
  return a;
}

// Creases first, then corners, as write_tags writes them. A sharpness of
// math.inf (or any from 10 up) is an infinitely sharp tag.
std::vector<FeatureTag> featureTagsOf(const TagArrays& a) {
  std::vector<FeatureTag> tags;
  auto ends = a.creases.unchecked<2>();
  for (py::ssize_t i = 0; i < a.creases.shape(0); ++i) {
    tags.push_back({.kind = FeatureTag::Kind::kCrease,
                    .v0 = ends(i, 0),
                    .v1 = ends(i, 1),
                    .sharpness = static_cast<float>(a.creaseSharpness.data()[i])});
  }
  for (py::ssize_t i = 0; i < a.corners.shape(0); ++i) {
    tags.push_back({.kind = FeatureTag::Kind::kCorner,
                    .v0 = a.corners.data()[i],
                    .sharpness = static_cast<float>(a.cornerSharpness.data()[i])});
  }
  return tags;
}

// write_mesh's surface: a tessera.Mesh (its polygons where it has them),
// or points with faces.
SurfaceMesh surfaceFrom(const py::object& source, const py::object& faces, const py::object& normals) {
  PolygonSoup soup;
  std::vector<Vec3> points, normalRows;
  py::object givenNormals = normals;
  if (py::isinstance<MeshArrays>(source)) {
    if (!faces.is_none()) throw py::value_error("faces are given with points, not with a tessera.Mesh");
    const auto& mesh = source.cast<const MeshArrays&>();
    points = pointsFrom(mesh.positions);
    if (givenNormals.is_none()) givenNormals = mesh.normals;
    if (!mesh.polygonOffsets.is_none()) {
      const auto offsets = mesh.polygonOffsets.cast<py::array_t<int32_t>>();
      const auto corners = mesh.polygonCorners.cast<py::array_t<int32_t>>();
      for (py::ssize_t f = 0; f + 1 < offsets.shape(0); ++f)
        soup.addFace(
            std::vector<int>(corners.data() + offsets.data()[f], corners.data() + offsets.data()[f + 1]));
    } else {
      addFaces(mesh.triangles, soup);
    }
  } else {
    if (faces.is_none()) throw py::value_error("points need faces: write_mesh(path, points, faces)");
    points = pointsFrom(source);
    addFaces(faces, soup);
  }
  if (!givenNormals.is_none()) normalRows = pointsFrom(givenNormals);
  return surfaceOf(std::move(points), soup, std::move(normalRows));
}

constexpr const char* kSourceDoc =
    "    source: a mesh file (.obj .off .ply .stl .gltf .glb), or (N, 3) points with `faces`.\n"
    "    faces: with points, an (M, 3) integer array (or a list of index lists).\n"
    "    tags: a tag file ('crease I J S', 'corner I S' lines, docs/FORMATS.md).\n"
    "    triangulate, drop_unused, crease_angle: the import options of `tessera refine`.";

}  // namespace

void bindOffline(py::module_& m) {
  bindMesh(m);
  py::class_<TagArrays>(m, "Tags",
                        "Feature tags as a tag file states them (docs/FORMATS.md \"Tag sidecar files\"):\n"
                        "creases (edges by their two end vertices) and corners (vertices), each\n"
                        "with its sharpness. A sharpness of 10 or more (math.inf) is infinitely\n"
                        "sharp; read_tags gives such tags 10.0, as core stores them.")
      .def(py::init(&tagArraysFrom), py::kw_only(), py::arg("creases") = py::none(),
           py::arg("crease_sharpness") = py::none(), py::arg("corners") = py::none(),
           py::arg("corner_sharpness") = py::none(),
           "Tags from arrays: creases (K, 2) vertex numbers with crease_sharpness (K,),\n"
           "corners (C,) vertex numbers with corner_sharpness (C,). Raises ValueError for\n"
           "other shapes.")
      .def_readonly("creases", &TagArrays::creases, "(K, 2) int32: the two end vertices of each crease.")
      .def_readonly("crease_sharpness", &TagArrays::creaseSharpness, "(K,) float64: each crease's sharpness.")
      .def_readonly("corners", &TagArrays::corners, "(C,) int32: the tagged vertices.")
      .def_readonly("corner_sharpness", &TagArrays::cornerSharpness, "(C,) float64: each corner's sharpness.")
      .def("__repr__", [](const TagArrays& t) {
        return "<tessera.Tags " + std::to_string(t.creases.shape(0)) + " creases, " +
               std::to_string(t.corners.shape(0)) + " corners>";
      });
  m.def(
      "read_tags", [](const py::object& path) { return tagArrays(valueOf(readTagFile(pathOf(path)))); },
      py::arg("path"),
      "Reads a tag file ('crease I J S' and 'corner I S' lines, docs/FORMATS.md) as\n"
      "core's parser does: a tessera.Tags, creases and corners each in the file's\n"
      "order. Raises tessera.Error ('parse error', naming the file and line) for a\n"
      "line the parser refuses. The tags are not checked against a mesh: pass the\n"
      "file as read_mesh(tags=) or refine(tags=) for that.");
  m.def(
      "write_tags",
      [](const py::object& path, const TagArrays& tags) {
        check(writeTagFile(pathOf(path), featureTagsOf(tags)));
      },
      py::arg("path"), py::arg("tags"),
      "Writes a tessera.Tags as a tag file (docs/FORMATS.md): creases, then corners,\n"
      "one line each, each sharpness as the shortest decimal that reads back to the\n"
      "same float32 (core stores float32), 'inf' from 10 up. read_tags reads it back\n"
      "to the same tags. Raises tessera.Error ('invalid argument', naming the tag by\n"
      "its position: creases from 0, then corners) for a negative vertex number, a\n"
      "crease naming one vertex twice, a negative or NaN sharpness, or a second tag\n"
      "on an edge or a vertex, which the reader would refuse; nothing is written then.");
  m.def(
      "write_mesh",
      [](const py::object& path, const py::object& source, const py::object& faces, const py::object& normals,
         bool draco, const TagArrays* tags, std::optional<std::string> scheme,
         std::optional<std::string> boundary, std::optional<std::string> creaseMethod) {
        const std::string file = pathOf(path);
        SurfaceMesh surface = surfaceFrom(source, faces, normals);
        const CageArgs cage{.tags = tags ? featureTagsOf(*tags) : std::vector<FeatureTag>{},
                            .scheme = scheme.value_or(""),
                            .boundary = boundary.value_or(""),
                            .creaseMethod = creaseMethod.value_or("")};
        if (Status names = checkCageNames(cage); !names.isOk()) throw py::value_error(names.message());
        check(setCage(surface, cage, file));
        Status written = internalError("write_mesh: not run");
        {
          py::gil_scoped_release writing;
          written = writeSurface(surface, file, draco);
        }
        check(written);
      },
      py::arg("path"), py::arg("source"), py::arg("faces") = py::none(), py::kw_only(),
      py::arg("normals") = py::none(), py::arg("draco") = false, py::arg("tags") = py::none(),
      py::arg("scheme") = py::none(), py::arg("boundary") = py::none(), py::arg("crease_method") = py::none(),
      "Writes a surface to a mesh file with core's exporter (no server), the format\n"
      "chosen by the extension as `tessera refine -o` chooses it: .obj and .off (text,\n"
      "the shortest decimals that read back to the same doubles: lossless), .ply\n"
      "(binary, float32), .stl (binary, float32, facet normals only), .glb (glTF 2.0,\n"
      "float32; draco=True compresses it) or .usda. OBJ, OFF, PLY and USDA keep\n"
      "polygons; STL and GLB get each polygon as a fan of triangles.\n\n"
      "Args:\n"
      "    path: the file to write (replaced).\n"
      "    source: a tessera.Mesh (its polygons where it has them, its normals), or\n"
      "      (N, 3) points with `faces`.\n"
      "    faces: with points, an (M, k) integer array (k = 3: triangles) or a list of\n"
      "      index lists.\n"
      "    normals: (N, 3) per-vertex normals (OBJ, PLY, GLB, USDA write them); None:\n"
      "      the Mesh's, or none.\n"
      "    draco: .glb only, KHR_draco_mesh_compression.\n"
      "    tags, scheme, boundary, crease_method: the surface as a subdivision cage, for\n"
      "      .obj (OpenSubdiv's `t` lines: tags, boundary, crease_method; no scheme) and\n"
      "      .usda (all of them, scheme required: 'loop', 'catmull-clark' or 'bilinear');\n"
      "      a tessera.Tags, 'edge-only' or 'edge-and-corner', 'uniform' or 'chaikin'.\n"
      "      Other formats refuse them ('unsupported'); a tag on a vertex the surface does\n"
      "      not have or a crease on no face's edge is 'invalid argument', as the\n"
      "      readers would refuse it; an unknown name a ValueError.\n\n"
      "Raises tessera.Error naming the element at fault and writing nothing: 'unsupported'\n"
      "for another extension (or draco with another format), 'invalid mesh' for an index\n"
      "out of range, a non-finite position or normal, a zero normal or a normal count\n"
      "other than N, 'i/o error' when the file cannot be written.");
  m.def(
      "read_mesh",
      [](const py::object& source, const py::object& faces, std::optional<std::string> tags, bool triangulate,
         bool dropUnused, std::optional<double> creaseAngle) {
        SchemeSource from = sourceOf(source, faces);
        Expected<BaseMesh> mesh = internalError("read_mesh: not run");
        {
          py::gil_scoped_release reading;
          mesh = baseMeshOf(std::move(from), {tags, triangulate, dropUnused, creaseAngle});
        }
        check(mesh.status());
        SurfaceMesh surface;
        surface.positions = mesh->positions();
        surface.triangles = mesh->faceVertexIndices();
        return meshArrays(surface);  // normals None: a file's own are not read
      },
      py::arg("source"), py::arg("faces") = py::none(), py::kw_only(), py::arg("tags") = py::none(),
      py::arg("triangulate") = false, py::arg("drop_unused") = false, py::arg("crease_angle") = py::none(),
      (std::string("Reads and validates a base mesh as core imports it (no server): its\n"
                   "positions and triangles as a tessera.Mesh. Raises tessera.Error naming the\n"
                   "file, the line and the reason for a mesh that does not import.\n\nArgs:\n") +
       kSourceDoc)
          .c_str());
  m.def(
      "refine",
      [](const py::object& source, const py::object& faces, int level, bool limit,
         std::optional<std::string> tags, bool triangulate, bool dropUnused,
         std::optional<double> creaseAngle, const std::string& creaseMethod, const std::string& boundary,
         const std::string& scheme) {
        const ImportArgs args{tags, triangulate, dropUnused, creaseAngle};
        const LoopOptions options = loopOptions(creaseMethod, boundary);
        const bool defaults = creaseMethod == "uniform" && boundary == "edge-only";
        // The caller's choice of scheme and options: ValueError; the mesh's
        // own failures below: tessera.Error (errors.h).
        if (auto checked = checkSchemeArguments(scheme, args, defaults, level, limit); !checked.isOk())
          throw py::value_error(checked.status().message());
        SchemeSource from = sourceOf(source, faces);
        Expected<SurfaceMesh> surface = internalError("refine: not run");
        {
          py::gil_scoped_release refining;
          surface = refineScheme(scheme, std::move(from), args, options, defaults, level, limit);
        }
        return meshArrays(valueOf(std::move(surface)));
      },
      py::arg("source"), py::arg("faces") = py::none(), py::kw_only(), py::arg("level"),
      py::arg("limit") = false, py::arg("tags") = py::none(), py::arg("triangulate") = false,
      py::arg("drop_unused") = false, py::arg("crease_angle") = py::none(),
      py::arg("crease_method") = "uniform", py::arg("boundary") = "edge-only", py::arg("scheme") = "loop",
      (std::string("Refines a mesh uniformly (no server), as `tessera refine --scheme` does: Loop's\n"
                   "rules (the default) or another scheme, with sharp features where the scheme has\n"
                   "them (OpenSubdiv 3.5 semantics for loop and catmull-clark).\n\n"
                   "Returns a tessera.Mesh: the control points of `level` with the control mesh's\n"
                   "area-weighted vertex normals, or with limit=True their exact limit positions\n"
                   "and unit limit normals. The first vertices of every level are the input's, "
                   "in order. A polygon scheme's surface also has polygon_offsets and\n"
                   "polygon_corners (every face of a Catmull-Clark level is a quad).\n\nArgs:\n") +
       kSourceDoc +
       "\n    level: how many times to refine (0: the base mesh).\n"
       "    limit: limit positions and normals instead of control points (loop,\n"
       "      catmull-clark and sqrt3, whose limit has positions only).\n"
       "    crease_method: 'uniform' or 'chaikin'; boundary: 'edge-only' or 'edge-and-corner'.\n"
       "    scheme: 'loop', 'catmull-clark', 'bilinear' or 'doo-sabin' (polygons as they are,\n"
       "      without the import options), 'butterfly' or 'sqrt3' (triangles).")
          .c_str());
}

}  // namespace tessera::python
