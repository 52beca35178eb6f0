#include "protocol/commands.h"

namespace tessera {

uint64_t documentOf(const wire::ClientMessage& m) {
  using C = wire::ClientMessage;
  switch (m.command_case()) {
    case C::kSubscribe:
      return m.subscribe().document_id();
    case C::kUnsubscribe:
      return m.unsubscribe().document_id();
    case C::kSelect:
      return m.select().document_id();
    case C::kExportDocument:
      return m.export_document().document_id();
    case C::kMoveVertex:
      return m.move_vertex().document_id();
    case C::kSetEdgeSharpness:
      return m.set_edge_sharpness().document_id();
    case C::kSetVertexType:
      return m.set_vertex_type().document_id();
    case C::kSetInterpolation:
      return m.set_interpolation().document_id();
    case C::kUndo:
      return m.undo().document_id();
    case C::kRedo:
      return m.redo().document_id();
    case C::kEditBatch:
      return m.edit_batch().document_id();
    case C::kAddMorphKey:
      return m.add_morph_key().document_id();
    case C::kGetMorphControl:
      return m.get_morph_control().document_id();
    case C::kSetView:
      return m.set_view().document_id();
    case C::kGetCage:
      return m.get_cage().document_id();
    default:
      return 0;
  }
}

uint64_t replyTo(const wire::ServerMessage& m) {
  using S = wire::ServerMessage;
  switch (m.body_case()) {
    case S::kHelloAck:
      return m.hello_ack().client_seq();
    case S::kAck:
      return m.ack().client_seq();
    case S::kReject:
      return m.reject().client_seq();
    case S::kDocumentList:
      return m.document_list().client_seq();
    case S::kExportResult:
      return m.export_result().client_seq();
    case S::kPong:
      return m.pong().client_seq();
    case S::kStatsReply:
      return m.stats_reply().client_seq();
    case S::kMorphControl:
      return m.morph_control().client_seq();
    case S::kCage:
      return m.cage().client_seq();
    default:
      return 0;
  }
}

void copyEditCommand(const wire::ClientMessage& from, wire::AppliedCommand& into) {
  using C = wire::ClientMessage;
  switch (from.command_case()) {
    case C::kMoveVertex:
      *into.mutable_move_vertex() = from.move_vertex();
      break;
    case C::kSetEdgeSharpness:
      *into.mutable_set_edge_sharpness() = from.set_edge_sharpness();
      break;
    case C::kSetVertexType:
      *into.mutable_set_vertex_type() = from.set_vertex_type();
      break;
    case C::kUndo:
      *into.mutable_undo() = from.undo();
      break;
    case C::kRedo:
      *into.mutable_redo() = from.redo();
      break;
    case C::kEditBatch:
      *into.mutable_edit_batch() = from.edit_batch();
      break;
    case C::kSetInterpolation:
      *into.mutable_set_interpolation() = from.set_interpolation();
      break;
    case C::kAddMorphKey:
      *into.mutable_add_morph_key() = from.add_morph_key();
      break;
    default:
      break;
  }
}

}  // namespace tessera
