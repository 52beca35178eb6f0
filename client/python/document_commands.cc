// tessera.Session's commands on documents as wholes (docs/PROTOCOL.md §5,
// §13.2, §17): list, create from a file or from arrays, open, close,
// delete, export, the control cage, grant.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "client/python/bindings.h"
#include "client/python/errors.h"
#include "client/python/mesh_bytes.h"
#include "client/python/numpy_arrays.h"
#include "client/python/replies.h"
#include "core/util/file_io.h"

namespace tessera::python {

namespace {

// The import and document options every create shares (tessera.proto
// CreateDocument).
struct CreateOptions {
  std::string name;
  std::optional<std::string> tags;  // a tag file's path
  uint32_t maxLevel = 0;
  bool triangulate = false, dropUnused = false;
  std::optional<double> creaseAngle;
  std::string scheme, creaseMethod, boundary;
};

void setOptions(wire::CreateDocument& c, const CreateOptions& o) {
  c.set_name(o.name);
  c.set_max_level(o.maxLevel);
  c.set_triangulate(o.triangulate);
  c.set_drop_unused(o.dropUnused);
  if (o.creaseAngle) {
    c.set_crease_by_angle(true);
    c.set_crease_angle(*o.creaseAngle);
  }
  if (o.tags) {
    c.set_tags(valueOf(readFile(*o.tags)));
    c.set_tags_file_name(*o.tags);
  }
  if (o.scheme == "loop")
    c.set_scheme(wire::SUBDIVISION_SCHEME_LOOP);
  else if (o.scheme == "catmull-clark")
    c.set_scheme(wire::SUBDIVISION_SCHEME_CATMULL_CLARK);
  else if (!o.scheme.empty())
    throw py::value_error("scheme must be 'loop' or 'catmull-clark', not '" + o.scheme + "'");
  if (o.creaseMethod == "chaikin")
    c.set_crease_method(wire::CREASE_METHOD_CHAIKIN);
  else if (o.creaseMethod == "uniform")
    c.set_crease_method(wire::CREASE_METHOD_UNIFORM);
  else if (!o.creaseMethod.empty())
    throw py::value_error("crease_method must be 'uniform' or 'chaikin'");
  if (o.boundary == "edge-and-corner")
    c.set_boundary(wire::BOUNDARY_INTERPOLATION_EDGE_AND_CORNER);
  else if (o.boundary == "edge-only")
    c.set_boundary(wire::BOUNDARY_INTERPOLATION_EDGE_ONLY);
  else if (!o.boundary.empty())
    throw py::value_error("boundary must be 'edge-only' or 'edge-and-corner'");
}

AckReply create(RemoteSession& s, wire::ClientMessage& m, std::optional<double> timeout) {
  // An import of a large mesh takes a while: a minute at least.
  return ackOf(s.call(m, timeout ? timeout : std::max(60.0, s.timeout())));
}

// A command naming only its document, answered with an Ack.
template <typename SetDocument>
auto documentCommand(SetDocument set) {
  return [set](RemoteSession& s, uint64_t document, std::optional<double> timeout) {
    wire::ClientMessage m;
    set(m, document);
    return ackOf(s.call(m, timeout));
  };
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  out.close();
  if (!out) throw Failure(ioError(path + ": cannot write the GLB"));
}

constexpr const char* kCreateOptionsDoc =
    "    name: the document's name.\n"
    "    tags: path of a tag file ('crease I J S', 'corner I S' lines, docs/FORMATS.md).\n"
    "    max_level: the deepest level edits and tessellation may reach; 0: the server's default.\n"
    "    triangulate, drop_unused, crease_angle: the import options of `tessera remote create`\n"
    "        (docs/PROTOCOL.md section 13.2).\n"
    "    scheme: 'loop' or 'catmull-clark'; None: catmull-clark when a face is not a triangle.\n"
    "    crease_method: 'uniform' or 'chaikin'; boundary: 'edge-only' or 'edge-and-corner'.\n"
    "    timeout: seconds to wait for the Ack (default: at least 60).\n\n"
    "Returns a tessera.Ack: document_id, version 1, scheme, dropped_vertices, creased_edges.\n"
    "Raises tessera.Rejected (e.g. REJECT_REASON_INVALID_MESH naming the element,\n"
    "REJECT_REASON_PERMISSION_DENIED without the admin role).";

}  // namespace

void bindDocumentCommands(SessionClass& session) {
  session.def(
      "list_documents",
      [](RemoteSession& s, std::optional<double> timeout) {
        wire::ClientMessage m;
        m.mutable_list_documents();
        const wire::ServerMessage reply = s.call(m, timeout);
        return std::vector<wire::DocumentInfo>(reply.document_list().documents().begin(),
                                               reply.document_list().documents().end());
      },
      py::arg("timeout") = py::none(), "The documents this token may read: a list of tessera.DocumentInfo.");

  session.def(
      "create_document",
      [](RemoteSession& s, const std::string& path, std::optional<std::string> name,
         std::optional<std::string> tags, uint32_t maxLevel, bool triangulate, bool dropUnused,
         std::optional<double> creaseAngle, std::optional<std::string> scheme,
         std::optional<std::string> creaseMethod, std::optional<std::string> boundary,
         std::optional<double> timeout) {
        wire::ClientMessage m;
        auto* c = m.mutable_create_document();
        c->set_mesh_format(meshFormatOf(path));
        c->set_mesh(valueOf(readFile(path)));
        c->set_file_name(path);
        setOptions(*c, {.name = name.value_or(std::filesystem::path(path).filename().string()),
                        .tags = tags,
                        .maxLevel = maxLevel,
                        .triangulate = triangulate,
                        .dropUnused = dropUnused,
                        .creaseAngle = creaseAngle,
                        .scheme = scheme.value_or(""),
                        .creaseMethod = creaseMethod.value_or(""),
                        .boundary = boundary.value_or("")});
        return create(s, m, timeout);
      },
      py::arg("path"), py::kw_only(), py::arg("name") = py::none(), py::arg("tags") = py::none(),
      py::arg("max_level") = 0, py::arg("triangulate") = false, py::arg("drop_unused") = false,
      py::arg("crease_angle") = py::none(), py::arg("scheme") = py::none(),
      py::arg("crease_method") = py::none(), py::arg("boundary") = py::none(),
      py::arg("timeout") = py::none(),
      (std::string("Imports a mesh file (.obj, .off, .ply, .stl, .glb) as a new document on the\n"
                   "server (admin role). The server reads the bytes and names the file in its errors.\n\n"
                   "Args:\n    path: the mesh file.\n") +
       kCreateOptionsDoc)
          .c_str());

  session.def(
      "create_document_from_arrays",
      [](RemoteSession& s, const py::object& points, const py::object& faces, const std::string& name,
         std::optional<std::string> tags, uint32_t maxLevel, std::optional<std::string> scheme,
         std::optional<std::string> creaseMethod, std::optional<std::string> boundary,
         std::optional<double> timeout) {
        PolygonSoup soup;
        addFaces(faces, soup);
        wire::ClientMessage m;
        auto* c = m.mutable_create_document();
        c->set_mesh_format(wire::MESH_FORMAT_OFF);
        c->set_mesh(offBytes(pointsFrom(points), soup));
        setOptions(*c, {.name = name,
                        .tags = tags,
                        .maxLevel = maxLevel,
                        .creaseAngle = std::nullopt,
                        .scheme = scheme.value_or(""),
                        .creaseMethod = creaseMethod.value_or(""),
                        .boundary = boundary.value_or("")});
        return create(s, m, timeout);
      },
      py::arg("points"), py::arg("faces"), py::kw_only(), py::arg("name") = "arrays",
      py::arg("tags") = py::none(), py::arg("max_level") = 0, py::arg("scheme") = py::none(),
      py::arg("crease_method") = py::none(), py::arg("boundary") = py::none(),
      py::arg("timeout") = py::none(),
      (std::string("Creates a document from NumPy arrays (admin role): `points` (N, 3) numbers and\n"
                   "`faces` an (M, 3) or (M, 4) integer array of vertex indices, counter-clockwise\n"
                   "(or a list of index lists of any lengths). They are sent as an OFF file written\n"
                   "by core's exporter, losslessly; tag vertex numbers are the rows of `points`.\n\n"
                   "Args:\n    points, faces: the base mesh.\n") +
       kCreateOptionsDoc)
          .c_str());

  session.def("open_document", documentCommand([](wire::ClientMessage& m, uint64_t d) {
                m.mutable_open_document()->set_document_id(d);
              }),
              py::arg("document_id"), py::arg("timeout") = py::none(),
              "Opens a document on this connection (any role on it); every other command on\n"
              "the document needs it open. Returns a tessera.Ack (version 0). Raises\n"
              "tessera.Rejected: REJECT_REASON_NOT_FOUND for an unknown document.");
  session.def(
      "close_document",
      [](RemoteSession& s, uint64_t document, std::optional<double> timeout) {
        wire::ClientMessage m;
        m.mutable_close_document()->set_document_id(document);
        AckReply ack = ackOf(s.call(m, timeout));
        s.stopWatching(document);
        return ack;
      },
      py::arg("document_id"), py::arg("timeout") = py::none(),
      "Closes a document on this connection (its subscription ends too).");
  session.def("delete_document", documentCommand([](wire::ClientMessage& m, uint64_t d) {
                m.mutable_delete_document()->set_document_id(d);
              }),
              py::arg("document_id"), py::arg("timeout") = py::none(),
              "Deletes a document (admin on it); it need not be open. Returns a tessera.Ack.");

  session.def(
      "export_document",
      [](RemoteSession& s, uint64_t document, uint32_t level, bool limit, bool draco,
         std::optional<std::string> path, std::optional<double> timeout) {
        wire::ClientMessage m;
        auto* e = m.mutable_export_document();
        e->set_document_id(document);
        e->set_level(level);
        e->set_limit(limit);
        e->set_draco(draco);
        const wire::ServerMessage reply = s.call(m, timeout ? timeout : std::max(60.0, s.timeout()));
        const std::string& glb = reply.export_result().glb();
        if (path) writeBytes(*path, glb);
        return py::make_tuple(reply.export_result().version(), py::bytes(glb));
      },
      py::arg("document_id"), py::arg("level"), py::kw_only(), py::arg("limit") = false,
      py::arg("draco") = false, py::arg("path") = py::none(), py::arg("timeout") = py::none(),
      "The document's surface refined uniformly to `level`, as glTF 2.0 binary (GLB),\n"
      "from the server (the document must be open).\n\n"
      "Args:\n"
      "    level: the uniform level to export.\n"
      "    limit: limit positions and normals instead of control points.\n"
      "    draco: Draco-compress the mesh (KHR_draco_mesh_compression).\n"
      "    path: also write the GLB to this file.\n\n"
      "Returns (version, glb): the version exported and the GLB's bytes.");

  session.def(
      "cage",
      [](RemoteSession& s, uint64_t document, uint32_t level, std::optional<double> timeout) {
        wire::ClientMessage m;
        m.mutable_get_cage()->set_document_id(document);
        m.mutable_get_cage()->set_level(level);
        const wire::ServerMessage reply = s.call(m, timeout);
        const wire::Cage& cage = reply.cage();
        py::array_t<uint32_t> sizes(cage.face_sizes_size());
        std::copy(cage.face_sizes().begin(), cage.face_sizes().end(), sizes.mutable_data());
        py::array_t<uint64_t> vertices(cage.vertices_size());
        std::copy(cage.vertices().begin(), cage.vertices().end(), vertices.mutable_data());
        return py::make_tuple(cage.version(), sizes, vertices);
      },
      py::arg("document_id"), py::arg("level") = 0, py::arg("timeout") = py::none(),
      "The polygons of one level of the document's control mesh (docs/PROTOCOL.md\n"
      "section 17), what a viewer draws as the control cage.\n\n"
      "Returns (version, face_sizes, vertex_ids): face k has face_sizes[k] corners,\n"
      "following those of face k - 1 in vertex_ids (uint64 packed ids at `level`),\n"
      "counter-clockwise.");

  session.def(
      "grant_token",
      [](RemoteSession& s, const std::string& token, const std::string& role, uint64_t document,
         std::optional<double> timeout) {
        wire::ClientMessage m;
        auto* g = m.mutable_grant_token();
        g->set_document_id(document);
        g->set_token(token);
        if (role == "viewer")
          g->set_role(wire::ROLE_VIEWER);
        else if (role == "editor")
          g->set_role(wire::ROLE_EDITOR);
        else if (role == "admin")
          g->set_role(wire::ROLE_ADMIN);
        else
          throw py::value_error("role must be 'viewer', 'editor' or 'admin', not '" + role + "'");
        return ackOf(s.call(m, timeout));
      },
      py::arg("token"), py::arg("role"), py::arg("document_id") = 0, py::arg("timeout") = py::none(),
      "Lets `token` act with `role` ('viewer', 'editor', 'admin') on one document, or\n"
      "on all of them with document_id 0 (admin role). Returns a tessera.Ack.");
}

}  // namespace tessera::python
