#include "client/python/replies.h"

#include <pybind11/stl.h>

#include "client/python/errors.h"

namespace tessera::python {

void requireReply(bool present, const std::string& command, const std::string& expected) {
  if (!present) {
    throw Failure(internalError("the server answered " + (command.empty() ? "" : command + " ") +
                                "with something other than " + expected));
  }
}

AckReply ackOf(const wire::ServerMessage& reply) {
  requireReply(reply.has_ack(), "", "an Ack");
  const wire::Ack& a = reply.ack();
  return {.documentId = a.document_id(),
          .version = a.version(),
          .editId = a.edit_id(),
          .editIds = {a.edit_ids().begin(), a.edit_ids().end()},
          .droppedVertices = a.dropped_vertices(),
          .creasedEdges = a.creased_edges(),
          .scheme = schemeName(a.scheme())};
}

std::string schemeName(wire::SubdivisionScheme scheme) {
  switch (scheme) {
    case wire::SUBDIVISION_SCHEME_LOOP:
      return "loop";
    case wire::SUBDIVISION_SCHEME_CATMULL_CLARK:
      return "catmull-clark";
    default:
      return "";
  }
}

std::string roleName(wire::Role role) {
  switch (role) {
    case wire::ROLE_VIEWER:
      return "viewer";
    case wire::ROLE_EDITOR:
      return "editor";
    case wire::ROLE_ADMIN:
      return "admin";
    default:
      return "";
  }
}

std::string creaseMethodName(wire::CreaseMethod method) {
  return method == wire::CREASE_METHOD_CHAIKIN ? "chaikin" : "uniform";
}

std::string boundaryName(wire::BoundaryInterpolation boundary) {
  return boundary == wire::BOUNDARY_INTERPOLATION_EDGE_AND_CORNER ? "edge-and-corner" : "edge-only";
}

void bindReplies(py::module_& m) {
  py::class_<AckReply>(m, "Ack",
                       "A command was accepted (docs/PROTOCOL.md section 5). Fields the command\n"
                       "does not set are 0 (or empty).")
      .def_readonly("document_id", &AckReply::documentId, "The created or affected document.")
      .def_readonly("version", &AckReply::version,
                    "The document's version after the command (1 at creation; 0 for open).")
      .def_readonly("edit_id", &AckReply::editId, "The edit made, undone or redone; 0 if none.")
      .def_readonly("edit_ids", &AckReply::editIds,
                    "An edit batch's edits, one per command, in order (edit_id is the last).")
      .def_readonly("dropped_vertices", &AckReply::droppedVertices,
                    "create_document with drop_unused: how many vertices were dropped.")
      .def_readonly("creased_edges", &AckReply::creasedEdges,
                    "create_document with crease_angle: how many edges became creases.")
      .def_readonly("scheme", &AckReply::scheme,
                    "create_document: 'loop' or 'catmull-clark', the scheme the document got.")
      .def("__repr__", [](const AckReply& a) {
        return "<tessera.Ack document " + std::to_string(a.documentId) + ", version " +
               std::to_string(a.version) + ", edit " + std::to_string(a.editId) + ">";
      });

  py::class_<wire::DocumentInfo>(m, "DocumentInfo", "A document the token may read (Session.list_documents).")
      .def_property_readonly("document_id", &wire::DocumentInfo::document_id, "The document's id.")
      .def_property_readonly(
          "name", [](const wire::DocumentInfo& d) { return d.name(); }, "The name it was created with.")
      .def_property_readonly("version", &wire::DocumentInfo::version, "Its current version.")
      .def_property_readonly("max_level", &wire::DocumentInfo::max_level,
                             "The deepest level edits and tessellation may reach; 0 when the server\n"
                             "does not say (docs/PROTOCOL.md section 12: this server does not).")
      .def("__repr__", [](const wire::DocumentInfo& d) {
        return "<tessera.DocumentInfo " + std::to_string(d.document_id()) + " '" + d.name() + "', version " +
               std::to_string(d.version()) + ">";
      });

  py::class_<wire::Participant>(m, "Participant",
                                "Someone who has a document open (docs/PROTOCOL.md section 6.3).")
      .def_property_readonly("session_id", &wire::Participant::session_id, "Their connection's session id.")
      .def_property_readonly(
          "name", [](const wire::Participant& p) { return p.name(); },
          "The name their session connected with.")
      .def_property_readonly(
          "role", [](const wire::Participant& p) { return roleName(p.role()); },
          "'viewer', 'editor' or 'admin' on that document.")
      .def_property_readonly(
          "selected_vertex_ids",
          [](const wire::Participant& p) {
            return std::vector<uint64_t>(p.selection().vertex_ids().begin(),
                                         p.selection().vertex_ids().end());
          },
          "The packed ids of the vertices they have selected.")
      .def("__repr__", [](const wire::Participant& p) {
        return "<tessera.Participant " + std::to_string(p.session_id()) + " '" + p.name() + "'>";
      });
}

}  // namespace tessera::python
