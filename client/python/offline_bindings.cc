// Work without a server, straight on core (docs/PYTHON.md "Offline"): read
// a mesh as core imports it, and refine it uniformly with Loop's rules to
// control points or the limit surface (core/loop/loop_refiner.h), as
// `tessera refine` does.
#include <pybind11/stl.h>

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

constexpr const char* kSourceDoc =
    "    source: a mesh file (.obj .off .ply .stl .gltf .glb), or (N, 3) points with `faces`.\n"
    "    faces: with points, an (M, 3) integer array (or a list of index lists).\n"
    "    tags: a tag file ('crease I J S', 'corner I S' lines, docs/FORMATS.md).\n"
    "    triangulate, drop_unused, crease_angle: the import options of `tessera refine`.";

}  // namespace

void bindOffline(py::module_& m) {
  bindMesh(m);
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
