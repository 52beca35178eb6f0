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

// The Ack in `reply`; Failure when the reply is something else.
AckReply ackOf(const wire::ServerMessage& reply);
// "loop" / "catmull-clark" / "", and "viewer" / "editor" / "admin" / "".
std::string schemeName(wire::SubdivisionScheme scheme);
std::string roleName(wire::Role role);

void bindReplies(py::module_& m);

}  // namespace tessera::python
