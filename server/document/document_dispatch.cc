#include "server/document/document_dispatch.h"

namespace tessera::server {

bool isEditCommand(const wire::ClientMessage& message) {
  using C = wire::ClientMessage;
  switch (message.command_case()) {
    case C::kEditBatch:
    case C::kMoveVertex:
    case C::kSetEdgeSharpness:
    case C::kSetVertexType:
    case C::kSetInterpolation:
    case C::kAddMorphKey:
    case C::kUndo:
    case C::kRedo:
      return true;
    default:
      return false;
  }
}

bool dispatchToDocument(DocumentEndpoint& document, const std::shared_ptr<Subscriber>& who,
                        const std::string& authorName, wire::ClientMessage message) {
  using C = wire::ClientMessage;
  const uint64_t seq = message.client_seq();
  if (isEditCommand(message)) {
    document.command(who, authorName, std::move(message));
    return true;
  }
  switch (message.command_case()) {
    case C::kSubscribe:
      document.subscribe(who, message.subscribe(), seq, false);
      return true;
    case C::kSetView:
      document.setView(who, seq, message.set_view().view());
      return true;
    case C::kUnsubscribe:
      document.unsubscribe(who->sessionId());
      return true;
    case C::kSelect:
      document.select(who, seq, message.select().selection());
      return true;
    case C::kExportDocument:
      document.exportGlb(who, seq, message.export_document());
      return true;
    case C::kGetMorphControl:
      document.morphControl(who, seq, message.get_morph_control());
      return true;
    case C::kGetCage:
      document.cage(who, seq, message.get_cage());
      return true;
    default:
      return false;
  }
}

}  // namespace tessera::server
