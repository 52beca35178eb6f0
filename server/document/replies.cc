#include "server/document/replies.h"

#include "protocol/framing.h"
#include "protocol/utf8_text.h"
#include "server/base/log.h"

namespace tessera::server {

std::shared_ptr<const std::string> frameOf(const wire::ServerMessage& message, uint32_t maxFrameBytes) {
  // The server's own text may quote a client's bytes (a mesh line an
  // importer refused): made valid UTF-8 so that the client can parse it.
  const std::string* text = message.has_reject()  ? &message.reject().message()
                            : message.has_error() ? &message.error().message()
                                                  : nullptr;
  if (text != nullptr && !isValidUtf8(*text)) {
    wire::ServerMessage copy = message;
    if (copy.has_reject()) copy.mutable_reject()->set_message(toValidUtf8(*text));
    if (copy.has_error()) copy.mutable_error()->set_message(toValidUtf8(*text));
    return frameOf(copy, maxFrameBytes);
  }
  auto frame = encodeFrame(message, maxFrameBytes);
  if (!frame.isOk()) {
    logEvent(LogLevel::kError, "frame_encode_failed", {{"error", frame.status().message()}});
    return nullptr;
  }
  return std::make_shared<const std::string>(std::move(*frame));
}

wire::ServerMessage ackFor(uint64_t clientSeq, uint64_t documentId) {
  wire::ServerMessage m;
  m.mutable_ack()->set_client_seq(clientSeq);
  m.mutable_ack()->set_document_id(documentId);
  return m;
}

wire::ServerMessage rejectWith(uint64_t clientSeq, wire::RejectReason reason, const std::string& text) {
  wire::ServerMessage m;
  wire::Reject* r = m.mutable_reject();
  r->set_client_seq(clientSeq);
  r->set_reason(reason);
  r->set_message(text);
  return m;
}

wire::ServerMessage rejectFor(uint64_t clientSeq, const Status& status) {
  return rejectWith(clientSeq, rejectReasonFor(status.code()), status.message());
}

wire::ServerMessage rejectForCommand(uint64_t clientSeq, const wire::ClientMessage& command,
                                     uint32_t failedIndex, const Status& status) {
  wire::ServerMessage reject = rejectFor(clientSeq, status);
  const auto kind = command.has_edit_batch() && failedIndex > 0
                        ? command.edit_batch().commands(static_cast<int>(failedIndex - 1)).command_case()
                        : wire::EditCommand::COMMAND_NOT_SET;
  const bool undoOrRedo = command.command_case() == wire::ClientMessage::kUndo ||
                          command.command_case() == wire::ClientMessage::kRedo ||
                          kind == wire::EditCommand::kUndo || kind == wire::EditCommand::kRedo;
  if (undoOrRedo && status.code() == ErrorCode::kInvalidArgument) {
    reject.mutable_reject()->set_reason(wire::REJECT_REASON_INVALID_STATE);
  }
  reject.mutable_reject()->set_batch_index(failedIndex);
  return reject;
}

std::shared_ptr<const std::string> replyOrReject(uint64_t clientSeq,
                                                 const Expected<wire::ServerMessage>& reply,
                                                 uint32_t maxFrameBytes, const std::string& tooLarge) {
  if (!reply.isOk()) return frameOf(rejectFor(clientSeq, reply.status()), maxFrameBytes);
  if (auto frame = frameOf(*reply, maxFrameBytes)) return frame;
  return frameOf(rejectFor(clientSeq, invalidArgument(tooLarge)), maxFrameBytes);
}

std::shared_ptr<const std::string> limitExceeded(uint64_t clientSeq, const std::string& message,
                                                 uint32_t maxFrameBytes) {
  return frameOf(rejectWith(clientSeq, wire::REJECT_REASON_LIMIT_EXCEEDED, message), maxFrameBytes);
}

wire::RejectReason rejectReasonFor(ErrorCode code) {
  switch (code) {
    case ErrorCode::kInvalidArgument:
      return wire::REJECT_REASON_INVALID_ARGUMENT;
    case ErrorCode::kNotFound:
      return wire::REJECT_REASON_NOT_FOUND;
    case ErrorCode::kInvalidMesh:
    case ErrorCode::kParseError:
      return wire::REJECT_REASON_INVALID_MESH;
    case ErrorCode::kUnsupported:
      return wire::REJECT_REASON_INVALID_ARGUMENT;
    default:
      return wire::REJECT_REASON_INTERNAL;
  }
}

}  // namespace tessera::server
