#include "server/net/outbox.h"

#include <algorithm>
#include <map>

#include "protocol/framing.h"
#include "protocol/tessera.pb.h"

namespace tessera::server {

void Outbox::push(Outgoing message, uint32_t maxFrameBytes) {
  if (message.delta && resyncs_.count(message.delta->documentId)) {
    ++drops_;  // a snapshot is coming that already holds it
    return;
  }
  if (message.presenceOf != 0 && !message.presenceFull && presenceResyncs_.count(message.presenceOf)) {
    ++drops_;  // the whole list is coming
    return;
  }
  bytes_ += message.frame->size();
  queue_.push_back(std::move(message));
  if (bytes_ > limits_.queueSoftBytes || queue_.size() > limits_.queueMaxMessages) {
    dropPresence();
    mergeDeltas(maxFrameBytes);
  }
  if (bytes_ > limits_.queueHardBytes || queue_.size() > limits_.queueMaxMessages) dropDeltas();
}

std::vector<std::shared_ptr<const std::string>> Outbox::startWrite(size_t maxFrames, uint64_t maxBytes) {
  std::vector<std::shared_ptr<const std::string>> frames;
  uint64_t bytes = 0;
  for (const Outgoing& m : queue_) {
    if (frames.size() == maxFrames || (!frames.empty() && bytes + m.frame->size() > maxBytes)) break;
    frames.push_back(m.frame);
    bytes += m.frame->size();
  }
  inFlight_ = frames.size();
  return frames;
}

void Outbox::finishWrite() {
  for (; inFlight_ > 0; --inFlight_) {
    bytes_ -= queue_.front().frame->size();
    queue_.pop_front();
  }
}

std::set<uint64_t> Outbox::takeResyncs() {
  return std::exchange(resyncs_, {});
}

std::set<uint64_t> Outbox::takePresenceResyncs() {
  return std::exchange(presenceResyncs_, {});
}

// Presence a client has not been sent yet goes first when it falls behind:
// one whole list replaces it once the queue has drained.
void Outbox::dropPresence() {
  std::deque<Outgoing> kept;
  bytes_ = 0;
  for (size_t i = 0; i < queue_.size(); ++i) {
    Outgoing& m = queue_[i];
    if (m.presenceOf != 0 && i >= inFlight_) {
      presenceResyncs_.insert(m.presenceOf);
      ++drops_;
      continue;
    }
    bytes_ += m.frame->size();
    kept.push_back(std::move(m));
  }
  queue_.swap(kept);
}

// Merges every queued delta of a document (except one being written) into
// the position of the first: newest payload per region, removals that
// stand, versions spanning them all.
void Outbox::mergeDeltas(uint32_t maxFrameBytes) {
  std::map<uint64_t, size_t> first;  // document -> index of its first mergeable delta
  std::deque<Outgoing> kept;
  std::map<uint64_t, DeltaContent> merged;
  // Puts a document's merged delta in the place of its group's first.
  auto flush = [&](uint64_t document, DeltaContent& content) {
    auto shared = std::make_shared<const DeltaContent>(std::move(content));
    auto frame = encodeDeltaFrame(*shared, maxFrameBytes);
    if (!frame) {
      resyncs_.insert(document);  // too big to send as one delta
      return;
    }
    kept[first[document]] = {frame, shared, 0};
  };
  const size_t start = inFlight_;
  for (size_t i = 0; i < queue_.size(); ++i) {
    Outgoing& m = queue_[i];
    if (m.snapshotOf != 0) {
      // Deltas after a snapshot start a new group: merging them into one
      // queued before it would apply them to the wrong version.
      if (auto it = merged.find(m.snapshotOf); it != merged.end()) {
        flush(m.snapshotOf, it->second);
        merged.erase(it);
      }
    }
    if (i < start || !m.delta) {
      kept.push_back(std::move(m));
      continue;
    }
    const DeltaContent& d = *m.delta;
    auto [it, fresh] = merged.try_emplace(d.documentId, d);
    if (fresh) {
      first[d.documentId] = kept.size();
      kept.push_back({});  // filled below
      continue;
    }
    DeltaContent& into = it->second;
    ++merges_;
    into.toVersion = d.toVersion;
    into.authorSession = d.authorSession;
    into.editId = d.editId;
    into.surfaceHash = d.surfaceHash;  // the state at the new toVersion
    into.viewComplete = d.viewComplete;
    into.viewSeq = d.viewSeq;
    for (const RegionPayload& payload : d.regions) {
      const auto same = [&](const RegionPayload& e) { return e.id == payload.id; };
      if (payload.selfContained) {
        // The newest self-contained payload replaces everything before it.
        into.regions.erase(std::remove_if(into.regions.begin(), into.regions.end(), same),
                           into.regions.end());
        into.regions.push_back(payload);
      } else {
        // A moved region needs its layout's ids: it replaces an earlier
        // move, but goes behind the payload that brought the layout.
        auto last = std::find_if(into.regions.rbegin(), into.regions.rend(), same);
        if (last != into.regions.rend() && !last->selfContained) {
          *last = payload;
        } else {
          into.regions.push_back(payload);
        }
      }
      into.removed.erase(std::remove(into.removed.begin(), into.removed.end(), payload.id),
                         into.removed.end());
    }
    for (uint64_t id : d.removed) {
      into.regions.erase(std::remove_if(into.regions.begin(), into.regions.end(),
                                        [&](const RegionPayload& e) { return e.id == id; }),
                         into.regions.end());
      if (std::find(into.removed.begin(), into.removed.end(), id) == into.removed.end())
        into.removed.push_back(id);
    }
  }
  bytes_ = 0;
  for (auto& [document, content] : merged) flush(document, content);
  queue_.clear();
  for (Outgoing& m : kept) {
    if (!m.frame) continue;
    bytes_ += m.frame->size();
    queue_.push_back(std::move(m));
  }
}

void Outbox::dropDeltas() {
  std::deque<Outgoing> kept;
  bytes_ = 0;
  for (size_t i = 0; i < queue_.size(); ++i) {
    Outgoing& m = queue_[i];
    if (m.delta && i >= inFlight_) {
      resyncs_.insert(m.delta->documentId);
      ++drops_;
      continue;
    }
    bytes_ += m.frame->size();
    kept.push_back(std::move(m));
  }
  queue_.swap(kept);
}

}  // namespace tessera::server
