// The replies a command returns to Python: an Ack's fields (docs/PROTOCOL.md
// §5) and a listed document, as plain values with readable names.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <vector>

#include "protocol/tessera.pb.h"

namespace tessera::python {

namespace py = pybind11;

struct AckReply {
  uint64_t documentId = 0;
  uint64_t version = 0;
  uint64_t editId = 0;
  std::vector<uint64_t> editIds;
  uint32_t droppedVertices = 0;
  uint32_t creasedEdges = 0;
  std::string scheme;  // "loop", "catmull-clark", or "" when the Ack names none
};

// Failure (an internal error: a reply the protocol does not give that
// command) unless `present`, i.e. unless the reply a command waited for is
// of the kind `expected` names ("an Ack"); `command` names the command in
// the message, or is empty.
void requireReply(bool present, const std::string& command, const std::string& expected);
// The Ack in `reply`; Failure when the reply is something else.
AckReply ackOf(const wire::ServerMessage& reply);
// "loop" / "catmull-clark" / "", and "viewer" / "editor" / "admin" / "".
std::string schemeName(wire::SubdivisionScheme scheme);
std::string roleName(wire::Role role);
// "uniform" / "chaikin", and "edge-only" / "edge-and-corner": the names
// create_document takes (document_commands.cc); unknown values read as
// the first, the protocol's default.
std::string creaseMethodName(wire::CreaseMethod method);
std::string boundaryName(wire::BoundaryInterpolation boundary);

void bindReplies(py::module_& m);

}  // namespace tessera::python
