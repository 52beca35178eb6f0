// What every side needs to know of the wire's commands, written once: the
// document a client message names, the request a server message answers,
// an EditBatch's commands unwrapped, the bound on a batch and the packed
// ids with a special meaning (docs/PROTOCOL.md §5, §7.2 and §13). The
// switches over the messages' oneofs live here and nowhere else.
#pragma once

#include <cstdint>

#include "protocol/tessera.pb.h"

namespace tessera {

// The bound on an EditBatch (docs/PROTOCOL.md, EditBatch): what a server
// applies as one version and a client may send in one message. A larger
// batch is refused with REJECT_REASON_LIMIT_EXCEEDED before anything is
// applied; a client splits nothing on its own (that would not be atomic).
inline constexpr int kMaxEditBatchCommands = 1024;

// SetEdgeSharpness.edge_id when the edge is named by end_vertex_ids instead:
// all ones (level 63), which a server without end_vertex_ids refuses as an
// unknown edge rather than tagging e0:0, the proto3 default.
inline constexpr uint64_t kEdgeIdNamedByEnds = ~uint64_t{0};

// The document a client message is about; 0 for one that names none
// (hello, list, create, ...).
uint64_t documentOf(const wire::ClientMessage& message);

// The client_seq of the request a server message answers; 0 for one that
// answers none (deltas, snapshots, presence, errors).
uint64_t replyTo(const wire::ServerMessage& message);

// Sets the one edit `command` holds on `into`, a ClientMessage or an
// AppliedCommand (both name the edit commands alike); false, with `into`
// unchanged, when it holds none.
template <typename Message>
bool unwrapEditCommand(const wire::EditCommand& command, Message& into) {
  switch (command.command_case()) {
    case wire::EditCommand::kMoveVertex:
      *into.mutable_move_vertex() = command.move_vertex();
      return true;
    case wire::EditCommand::kSetEdgeSharpness:
      *into.mutable_set_edge_sharpness() = command.set_edge_sharpness();
      return true;
    case wire::EditCommand::kSetVertexType:
      *into.mutable_set_vertex_type() = command.set_vertex_type();
      return true;
    case wire::EditCommand::kUndo:
      *into.mutable_undo() = command.undo();
      return true;
    case wire::EditCommand::kRedo:
      *into.mutable_redo() = command.redo();
      return true;
    case wire::EditCommand::kSetInterpolation:
      *into.mutable_set_interpolation() = command.set_interpolation();
      return true;
    case wire::EditCommand::COMMAND_NOT_SET:
      return false;
  }
  return false;
}

// Copies the edit command a client sent onto what recorders receive
// (AppliedCommand); commands that are not edits copy nothing.
void copyEditCommand(const wire::ClientMessage& from, wire::AppliedCommand& into);

}  // namespace tessera
