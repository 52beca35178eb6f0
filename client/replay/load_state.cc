#include "client/replay/load_state.h"

#include "client/lib/view_wire.h"
#include "client/replay/load.h"

namespace tessera::replay {

ViewerEvent trackViewerMessage(const wire::ServerMessage& m, Clock::time_point arrival, uint64_t document,
                               ViewerResult& out, Shared& shared) {
  const int64_t bytes = static_cast<int64_t>(m.ByteSizeLong()) + 4;
  if (m.has_snapshot() && m.snapshot().document_id() == document) {
    out.snapshotBytes += bytes;
    if (m.snapshot().resync()) ++shared.resyncs;
    if (m.snapshot().remaining_parts() != 0) return ViewerEvent::kNone;
    out.version = m.snapshot().version();
    if (out.ready) return ViewerEvent::kNone;
    out.ready = true;
    ++shared.viewersReady;
    return ViewerEvent::kReady;
  }
  if (m.has_delta()) {
    const auto& d = m.delta();
    return trackDelta({d.document_id(), d.from_version(), d.to_version(), d.regions_size()}, bytes, arrival,
                      document, out, shared);
  }
  if (m.has_presence()) {
    shared.lastPresenceNs = arrival.time_since_epoch().count();
    out.presenceBytes += bytes;
    ++out.presenceMessages;
    return ViewerEvent::kNone;
  }
  if (m.has_error() && m.error().fatal()) return ViewerEvent::kFatal;
  return ViewerEvent::kNone;
}

ViewerEvent trackDelta(const DeltaHeader& d, int64_t bytes, Clock::time_point arrival, uint64_t document,
                       ViewerResult& out, Shared& shared) {
  if (d.documentId != document) return ViewerEvent::kNone;
  out.deltaBytes += bytes;
  out.regionsReceived += d.regions;
  ++shared.deltas;
  if (!out.ready) return ViewerEvent::kNone;  // waiting for a resync snapshot
  if (d.fromVersion != out.version) {
    ++shared.gaps;
    ++shared.resyncs;
    out.ready = false;
    --shared.viewersReady;
    return ViewerEvent::kGap;
  }
  out.version = d.toVersion;
  if (out.deltaTimes.size() < 1000000)
    out.deltaTimes.push_back({d.fromVersion, d.toVersion, arrival, d.regions});
  return ViewerEvent::kNone;
}

namespace {

double cameraSeconds(const Shared& shared) {
  return std::chrono::duration<double>(Clock::now() - shared.cameraEpoch).count();
}

}  // namespace

wire::ClientMessage subscribeMessage(const LoadOptions& o, int viewer, const Shared& shared) {
  wire::ClientMessage sub;
  if (o.cameras) {
    sub = client::subscribeWithView(o.document, cameraAt(*o.cameras, viewer, cameraSeconds(shared)),
                                    o.profile.triangle_budget());
  } else {
    sub.mutable_subscribe()->set_document_id(o.document);
    *sub.mutable_subscribe()->mutable_profile() = o.profile;
    sub.mutable_subscribe()->set_codec(o.codec);
  }
  return sub;
}

std::optional<wire::ClientMessage> viewIfDue(const LoadOptions& o, int viewer, const Shared& shared,
                                             Clock::time_point& last) {
  if (!o.cameras || o.cameras->viewsPerSecond <= 0) return std::nullopt;
  const auto now = Clock::now();
  if (now - last < std::chrono::duration<double>(1.0 / o.cameras->viewsPerSecond)) return std::nullopt;
  last = now;
  return client::setView(o.document, cameraAt(*o.cameras, viewer, cameraSeconds(shared)));
}

}  // namespace tessera::replay
