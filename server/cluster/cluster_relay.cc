#include "server/cluster/cluster_relay.h"

#include <boost/asio/post.hpp>

#include "core/util/byte_io.h"
#include "protocol/framing.h"
#include "protocol/tessera.pb.h"
#include "server/base/log.h"
#include "server/cluster/message_chunks.h"

namespace tessera::cluster {

std::string nodeSubject(const std::string& node, const char* kind) {
  return "tessera.node." + node + "." + kind;
}

void FrameRelay::send(const std::string& node, uint64_t session, const server::Outgoing& message) {
  if (!message.frame) return;
  std::lock_guard<std::mutex> lock(mutex_);
  auto& queue = pending_[node];
  // The same frame as the last one queued for this node: one more session.
  if (!queue.empty() && queue.back().frame == message.frame) {
    queue.back().message.add_session_ids(session);
  } else {
    Pending p;
    p.frame = message.frame;
    p.message.add_session_ids(session);
    p.message.set_snapshot_of(message.snapshotOf);
    p.message.set_presence_of(message.presenceOf);
    p.message.set_presence_full(message.presenceFull);
    if (message.delta) {
      p.message.set_document_id(message.delta->documentId);
      p.message.set_is_delta(true);
      for (const server::RegionPayload& r : message.delta->regions)
        p.message.add_region_self_contained(r.selfContained);
    }
    queue.push_back(std::move(p));
  }
  if (!flushPosted_) {
    flushPosted_ = true;
    boost::asio::post(executor_, [this] { flush(); });
  }
}

void FrameRelay::flush() {
  std::map<std::string, std::vector<Pending>> batch;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    batch.swap(pending_);
    flushPosted_ = false;
  }
  for (auto& [node, queue] : batch) {
    const std::string subject = nodeSubject(node, "frames");
    for (Pending& p : queue) {
      NodeMessage m;
      *m.mutable_frames() = std::move(p.message);
      m.mutable_frames()->set_frame(*p.frame);
      const std::string bytes = m.SerializeAsString();
      const Status sent = publishMessage(link_, subject, sender_, bytes);
      if (!sent.isOk()) {
        // The node's sessions miss this frame; the version continuity of
        // their deltas makes them ask for a resync (PROTOCOL.md 6.4).
        server::logEvent(
            server::LogLevel::kWarn, "cluster_publish_failed",
            {{"to", node}, {"bytes", static_cast<uint64_t>(bytes.size())}, {"error", sent.message()}});
        continue;
      }
      std::lock_guard<std::mutex> lock(mutex_);
      ++published_;
    }
  }
}

void FrameRelay::publish(const std::string& node, const NodeMessage& message) {
  (void)publishMessage(link_, nodeSubject(node, "frames"), sender_, message.SerializeAsString());
}

uint64_t FrameRelay::framesPublished() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return published_;
}

Expected<server::Outgoing> framesToOutgoing(const Frames& frames, uint32_t maxFrameBytes) {
  const std::string& bytes = frames.frame();
  if (bytes.size() <= kFrameHeaderBytes || bytes.size() - kFrameHeaderBytes > maxFrameBytes) {
    return invalidArgument("a cluster frame of " + std::to_string(bytes.size()) +
                           " bytes is not a frame this node sends");
  }
  const uint32_t announced = getBigEndian32(bytes.data());
  if (announced != bytes.size() - kFrameHeaderBytes) {
    return invalidArgument("a cluster frame announces " + std::to_string(announced) + " bytes but carries " +
                           std::to_string(bytes.size() - kFrameHeaderBytes));
  }
  server::Outgoing out;
  out.frame = std::make_shared<const std::string>(bytes);
  out.snapshotOf = frames.snapshot_of();
  out.presenceOf = frames.presence_of();
  out.presenceFull = frames.presence_full();
  if (!frames.is_delta()) return out;
  wire::ServerMessage message;
  if (!message.ParseFromArray(bytes.data() + kFrameHeaderBytes, static_cast<int>(announced)) ||
      !message.has_delta()) {
    return invalidArgument("a cluster frame marked as a delta does not hold one");
  }
  const wire::Delta& d = message.delta();
  if (d.regions_size() != frames.region_self_contained_size()) {
    return invalidArgument("a cluster delta has " + std::to_string(d.regions_size()) + " regions but " +
                           std::to_string(frames.region_self_contained_size()) + " region flags");
  }
  auto content = std::make_shared<server::DeltaContent>();
  content->documentId = d.document_id();
  content->fromVersion = d.from_version();
  content->toVersion = d.to_version();
  content->authorSession = d.author_session_id();
  content->editId = d.edit_id();
  content->surfaceHash = d.surface_hash();
  for (int i = 0; i < d.regions_size(); ++i) {
    content->regions.push_back(server::RegionPayload{
        d.regions(i).region_id(), std::make_shared<const std::string>(d.regions(i).draco()),
        frames.region_self_contained(i)});
  }
  content->removed.assign(d.removed_region_ids().begin(), d.removed_region_ids().end());
  out.delta = std::move(content);
  return out;
}

}  // namespace tessera::cluster
