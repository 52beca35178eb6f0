// A client's bounded outgoing queue (issue §2): frames are shared between
// clients (encoded once), and a client that falls behind never grows server
// memory without bound. Above the soft limit, queued deltas of a document
// are merged into one that keeps only the newest payload per region; above
// the hard limit (or the message cap) they are dropped, and the document is
// marked for a resync snapshot.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "server/config.h"

namespace tessera::server {

// One region's encoding in a delta.
struct RegionPayload {
  uint64_t id = 0;
  std::shared_ptr<const std::string> bytes;
  // Decodes on its own; false for a region that only moved, whose payload
  // leaves out the ids of the layout the receiver holds (region_codec.h).
  bool selfContained = true;
};

// What a delta carries, kept beside its frame so queued deltas can merge.
// A region appears once, or twice when a merge put a moved region's
// payload behind the self-contained one that brought its layout.
struct DeltaContent {
  uint64_t documentId = 0, fromVersion = 0, toVersion = 0, authorSession = 0, editId = 0;
  uint64_t surfaceHash = 0;  // the profile's surface at toVersion (PROTOCOL 6.5); 0 = none
  std::vector<RegionPayload> regions;  // applied in order
  std::vector<uint64_t> removed;
};

struct Outgoing {
  std::shared_ptr<const std::string> frame;   // length prefix + payload
  std::shared_ptr<const DeltaContent> delta;  // set for deltas
  uint64_t snapshotOf = 0;                    // set for snapshot parts: deltas never merge across them
  // Set for presence: changes since the last broadcast, or the whole list.
  // Both may be dropped from a client that falls behind, which then gets
  // the whole list again (issue 13 §3).
  uint64_t presenceOf = 0;
  bool presenceFull = false;
};

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

// The frame of a delta (also used after merging).
std::shared_ptr<const std::string> encodeDeltaFrame(const DeltaContent& delta, uint32_t maxFrameBytes);

}  // namespace tessera::server
