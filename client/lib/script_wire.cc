#include "client/lib/script_wire.h"

#include "protocol/commands.h"
#include "protocol/morph_key.h"

namespace tessera::client {

wire::EditCommand editCommandOf(const ScriptCommand& c, uint32_t key) {
  wire::EditCommand m;
  using Kind = ScriptCommand::Kind;
  switch (c.kind) {
    case Kind::kMove:
    case Kind::kOffset: {
      auto* move = m.mutable_move_vertex();
      for (VertexId v : c.vertices) move->add_vertex_ids(v.packed());
      move->mutable_target()->set_x(c.value[0]);
      move->mutable_target()->set_y(c.value[1]);
      move->mutable_target()->set_z(c.value[2]);
      move->set_mode(c.kind == Kind::kMove ? wire::MOVE_MODE_DIRECT_MANIPULATION : wire::MOVE_MODE_OFFSET);
      break;
    }
    case Kind::kCrease:
      m.mutable_set_edge_sharpness()->set_edge_id(c.edge.packed());
      m.mutable_set_edge_sharpness()->set_sharpness(c.sharpness);
      break;
    case Kind::kCorner:
      m.mutable_set_vertex_type()->set_vertex_id(c.vertices[0].packed());
      m.mutable_set_vertex_type()->set_sharpness(c.sharpness);
      break;
    case Kind::kInterpolate: {
      auto* tag = m.mutable_set_interpolation();
      tag->set_vertex_id(c.vertices[0].packed());
      tag->set_interpolating(c.interpolating);
      tag->set_tension(c.tension);
      tag->mutable_tangent()->set_x(c.value[0]);
      tag->mutable_tangent()->set_y(c.value[1]);
      tag->mutable_tangent()->set_z(c.value[2]);
      break;
    }
    case Kind::kUndo:
      m.mutable_undo()->set_edit_id(c.edit.value);
      break;
    case Kind::kRedo:
      m.mutable_redo()->set_edit_id(c.edit.value);
      break;
    case Kind::kRemove:
      break;  // refused before anything is sent
  }
  setMorphKey(m, key);
  return m;
}

Expected<wire::ClientMessage> clientMessageOf(const ScriptCommand& c, uint64_t document, uint32_t key) {
  if (c.kind == ScriptCommand::Kind::kRemove)
    return unsupported("line " + std::to_string(c.line) + ": remove is local only (use undo)");
  wire::ClientMessage message;
  unwrapEditCommand(editCommandOf(c, key), message);
  switch (message.command_case()) {
    case wire::ClientMessage::kMoveVertex:
      message.mutable_move_vertex()->set_document_id(document);
      break;
    case wire::ClientMessage::kSetEdgeSharpness:
      message.mutable_set_edge_sharpness()->set_document_id(document);
      break;
    case wire::ClientMessage::kSetVertexType:
      message.mutable_set_vertex_type()->set_document_id(document);
      break;
    case wire::ClientMessage::kSetInterpolation:
      message.mutable_set_interpolation()->set_document_id(document);
      break;
    case wire::ClientMessage::kUndo:
      message.mutable_undo()->set_document_id(document);
      break;
    case wire::ClientMessage::kRedo:
      message.mutable_redo()->set_document_id(document);
      break;
    default:
      return internalError("line " + std::to_string(c.line) + ": no wire command");
  }
  return message;
}

}  // namespace tessera::client
