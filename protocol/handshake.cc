#include "protocol/handshake.h"

#include "core/util/hex.h"

namespace tessera {

namespace {

// The oneof member's field name ("move_vertex"), for messages about a frame
// that arrived where another was expected.
template <typename Envelope>
std::string caseName(int fieldNumber) {
  if (fieldNumber == 0) return "an envelope with nothing set";
  const auto* field = Envelope::descriptor()->FindFieldByNumber(fieldNumber);
  return field ? field->name() : "unknown field " + std::to_string(fieldNumber);
}

// Names show up in other people's presence lists and in log lines, so
// control characters (newlines, escape sequences) are refused.
Status checkText(const std::string& text, const char* field, size_t maxBytes) {
  if (text.size() > maxBytes) {
    return invalidArgument(std::string("Hello.") + field + " is " + std::to_string(text.size()) +
                           " bytes, more than the limit of " + std::to_string(maxBytes));
  }
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      return invalidArgument(std::string("Hello.") + field + " contains control character " +
                             hexNumber(c, 2) + " at byte " + std::to_string(i));
    }
  }
  return Status::ok();
}

}  // namespace

wire::ClientMessage makeHello(const HelloOptions& options) {
  wire::ClientMessage message;
  message.set_client_seq(options.clientSeq);
  wire::Hello* hello = message.mutable_hello();
  hello->set_protocol_version(options.protocolVersion);
  hello->set_client_name(options.clientName);
  hello->set_token(options.token);
  return message;
}

wire::ServerMessage makeHelloAck(const HelloAckOptions& options) {
  wire::ServerMessage message;
  wire::HelloAck* ack = message.mutable_hello_ack();
  ack->set_client_seq(options.clientSeq);
  ack->set_protocol_version(kProtocolVersion);
  ack->set_server_version(options.serverVersion);
  ack->set_session_id(options.sessionId);
  ack->set_role(options.role);
  ack->set_max_frame_bytes(options.maxFrameBytes);
  return message;
}

Status checkHello(const wire::Hello& hello, uint32_t serverVersion) {
  if (hello.protocol_version() == 0) {
    return unsupported("the Hello carries no protocol_version; server speaks protocol " +
                       std::to_string(serverVersion));
  }
  if (hello.protocol_version() != serverVersion) {
    return unsupported("client speaks protocol " + std::to_string(hello.protocol_version()) +
                       ", server speaks " + std::to_string(serverVersion));
  }
  // The token is only measured: its characters are the auth layer's business,
  // and it must never end up in a message or a log.
  if (hello.token().size() > kMaxTokenBytes) {
    return invalidArgument("Hello.token is " + std::to_string(hello.token().size()) +
                           " bytes, more than the limit of " + std::to_string(kMaxTokenBytes));
  }
  return checkText(hello.client_name(), "client_name", kMaxClientNameBytes);
}

Status checkHandshake(const wire::ClientMessage& first, uint32_t serverVersion) {
  if (!first.has_hello()) {
    return invalidArgument("the first frame must be a Hello, got " +
                           caseName<wire::ClientMessage>(first.command_case()));
  }
  return checkHello(first.hello(), serverVersion);
}

wire::ServerMessage makeHandshakeError(const Status& status) {
  wire::ServerMessage message;
  wire::Error* error = message.mutable_error();
  error->set_code(status.code() == ErrorCode::kUnsupported ? wire::ERROR_CODE_VERSION_MISMATCH
                                                           : wire::ERROR_CODE_BAD_HANDSHAKE);
  error->set_message(status.message());
  error->set_fatal(true);
  return message;
}

Status checkHelloAck(const wire::ServerMessage& first, uint32_t clientVersion) {
  if (first.has_error()) {
    const wire::Error& error = first.error();
    // A newer server may send a code this client does not know by name.
    std::string code = wire::ErrorCode_Name(error.code());
    if (code.empty()) code = "error code " + std::to_string(error.code());
    const std::string text = "server refused the handshake (" + code + "): " + error.message();
    return error.code() == wire::ERROR_CODE_VERSION_MISMATCH ? unsupported(text) : invalidArgument(text);
  }
  if (!first.has_hello_ack()) {
    return invalidArgument("the server's first frame must be a HelloAck, got " +
                           caseName<wire::ServerMessage>(first.body_case()));
  }
  const uint32_t serverVersion = first.hello_ack().protocol_version();
  if (serverVersion != clientVersion) {
    return unsupported("server speaks protocol " + std::to_string(serverVersion) + ", client speaks " +
                       std::to_string(clientVersion));
  }
  return Status::ok();
}

}  // namespace tessera
