// tessera.Session's edit commands (docs/PROTOCOL.md §7.2, §13.1): each is
// built as an edit-script command (core/document/edit_script.h) and turned
// into its wire message by client/lib/script_wire.h, as `tessera remote
// edit` does, so that Python sends exactly what the CLI sends.
#include <pybind11/stl.h>

#include "client/lib/script_wire.h"
#include "client/python/bindings.h"
#include "client/python/element_ids.h"
#include "client/python/errors.h"
#include "client/python/replies.h"
#include "protocol/commands.h"

namespace tessera::python {

namespace {

using Kind = ScriptCommand::Kind;

Vec3 vec3Of(const std::array<double, 3>& v) {
  return {v[0], v[1], v[2]};
}

ScriptCommand command(Kind kind) {
  ScriptCommand c;
  c.kind = kind;
  return c;
}

AckReply sendEdit(RemoteSession& s, uint64_t document, const ScriptCommand& c, uint32_t key,
                  std::optional<double> timeout) {
  return ackOf(s.call(valueOf(client::clientMessageOf(c, document, key)), timeout));
}

constexpr const char* kEditReturns =
    "Returns a tessera.Ack: version (the document's new version) and edit_id.\n"
    "Raises tessera.Rejected with the server's reason (REJECT_REASON_NOT_FOUND for an\n"
    "unknown id, REJECT_REASON_NOT_OPEN, REJECT_REASON_PERMISSION_DENIED for a viewer,\n"
    "REJECT_REASON_LIMIT_EXCEEDED outside the document's grid, ...).";

std::string doc(const std::string& text) {
  return text + "\n\n" + kEditReturns;
}

}  // namespace

void bindEditCommands(SessionClass& session) {
  session.def(
      "move_vertex",
      [](RemoteSession& s, uint64_t document, const py::object& vertices, std::array<double, 3> target,
         uint32_t key, std::optional<double> timeout) {
        ScriptCommand c = command(Kind::kMove);
        c.vertices = vertexIdsOf(vertices);
        c.value = vec3Of(target);
        return sendEdit(s, document, c, key, timeout);
      },
      py::arg("document_id"), py::arg("vertex_ids"), py::arg("target"), py::kw_only(), py::arg("key") = 0,
      py::arg("timeout") = py::none(),
      doc("Direct manipulation: moves the first vertex's LIMIT position to `target`\n"
          "(x, y, z); the other vertices (all of one level) move by the same amount.\n"
          "Vertex ids are packed ints or text ('v2:40'); one id or a list.\n"
          "`key`: a morph document's key (0 or 1).")
          .c_str());
  session.def(
      "offset_vertices",
      [](RemoteSession& s, uint64_t document, const py::object& vertices, std::array<double, 3> displacement,
         uint32_t key, std::optional<double> timeout) {
        ScriptCommand c = command(Kind::kOffset);
        c.vertices = vertexIdsOf(vertices);
        c.value = vec3Of(displacement);
        return sendEdit(s, document, c, key, timeout);
      },
      py::arg("document_id"), py::arg("vertex_ids"), py::arg("displacement"), py::kw_only(),
      py::arg("key") = 0, py::arg("timeout") = py::none(),
      doc("Adds `displacement` (dx, dy, dz) to the control points of these vertices,\n"
          "all of one level: an offset at that level, which finer detail follows.")
          .c_str());
  session.def(
      "set_edge_sharpness",
      [](RemoteSession& s, uint64_t document, const py::object& edge, float sharpness, uint32_t key,
         std::optional<double> timeout) {
        ScriptCommand c = command(Kind::kCrease);
        c.sharpness = sharpness;
        // Two vertex ids: the edge named by its ends (PROTOCOL.md §7.2,
        // SetEdgeSharpness.end_vertex_ids), which the server resolves.
        const bool byEnds = py::isinstance<py::tuple>(edge) || py::isinstance<py::list>(edge);
        std::vector<VertexId> ends;
        if (byEnds) {
          ends = vertexIdsOf(edge);
          if (ends.size() != 2)
            throw py::value_error("an edge named by its ends takes two vertex ids, not " +
                                  std::to_string(ends.size()));
        } else {
          c.edge = edgeIdOf(edge);
        }
        wire::ClientMessage m = valueOf(client::clientMessageOf(c, document, key));
        if (byEnds) {
          auto* set = m.mutable_set_edge_sharpness();
          set->set_edge_id(kEdgeIdNamedByEnds);
          for (const VertexId& v : ends) set->add_end_vertex_ids(v.packed());
        }
        return ackOf(s.call(std::move(m), timeout));
      },
      py::arg("document_id"), py::arg("edge_id"), py::arg("sharpness"), py::kw_only(), py::arg("key") = 0,
      py::arg("timeout") = py::none(),
      doc("Tags an edge with a sharpness that holds at its level and below: 0 smooth,\n"
          "(0, 10) semi-sharp, 10 or more (or math.inf) a crease. `edge_id` is an edge id\n"
          "(packed int or 'e1:5') or a tuple of its two end vertices' ids, of one level,\n"
          "in either order (('v1:3', 'v1:40')): the server finds the edge, and refuses\n"
          "two vertices that no edge of that level joins (REJECT_REASON_INVALID_ARGUMENT).")
          .c_str());
  session.def(
      "set_vertex_sharpness",
      [](RemoteSession& s, uint64_t document, const py::object& vertex, float sharpness, uint32_t key,
         std::optional<double> timeout) {
        ScriptCommand c = command(Kind::kCorner);
        c.vertices = {vertexIdOf(vertex)};
        c.sharpness = sharpness;
        return sendEdit(s, document, c, key, timeout);
      },
      py::arg("document_id"), py::arg("vertex_id"), py::arg("sharpness"), py::kw_only(), py::arg("key") = 0,
      py::arg("timeout") = py::none(),
      doc("Sets a vertex's sharpness: 0 smooth, more a corner (or a cusp where no sharp\n"
          "edge meets it); 10 or more (or math.inf) infinitely sharp.")
          .c_str());
  session.def(
      "set_vertex_type",
      [](RemoteSession& s, uint64_t document, const py::object& vertex, const std::string& type, uint32_t key,
         std::optional<double> timeout) {
        // No edit-script form: the message itself (tessera.proto SetVertexType).
        wire::ClientMessage m;
        auto* set = m.mutable_set_vertex_type();
        set->set_document_id(document);
        set->set_vertex_id(vertexIdOf(vertex).packed());
        set->set_key(key);
        if (type == "smooth")
          set->set_type(wire::VERTEX_TYPE_SMOOTH);
        else if (type == "cusp")
          set->set_type(wire::VERTEX_TYPE_CUSP);
        else if (type == "corner")
          set->set_type(wire::VERTEX_TYPE_CORNER);
        else
          throw py::value_error("type must be 'smooth', 'cusp' or 'corner', not '" + type + "'");
        return ackOf(s.call(m, timeout));
      },
      py::arg("document_id"), py::arg("vertex_id"), py::arg("type"), py::kw_only(), py::arg("key") = 0,
      py::arg("timeout") = py::none(),
      doc("Sets a vertex's type by name: 'smooth' (sharpness 0), 'cusp' (infinitely sharp\n"
          "where no sharp edge meets it) or 'corner' (infinitely sharp where sharp edges\n"
          "meet it).")
          .c_str());
  session.def(
      "set_interpolation",
      [](RemoteSession& s, uint64_t document, const py::object& vertex, bool interpolating, double tension,
         std::optional<std::array<double, 3>> tangent, uint32_t key, std::optional<double> timeout) {
        ScriptCommand c = command(Kind::kInterpolate);
        c.vertices = {vertexIdOf(vertex)};
        c.interpolating = interpolating;
        c.tension = tension;
        if (tangent) c.value = vec3Of(*tangent);
        return sendEdit(s, document, c, key, timeout);
      },
      py::arg("document_id"), py::arg("vertex_id"), py::arg("interpolating") = true, py::kw_only(),
      py::arg("tension") = 1.0, py::arg("tangent") = py::none(), py::arg("key") = 0,
      py::arg("timeout") = py::none(),
      doc("Makes the limit surface pass through this vertex's control point\n"
          "(docs/INTERPOLATION.md), or stops it with interpolating=False. `tension` in\n"
          "[0.001, 1000] pulls the surface tighter; `tangent` (boundary and crease\n"
          "vertices only) sets the tangent line.")
          .c_str());
  session.def(
      "undo",
      [](RemoteSession& s, uint64_t document, uint64_t edit, uint32_t key, std::optional<double> timeout) {
        ScriptCommand c = command(Kind::kUndo);
        c.edit = EditId{edit};
        return sendEdit(s, document, c, key, timeout);
      },
      py::arg("document_id"), py::arg("edit_id"), py::kw_only(), py::arg("key") = 0,
      py::arg("timeout") = py::none(),
      doc("Undoes an edit by its id (an Ack's edit_id); the Ack's edit_id is the edit undone.\n"
          "REJECT_REASON_INVALID_STATE when it is undone already.")
          .c_str());
  session.def(
      "redo",
      [](RemoteSession& s, uint64_t document, uint64_t edit, uint32_t key, std::optional<double> timeout) {
        ScriptCommand c = command(Kind::kRedo);
        c.edit = EditId{edit};
        return sendEdit(s, document, c, key, timeout);
      },
      py::arg("document_id"), py::arg("edit_id"), py::kw_only(), py::arg("key") = 0,
      py::arg("timeout") = py::none(), doc("Redoes an undone edit by its id.").c_str());
  session.def(
      "edit",
      [](RemoteSession& s, uint64_t document, const std::string& script, uint32_t key,
         std::optional<double> timeout) {
        const std::vector<ScriptCommand> commands = valueOf(parseEditScript(script, "script"));
        if (commands.empty()) throw py::value_error("the script has no commands");
        if (commands.size() > static_cast<size_t>(kMaxEditBatchCommands)) {
          throw py::value_error(std::to_string(commands.size()) + " commands, above the server's limit of " +
                                std::to_string(kMaxEditBatchCommands) + " per batch");
        }
        wire::ClientMessage batch;
        batch.mutable_edit_batch()->set_document_id(document);
        for (const ScriptCommand& c : commands) {
          if (c.kind == Kind::kRemove)
            throw py::value_error("script:" + std::to_string(c.line) + ": remove is local only (use undo)");
          *batch.mutable_edit_batch()->add_commands() = client::editCommandOf(c, key);
        }
        return ackOf(s.call(batch, timeout));
      },
      py::arg("document_id"), py::arg("script"), py::kw_only(), py::arg("key") = 0,
      py::arg("timeout") = py::none(),
      "Applies an edit script (the format of `tessera doc edit`: 'move v2:40 to X Y Z',\n"
      "'offset v1:3 by DX DY DZ', 'crease e1:5 S', 'corner v0:2 S', 'undo N', ...) as\n"
      "ONE edit batch: all of it as one version, or none (docs/PROTOCOL.md section 13.1).\n\n"
      "Returns a tessera.Ack whose edit_ids has one edit per command. Raises\n"
      "tessera.Rejected with batch_index naming the refused command (from 1), and\n"
      "tessera.Error for a script that does not parse ('script:LINE: reason').");
}

}  // namespace tessera::python
