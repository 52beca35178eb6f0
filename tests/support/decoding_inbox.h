// A Subscriber for tests that drive a document stage: it decodes every
// frame queued for it and keeps the messages in order. A test that drives
// the stage on its own thread may read `received` directly; one whose stage
// runs on other threads (a document host on an io_context thread) reads
// through waitFor, count and countOf, which lock.
#pragma once

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

#include "protocol/framing.h"
#include "server/document/subscriber.h"

namespace tessera::testing {

class DecodingInbox final : public server::Subscriber {
 public:
  using Match = std::function<bool(const wire::ServerMessage&)>;

  explicit DecodingInbox(uint64_t session) : session_(session) {}
  uint64_t sessionId() const override { return session_; }
  void send(server::Outgoing message) override {
    FrameDecoder decoder({.maxFrameBytes = 1u << 30});
    wire::ServerMessage m;
    if (!message.frame || !decoder.feed(*message.frame).isOk() || !decoder.next(m).isOk())
      m.mutable_error()->set_message("bad frame");
    std::lock_guard lock(mutex_);
    received.push_back(std::move(m));
    if (note) noted.push_back(note());
    arrived_.notify_all();
  }
  // Acks and Rejects that answer client_seq `seq`.
  int answersTo(uint64_t seq) const {
    std::lock_guard lock(mutex_);
    int n = 0;
    for (const auto& m : received) {
      n += (m.has_ack() && m.ack().client_seq() == seq) || (m.has_reject() && m.reject().client_seq() == seq);
    }
    return n;
  }
  // The index of the first message from index `from` on that `match`
  // accepts, waiting for it up to `seconds`; -1 if none came.
  int waitFor(const Match& match, double seconds, size_t from = 0) {
    std::unique_lock lock(mutex_);
    int found = -1;
    arrived_.wait_for(lock, std::chrono::duration<double>(seconds), [&] {
      for (size_t i = from; i < received.size(); ++i) {
        if (match(received[i])) return found = static_cast<int>(i), true;
      }
      return false;
    });
    return found;
  }
  size_t count() const {
    std::lock_guard lock(mutex_);
    return received.size();
  }
  size_t countOf(const Match& match) const {
    std::lock_guard lock(mutex_);
    return static_cast<size_t>(std::count_if(received.begin(), received.end(), match));
  }

  std::vector<wire::ServerMessage> received;
  // If set, called as each message is queued, and its value kept in
  // `noted` beside it: what the sender's state was at that moment.
  std::function<int64_t()> note;
  std::vector<int64_t> noted;

 private:
  const uint64_t session_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
};

}  // namespace tessera::testing
