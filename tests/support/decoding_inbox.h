// A Subscriber for tests that drive a document stage on their own thread:
// it decodes every frame queued for it and keeps the messages in order.
#pragma once

#include <cstdint>
#include <vector>

#include "protocol/framing.h"
#include "server/document/subscriber.h"

namespace tessera::testing {

class DecodingInbox final : public server::Subscriber {
 public:
  explicit DecodingInbox(uint64_t session) : session_(session) {}
  uint64_t sessionId() const override { return session_; }
  void send(server::Outgoing message) override {
    FrameDecoder decoder({.maxFrameBytes = 1u << 30});
    wire::ServerMessage m;
    if (!message.frame || !decoder.feed(*message.frame).isOk() || !decoder.next(m).isOk())
      m.mutable_error()->set_message("bad frame");
    received.push_back(std::move(m));
  }
  // Acks and Rejects that answer client_seq `seq`.
  int answersTo(uint64_t seq) const {
    int n = 0;
    for (const auto& m : received) {
      n += (m.has_ack() && m.ack().client_seq() == seq) || (m.has_reject() && m.reject().client_seq() == seq);
    }
    return n;
  }
  std::vector<wire::ServerMessage> received;

 private:
  const uint64_t session_;
};

}  // namespace tessera::testing
