#include "server/document/delta.h"

#include "protocol/framing.h"
#include "protocol/tessera.pb.h"

namespace tessera::server {

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
