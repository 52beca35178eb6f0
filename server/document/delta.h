// Region deltas: what a document sends its subscribers after a change
// (docs/ARCHITECTURE.md, "One edit, end to end", steps 4 and 5). A delta
// names the regions a command changed, each with its payload encoded once
// and shared by every subscriber that holds the same profile, and the
// regions it removed. Its frame is built here, once; a subscriber's queue
// (net/outbox.h) only holds, merges or drops what it is given.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "protocol/tessera.pb.h"

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
  uint64_t surfaceHash = 0;            // the profile's surface at toVersion (PROTOCOL 6.5); 0 = none
  bool viewComplete = false;           // a view's tiles are all held with it (Delta.view_complete)
  uint64_t viewSeq = 0;                // the SetView its tiles follow (Delta.view_seq)
  std::vector<RegionPayload> regions;  // applied in order
  std::vector<uint64_t> removed;
};

// One message for one subscriber, as the document hands it over: a frame
// shared between subscribers, with what a queue needs to merge or drop it.
struct Outgoing {
  std::shared_ptr<const std::string> frame;   // length prefix + payload
  std::shared_ptr<const DeltaContent> delta;  // set for deltas
  uint64_t snapshotOf = 0;                    // set for snapshot parts: deltas never merge across them
  // Set for presence: changes since the last broadcast, or the whole list.
  // Both may be dropped from a client that falls behind, which then gets
  // the whole list again (docs/PROTOCOL.md on presence).
  uint64_t presenceOf = 0;
  bool presenceFull = false;
};

// Snapshot parts stay well under any client's frame limit.
inline constexpr size_t kSnapshotPartBytes = 4u << 20;

// What every part of one snapshot says besides its regions (tessera.proto
// Snapshot): a profile's, or a view-dependent subscription's first picture.
struct SnapshotHeader {
  uint64_t documentId = 0, version = 0;
  const wire::LodProfile& profile;
  bool resync = false;
  uint64_t surfaceHash = 0;  // of every region, all parts applied
};

// The snapshot's frames: its regions (id and shared encoding, in order) in
// parts of at most about `partBytes` each, remaining_parts counting down.
std::vector<std::shared_ptr<const std::string>> encodeSnapshotFrames(
    const SnapshotHeader& header,
    const std::vector<std::pair<uint64_t, std::shared_ptr<const std::string>>>& regions, size_t partBytes,
    uint32_t maxFrameBytes);

// The frame of a delta (also used after merging); null when the delta does
// not fit in `maxFrameBytes`.
std::shared_ptr<const std::string> encodeDeltaFrame(const DeltaContent& delta, uint32_t maxFrameBytes);

}  // namespace tessera::server
