// tessera.Session: connecting, the session's own state, and reading what
// the server sends (docs/PROTOCOL.md §4, §6.3). The commands are bound in
// document_commands.cc, edit_commands.cc and view_bindings.cc.
#include <pybind11/stl.h>

#include "client/python/bindings.h"
#include "client/python/element_ids.h"
#include "client/python/errors.h"
#include "client/python/replies.h"

namespace tessera::python {

namespace {

// What receive() returns for a message: its kind and the fields a script
// waits on; the regions themselves are in the session's views.
py::dict summaryOf(const wire::ServerMessage& m) {
  py::dict d;
  const auto* field = wire::ServerMessage::descriptor()->FindFieldByNumber(m.body_case());
  d["kind"] = field != nullptr ? field->name() : std::string("unknown");
  if (m.has_snapshot()) {
    d["document_id"] = m.snapshot().document_id();
    d["version"] = m.snapshot().version();
    d["resync"] = m.snapshot().resync();
    d["remaining_parts"] = m.snapshot().remaining_parts();
  } else if (m.has_delta()) {
    d["document_id"] = m.delta().document_id();
    d["from_version"] = m.delta().from_version();
    d["version"] = m.delta().to_version();
    d["edit_id"] = m.delta().edit_id();
    d["author_session_id"] = m.delta().author_session_id();
  } else if (m.has_presence()) {
    d["document_id"] = m.presence().document_id();
    d["full"] = m.presence().full();
  } else if (m.has_applied_command()) {
    d["document_id"] = m.applied_command().document_id();
    d["version"] = m.applied_command().version();
    d["edit_id"] = m.applied_command().edit_id();
    d["author_name"] = m.applied_command().author_name();
  } else if (m.has_error()) {
    d["code"] = wire::ErrorCode_Name(m.error().code());
    d["message"] = m.error().message();
  } else if (m.has_reject()) {
    d["reason"] = wire::RejectReason_Name(m.reject().reason());
    d["message"] = m.reject().message();
  }
  return d;
}

}  // namespace

SessionClass bindSession(py::module_& m) {
  SessionClass session(m, "Session",
                       "A connection to tessera-server (docs/PROTOCOL.md), through the C++ client\n"
                       "library: every command waits for its reply and returns it (an Ack, a list,\n"
                       "an export) or raises tessera.Rejected with the server's reason.\n\n"
                       "Updates (snapshots, deltas, presence) are read by receive() and wait_for(),\n"
                       "which apply them to the session's views (Session.view) and presence\n"
                       "(Session.participants). Every blocking call releases the GIL while it\n"
                       "waits; calls from several threads take turns on the one connection.\n\n"
                       "    with tessera.Session.connect('127.0.0.1', 7878, token) as s:\n"
                       "        s.open_document(doc)\n"
                       "        ack = s.move_vertex(doc, 'v0:3', (0.0, 0.0, 1.5))");
  session.def_static(
      "connect",
      [](const std::string& host, uint16_t port, const std::string& token, const std::string& name, bool tls,
         const std::string& tlsCaFile, double timeout) {
        client::SessionOptions options;
        options.host = host;
        options.port = port;
        options.token = token;
        options.name = name;
        options.tls = tls || !tlsCaFile.empty();
        options.tlsCaFile = tlsCaFile;
        options.timeoutSeconds = timeout;
        return RemoteSession::connect(options);
      },
      py::arg("host") = "127.0.0.1", py::arg("port") = 7878, py::arg("token") = "",
      py::arg("name") = "tessera-python", py::kw_only(), py::arg("tls") = false, py::arg("tls_ca_file") = "",
      py::arg("timeout") = 10.0,
      "Connects to tessera-server at host:port and authenticates with `token`\n"
      "(docs/PROTOCOL.md section 4).\n\n"
      "Args:\n"
      "    host, port: the server's address.\n"
      "    token: an access token (the admin token, or one granted with\n"
      "        Session.grant_token / `tessera-server token new`). Empty: only ping works.\n"
      "    name: how other participants see this session in presence.\n"
      "    tls: connect with TLS, verifying the server's certificate and host name.\n"
      "    tls_ca_file: trusted certificates (PEM) for TLS; empty: the system's. Implies tls.\n"
      "    timeout: seconds to wait for the handshake and, later, for any reply\n"
      "        when a call gives no timeout of its own.\n\n"
      "Raises:\n"
      "    tessera.AuthenticationFailed: the server does not know the token.\n"
      "    tessera.ServerError: the server refused the handshake otherwise.\n"
      "    tessera.Error: nothing answers at host:port, or TLS failed.");
  session.def_property_readonly("session_id", &RemoteSession::sessionId,
                                "This connection's id, unique while the server runs.");
  session.def_property_readonly(
      "role", [](const RemoteSession& s) { return roleName(s.role()); },
      "The token's role on all documents: 'viewer', 'editor', 'admin', or '' when it\n"
      "has roles on some documents only (or no token was given).");
  session.def_property_readonly("timeout", &RemoteSession::timeout, "The default wait for a reply, seconds.");
  session.def_property_readonly("closed", &RemoteSession::closed, "Whether close() was called.");
  session.def("close", &RemoteSession::close, "Closes the connection; the session cannot be used after.");
  session.def(
      "__enter__", [](std::shared_ptr<RemoteSession> s) { return s; },
      "`with` keeps the session open in its block.");
  session.def(
      "__exit__", [](RemoteSession& s, const py::args&) { s.close(); },
      "Closes the session at the end of `with`.");

  session.def(
      "ping",
      [](RemoteSession& s, std::optional<double> timeout) {
        wire::ClientMessage message;
        message.mutable_ping();
        return s.call(message, timeout).pong().server_time_unix_ms();
      },
      py::arg("timeout") = py::none(), "Asks the server for its clock: milliseconds since 1970 (its Pong).");
  session.def(
      "stats",
      [](RemoteSession& s, std::optional<double> timeout) {
        wire::ClientMessage message;
        message.mutable_stats();
        std::map<std::string, double> stats;
        for (const auto& stat : s.call(message, timeout).stats_reply().stats())
          stats[stat.name()] = stat.value();
        return stats;
      },
      py::arg("timeout") = py::none(), "The server's counters by name (docs/PROTOCOL.md lists them).");

  session.def(
      "receive",
      [](RemoteSession& s, double timeout) -> py::object {
        auto next = s.receive(timeout);
        if (!next) return py::none();
        return summaryOf(*next);
      },
      py::arg("timeout") = 1.0,
      "Reads the next message the server sent that was no reply: a snapshot, a\n"
      "delta, presence, an applied command or a non-fatal error. It is applied to\n"
      "the view of its document (see subscribe) and to presence first.\n\n"
      "Returns a dict with 'kind' ('snapshot', 'delta', 'presence', ...) and, where\n"
      "they apply, 'document_id', 'version', 'edit_id', ...; None when nothing\n"
      "arrives within `timeout` seconds (the connection stays usable).\n"
      "Raises tessera.ServerError for a fatal error (the server closes the connection).");

  session.def(
      "participants",
      [](const RemoteSession& s, uint64_t document) { return s.presence().participants(document); },
      py::arg("document_id"),
      "Who has the document open, as the presence messages read so far say\n"
      "(docs/PROTOCOL.md section 6.3): a list of tessera.Participant. Presence comes up\n"
      "to 100 ms after a change, and is read by receive() and wait_for().");
  session.def(
      "select",
      [](RemoteSession& s, uint64_t document, const py::object& vertices) {
        wire::ClientMessage message;
        message.mutable_select()->set_document_id(document);
        for (VertexId v : vertexIdsOf(vertices))
          message.mutable_select()->mutable_selection()->add_vertex_ids(v.packed());
        s.send(message);
      },
      py::arg("document_id"), py::arg("vertex_ids"),
      "Replaces this participant's selection in an open document with these\n"
      "vertices (packed ids or 'v2:40' text). A valid selection gets no reply: the\n"
      "others (and this session) see it in presence. An invalid one comes back as a\n"
      "'reject' from receive().");
  return session;
}

}  // namespace tessera::python
