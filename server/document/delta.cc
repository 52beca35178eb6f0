#include "server/document/delta.h"

#include "protocol/framing.h"
#include "protocol/tessera.pb.h"
#include "server/document/replies.h"

namespace tessera::server {

std::vector<std::shared_ptr<const std::string>> encodeSnapshotFrames(
    const SnapshotHeader& header,
    const std::vector<std::pair<uint64_t, std::shared_ptr<const std::string>>>& regions, size_t partBytes,
    uint32_t maxFrameBytes) {
  std::vector<std::vector<size_t>> parts(1);
  size_t bytes = 0;
  for (size_t i = 0; i < regions.size(); ++i) {
    if (bytes > 0 && bytes + regions[i].second->size() > partBytes) parts.emplace_back(), bytes = 0;
    parts.back().push_back(i);
    bytes += regions[i].second->size() + 16;
  }
  std::vector<std::shared_ptr<const std::string>> frames;
  for (size_t p = 0; p < parts.size(); ++p) {
    wire::ServerMessage m;
    wire::Snapshot* s = m.mutable_snapshot();
    s->set_document_id(header.documentId);
    s->set_version(header.version);
    *s->mutable_profile() = header.profile;
    s->set_remaining_parts(static_cast<uint32_t>(parts.size() - p - 1));
    s->set_resync(header.resync);
    s->set_surface_hash(header.surfaceHash);
    for (size_t i : parts[p]) {
      wire::Region* r = s->add_regions();
      r->set_region_id(regions[i].first);
      r->set_draco(*regions[i].second);
    }
    frames.push_back(frameOf(m, maxFrameBytes));
  }
  return frames;
}

std::shared_ptr<const std::string> encodeDeltaFrame(const DeltaContent& delta, uint32_t maxFrameBytes) {
  wire::ServerMessage message;
  wire::Delta* d = message.mutable_delta();
  d->set_document_id(delta.documentId);
  d->set_from_version(delta.fromVersion);
  d->set_to_version(delta.toVersion);
  d->set_author_session_id(delta.authorSession);
  d->set_edit_id(delta.editId);
  d->set_surface_hash(delta.surfaceHash);
  d->set_view_complete(delta.viewComplete);
  d->set_view_seq(delta.viewSeq);
  for (const RegionPayload& payload : delta.regions) {
    wire::Region* r = d->add_regions();
    r->set_region_id(payload.id);
    r->set_draco(*payload.bytes);
  }
  for (uint64_t id : delta.removed) d->add_removed_region_ids(id);
  auto frame = encodeFrame(message, maxFrameBytes);
  return frame.isOk() ? std::make_shared<const std::string>(std::move(*frame)) : nullptr;
}

}  // namespace tessera::server
