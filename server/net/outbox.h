// A client's bounded outgoing queue (docs/ARCHITECTURE.md, "Fan-out"):
// frames are shared between clients (encoded once, document/delta.h), and a client that falls behind never
// grows server memory without bound. Above the soft limit, queued deltas of a document are merged into one
// that keeps only the newest payload per region; above the hard limit (or the message cap) they are dropped,
// and the document is marked for a resync snapshot.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "server/base/config.h"
#include "server/document/delta.h"

namespace tessera::server {

class Outbox {
 public:
  explicit Outbox(const Limits& limits) : limits_(limits) {}

  // Queues a message. Deltas may be merged, or dropped (their documents then
  // appear in takeResyncs()).
  void push(Outgoing message, uint32_t maxFrameBytes);
  bool empty() const { return queue_.empty(); }
  // Takes the frames at the front for one gathered write (at most
  // `maxFrames` and about `maxBytes`): they stay queued, and are never merged
  // or dropped, until finishWrite() after the write completes. One write
  // per burst instead of one per frame is what keeps a server with many
  // subscribers out of the send() syscall.
  std::vector<std::shared_ptr<const std::string>> startWrite(size_t maxFrames, uint64_t maxBytes);
  void finishWrite();
  bool writing() const { return inFlight_ > 0; }

  uint64_t bytes() const { return bytes_; }
  size_t size() const { return queue_.size(); }
  uint64_t merges() const { return merges_; }
  uint64_t drops() const { return drops_; }
  // Documents whose deltas were dropped: each needs a fresh snapshot.
  std::set<uint64_t> takeResyncs();
  // Documents whose presence was dropped: each needs the whole list.
  std::set<uint64_t> takePresenceResyncs();

 private:
  void mergeDeltas(uint32_t maxFrameBytes);
  void dropDeltas();
  void dropPresence();

  const Limits& limits_;
  std::deque<Outgoing> queue_;
  uint64_t bytes_ = 0;
  size_t inFlight_ = 0;  // frames at the front being written
  uint64_t merges_ = 0, drops_ = 0;
  std::set<uint64_t> resyncs_, presenceResyncs_;
};

}  // namespace tessera::server
