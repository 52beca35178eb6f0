// tessera.Session's commands on morph documents (docs/PROTOCOL.md §14,
// "Morph documents"): AddMorphKey, which gives a document its second key,
// and GetMorphControl, the control points at a time t (the coarse stream).
// The messages are those `tessera remote morph-key` and tessera-view send
// (client/cli/remote_morph.cc, client/view/connection.cc), sent through
// client::Session; edits name their key with `key=` (edit_commands.cc) and
// a subscription its time with `morph_t=` (view_bindings.cc).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>

#include "client/python/bindings.h"
#include "client/python/errors.h"
#include "client/python/mesh_bytes.h"
#include "client/python/numpy_arrays.h"
#include "client/python/replies.h"
#include "core/util/file_io.h"

namespace tessera::python {

namespace {

// A MorphControl reply as arrays (tessera.MorphControl).
struct MorphControlArrays {
  uint64_t documentId = 0, version = 0;
  double t = 0;
  py::array_t<float> points;                // (N, 3), float32 as sent
  py::object triangles = py::none();        // (M, 3) uint32, with_topology only
  py::object creases = py::none();          // (K, 2) uint32
  py::object creaseSharpness = py::none();  // (K,) float32
  py::object vertexSharpness = py::none();  // (N,) float32
  std::string creaseMethod, boundary;       // "" without topology
  uint32_t maxLevel = 0;
  py::bytes imageFrom, imageTo;
};

template <typename T, typename Repeated>
py::array_t<T> arrayOf(const Repeated& values, py::ssize_t columns) {
  const auto rows = static_cast<py::ssize_t>(values.size()) / std::max<py::ssize_t>(columns, 1);
  py::array_t<T> a(columns > 0 ? std::vector<py::ssize_t>{rows, columns} : std::vector<py::ssize_t>{rows});
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

MorphControlArrays morphControlOf(const wire::ServerMessage& reply, bool withTopology) {
  requireReply(reply.has_morph_control(), "get_morph_control", "MorphControl");
  const wire::MorphControl& c = reply.morph_control();
  if (c.points_size() % 3 != 0 || c.triangles_size() % 3 != 0 || c.crease_vertices_size() % 2 != 0)
    throw Failure(parseError("MorphControl: points, triangles or crease ends not whole (" +
                             std::to_string(c.points_size()) + " coordinates, " +
                             std::to_string(c.triangles_size()) + " triangle corners, " +
                             std::to_string(c.crease_vertices_size()) + " crease ends)"));
  MorphControlArrays a;
  a.documentId = c.document_id();
  a.version = c.version();
  a.t = c.t();
  a.points = arrayOf<float>(c.points(), 3);
  a.imageFrom = py::bytes(c.image_from());
  a.imageTo = py::bytes(c.image_to());
  if (!withTopology) return a;
  a.triangles = arrayOf<uint32_t>(c.triangles(), 3);
  a.creases = arrayOf<uint32_t>(c.crease_vertices(), 2);
  a.creaseSharpness = arrayOf<float>(c.crease_sharpness(), 0);
  a.vertexSharpness = arrayOf<float>(c.vertex_sharpness(), 0);
  a.creaseMethod = creaseMethodName(c.crease_method());
  a.boundary = boundaryName(c.boundary());
  a.maxLevel = c.max_level();
  return a;
}

}  // namespace

void bindMorphCommands(py::module_& m, SessionClass& session) {
  py::class_<MorphControlArrays>(
      m, "MorphControl",
      "A morph document's control mesh at time t (docs/PROTOCOL.md section 14, the\n"
      "coarse stream): its base points on their paths, and with with_topology its\n"
      "triangles, tags at t and options. Finer edits of the keys are not in it.")
      .def_readonly("document_id", &MorphControlArrays::documentId, "The document.")
      .def_readonly("version", &MorphControlArrays::version, "The document version it was taken at.")
      .def_readonly("t", &MorphControlArrays::t, "The time asked for, not rounded.")
      .def_readonly("points", &MorphControlArrays::points,
                    "(N, 3) float32: every base point at t, as the server sent it.")
      .def_readonly("triangles", &MorphControlArrays::triangles,
                    "(M, 3) uint32 base vertex indices per triangle; None without with_topology.")
      .def_readonly("creases", &MorphControlArrays::creases,
                    "(K, 2) uint32 end vertices of each base crease; None without with_topology.")
      .def_readonly("crease_sharpness", &MorphControlArrays::creaseSharpness,
                    "(K,) float32 sharpness of each crease at t; None without with_topology.")
      .def_readonly("vertex_sharpness", &MorphControlArrays::vertexSharpness,
                    "(N,) float32 sharpness of each base vertex at t; None without with_topology.")
      .def_readonly("crease_method", &MorphControlArrays::creaseMethod,
                    "'uniform' or 'chaikin' with with_topology; '' without.")
      .def_readonly("boundary", &MorphControlArrays::boundary,
                    "'edge-only' or 'edge-and-corner' with with_topology; '' without.")
      .def_readonly("max_level", &MorphControlArrays::maxLevel,
                    "The document's deepest level with with_topology; 0 without.")
      .def_readonly("image_from", &MorphControlArrays::imageFrom,
                    "A 2D morph's PNG under key 0 (with_topology); b'' if none.")
      .def_readonly("image_to", &MorphControlArrays::imageTo,
                    "A 2D morph's PNG under key 1 (with_topology); b'' if none.")
      .def("__repr__", [](const MorphControlArrays& c) {
        return "<tessera.MorphControl document " + std::to_string(c.documentId) + ", version " +
               std::to_string(c.version) + ", t " + std::to_string(c.t) + ", " +
               std::to_string(c.points.shape(0)) + " points>";
      });

  session.def(
      "add_morph_key",
      [](RemoteSession& s, uint64_t document, const py::object& source, const py::object& faces,
         std::optional<std::string> imageFrom, std::optional<std::string> imageTo,
         std::optional<double> timeout) {
        if (imageFrom.has_value() != imageTo.has_value())
          throw py::value_error("image_from and image_to go together: both images or neither");
        wire::ClientMessage m;
        auto* add = m.mutable_add_morph_key();
        add->set_document_id(document);
        if (py::isinstance<py::str>(source) || py::hasattr(source, "__fspath__")) {
          if (!faces.is_none()) throw py::value_error("faces are given with points, not with a file");
          const std::string path = py::str(py::module_::import("os").attr("fspath")(source));
          add->set_mesh_format(meshFormatOf(path));
          add->set_mesh(valueOf(readFile(path)));
          add->set_file_name(path);
        } else {
          if (faces.is_none()) throw py::value_error("points need faces: add_morph_key(doc, points, faces)");
          PolygonSoup soup;
          addFaces(faces, soup);
          add->set_mesh_format(wire::MESH_FORMAT_OFF);
          add->set_mesh(offBytes(pointsFrom(source), soup));
          add->set_file_name("arrays");
        }
        if (imageFrom) {
          add->set_image_from(valueOf(readFile(*imageFrom)));
          add->set_image_to(valueOf(readFile(*imageTo)));
        }
        // The server imports the key and rebuilds the document: as long as
        // a create (document_commands.cc).
        return ackOf(s.call(m, timeout ? timeout : std::max(60.0, s.timeout())));
      },
      py::arg("document_id"), py::arg("source"), py::arg("faces") = py::none(), py::kw_only(),
      py::arg("image_from") = py::none(), py::arg("image_to") = py::none(), py::arg("timeout") = py::none(),
      "Makes an open document a morph document (docs/PROTOCOL.md section 14, editor\n"
      "role) by sending its key 1, as `tessera remote morph-key` does: a mesh of key\n"
      "0's base triangles, vertex for vertex, with other points. Key 1 starts with key\n"
      "0's tags and edits; from then on edits name their key (key=1), and\n"
      "subscribe(morph_t=) and get_morph_control show the document between the keys.\n\n"
      "Args:\n"
      "    source: a mesh file (.obj .off .ply .stl .glb .usda), or (N, 3) points with\n"
      "      `faces` (sent as an OFF file written by core's exporter, losslessly).\n"
      "    faces: with points, an (M, 3) integer array (or a list of index lists).\n"
      "    image_from, image_to: a 2D morph's PNG files under key 0 and key 1, both or\n"
      "      neither (ValueError otherwise).\n"
      "    timeout: seconds to wait for the Ack (default: at least 60).\n\n"
      "Returns a tessera.Ack (document_id, version). Raises tessera.Rejected with the\n"
      "server's message: REJECT_REASON_INVALID_ARGUMENT naming the first triangle\n"
      "that differs from key 0's, or when the document already has two keys;\n"
      "REJECT_REASON_LIMIT_EXCEEDED when key 1 leaves the document's grid;\n"
      "REJECT_REASON_PERMISSION_DENIED for a viewer.");

  session.def(
      "get_morph_control",
      [](RemoteSession& s, uint64_t document, double t, bool withTopology, std::optional<double> timeout) {
        wire::ClientMessage m;
        auto* get = m.mutable_get_morph_control();
        get->set_document_id(document);
        get->set_t(t);
        get->set_with_topology(withTopology);
        return morphControlOf(s.call(m, timeout), withTopology);
      },
      py::arg("document_id"), py::arg("t"), py::kw_only(), py::arg("with_topology") = false,
      py::arg("timeout") = py::none(),
      "A morph document's control mesh at time t in [0, 1] (docs/PROTOCOL.md section\n"
      "14, the coarse stream; any role, document open): its base points, linear in t\n"
      "between the keys' base points, and with with_topology=True its triangles,\n"
      "crease ends with their sharpness at t, vertex sharpness at t, options and\n"
      "images. Ask once with with_topology, then for the points only.\n\n"
      "Returns a tessera.MorphControl. Raises tessera.Rejected with the server's\n"
      "message: REJECT_REASON_INVALID_ARGUMENT for a document with one key or a t\n"
      "outside [0, 1].");
}

}  // namespace tessera::python
