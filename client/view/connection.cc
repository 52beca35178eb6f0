#include "client/view/connection.h"

#include "client/view/control_cage.h"

#include <algorithm>
#include <cstdio>

#include "client/lib/view_wire.h"
#include "protocol/commands.h"
#include "protocol/morph_key.h"

namespace tessera::view {

namespace {

using Clock = std::chrono::steady_clock;

Status expectAck(const Expected<wire::ServerMessage>& reply, const std::string& what) {
  if (!reply.isOk()) return reply.status().withContext(what);
  if (reply->has_reject()) {
    return invalidArgument(what + ": " + wire::RejectReason_Name(reply->reject().reason()) + ": " +
                           reply->reject().message());
  }
  if (!reply->has_ack())
    return internalError(what + ": the server answered with something other than an Ack");
  return Status::ok();
}

// With a camera, a view-dependent subscription (the profile then serves
// only its triangle budget). Views are Draco only (checkCodec), so a
// camera goes with the default codec.
wire::ClientMessage subscribeMessage(uint64_t document, const wire::LodProfile& profile,
                                     wire::RegionCodec codec = wire::REGION_CODEC_DRACO,
                                     const std::optional<wire::View>& camera = std::nullopt) {
  wire::ClientMessage m;
  m.mutable_subscribe()->set_document_id(document);
  *m.mutable_subscribe()->mutable_profile() = profile;
  m.mutable_subscribe()->set_codec(codec);
  if (camera) *m.mutable_subscribe()->mutable_view() = *camera;
  return m;
}

wire::RegionCodec wireCodec(RegionCodec codec) {
  return codec == RegionCodec::kMeshopt ? wire::REGION_CODEC_MESHOPT : wire::REGION_CODEC_DRACO;
}

// Before the model is framed: a camera far down +Z at the coarsest
// tolerance. The first snapshot is the coarsest tiles whatever the camera;
// the viewer frames them and sends its own.
View placeholderView() {
  View v;
  v.eye = Vec3(0, 0, 1e3);
  v.forward = Vec3(0, 0, -1);
  v.width = 800;
  v.height = 600;
  v.tolerancePixels = kMaxTolerancePixels;
  return v;
}

// Connect, open the document and subscribe with `profile` in `codec` (and `camera`).
Expected<std::unique_ptr<client::Session>> establish(const client::SessionOptions& s, uint64_t document,
                                                     const wire::LodProfile& profile,
                                                     wire::RegionCodec codec = wire::REGION_CODEC_DRACO,
                                                     const std::optional<wire::View>& camera = std::nullopt) {
  TESSERA_ASSIGN_OR_RETURN(std::unique_ptr<client::Session> session, client::Session::connect(s));
  wire::ClientMessage open;
  open.mutable_open_document()->set_document_id(document);
  TESSERA_RETURN_IF_ERROR(
      expectAck(session->call(open, s.timeoutSeconds), "open document " + std::to_string(document)));
  TESSERA_RETURN_IF_ERROR(
      expectAck(session->call(subscribeMessage(document, profile, codec, camera), s.timeoutSeconds),
                "subscribe to document " + std::to_string(document)));
  return session;
}

}  // namespace

Expected<std::unique_ptr<Connection>> Connection::open(const ViewOptions& options) {
  TESSERA_RETURN_IF_ERROR(checkCodec(options));
  const wire::RegionCodec codec = wireCodec(options.codec);
  client::SessionOptions s;
  s.host = options.host;
  s.port = options.port;
  s.name = options.name;
  s.token = options.token;
  s.timeoutSeconds = options.timeoutSeconds;
  wire::LodProfile profile;
  profile.set_base_level(options.baseLevel);
  profile.set_max_level(options.maxLevel);
  profile.set_angle_threshold_degrees(options.angle);
  if (options.morphT) profile.set_morph_t(*options.morphT);
  std::optional<wire::View> camera;
  if (options.views) {
    View first = placeholderView();
    first.tolerancePixels = std::max(first.tolerancePixels, options.tolerancePixels);
    camera = client::viewToWire(first);
  }
  auto established = establish(s, options.document, profile, codec, camera);
  if (!established.isOk() && camera) {
    // A view the server refuses is answered by showing the profile; the
    // reason is said.
    std::fprintf(stderr, "tessera-view: %s; showing the LOD profile instead\n",
                 established.status().message().c_str());
    camera.reset();
    established = establish(s, options.document, profile, codec);
  }
  if (!established.isOk()) return established.status();
  std::unique_ptr<client::Session> session = std::move(*established);
  // Whether the document is a morph: only a morph document answers with
  // its control points (and its images, which come once, here).
  wire::ClientMessage probe;
  probe.mutable_get_morph_control()->set_document_id(options.document);
  probe.mutable_get_morph_control()->set_with_topology(true);
  auto control = session->call(probe, s.timeoutSeconds);
  std::unique_ptr<Connection> c(new Connection(std::move(session), options.document));
  if (control.isOk() && control->has_morph_control()) {
    c->morph_ = true;
    c->imageFrom_ = control->morph_control().image_from();
    c->imageTo_ = control->morph_control().image_to();
    auto base = coarseMorphBase(control->morph_control());
    if (base.isOk()) c->coarseBase_ = std::move(*base);
  }
  // A morph's time is a field of the profile (PROTOCOL.md section 14): a
  // morph document is shown with the profile, whatever the command line.
  const bool views = camera.has_value() && !c->morph_;
  if (camera && c->morph_ && c->imageFrom_.empty()) {
    TESSERA_RETURN_IF_ERROR(
        expectAck(c->session_->call(subscribeMessage(options.document, profile, codec), s.timeoutSeconds),
                  "subscribe to document " + std::to_string(options.document)));
    camera.reset();
  }
  if (!c->imageFrom_.empty()) {
    // A 2D morph is shown uniformly at the max level, so that every frame
    // has the same vertices as the key views (their ids find their
    // texture coordinates); two more sessions follow the keys.
    profile.set_base_level(options.maxLevel);
    TESSERA_RETURN_IF_ERROR(
        expectAck(c->session_->call(subscribeMessage(options.document, profile, codec), s.timeoutSeconds),
                  "subscribe to document " + std::to_string(options.document)));
    std::array<std::unique_ptr<client::Session>, 2> keySessions;
    for (int k = 0; k < 2; ++k) {
      client::SessionOptions keyOptions = s;
      keyOptions.name = s.name + " (key " + std::to_string(k) + ")";
      TESSERA_ASSIGN_OR_RETURN(keySessions[k], establish(keyOptions, options.document,
                                                         MorphKeyFollower::profileAtKey(profile, k)));
    }
    c->keys_ = std::make_unique<MorphKeyFollower>(options.document, std::move(keySessions));
  }
  c->viewDependent_ = views;
  c->codec_ = codec;
  c->camera_ = views ? camera : std::nullopt;
  c->morphT_ = options.morphT;
  c->wanted_ = profile;
  c->wanted_.clear_morph_t();
  c->sessionOptions_ = s;
  c->profile_ = profile;
  c->hashSurfaces_ = options.hashSurfaces;
  c->thread_ = std::thread([raw = c.get()] { raw->run(); });
  return c;
}

Connection::Connection(std::unique_ptr<client::Session> session, uint64_t document)
    : session_(std::move(session)), document_(document), view_(document) {
  stats_.sessionId = session_->sessionId();
}

void Connection::lost(const std::string& why) {
  session_->close();
  std::lock_guard lock(mutex_);
  stats_.connected = false;
  stats_.lastError = why;
}

bool Connection::reconnect() {
  // The wait doubles from 0.1 s up to 5 s; each attempt is bounded too, so
  // the destructor never waits long for this thread.
  client::SessionOptions s = sessionOptions_;
  s.timeoutSeconds = std::min(s.timeoutSeconds, 5.0);
  double delay = 0.1;
  while (!stop_) {
    const auto until = Clock::now() + std::chrono::duration<double>(delay);
    while (!stop_ && Clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (stop_) return false;
    auto session = establish(s, document_, profile_, codec_, cameraNow());
    if (session.isOk()) {
      session_ = std::move(*session);
      view_ = client::DocumentView(document_);
      cameraSeq_ = 0;  // the new subscription carries the latest camera
      for (const auto& [seq, sent] : inFlight_) forget(sent);
      inFlight_.clear();
      latency_.reset();
      std::lock_guard lock(mutex_);
      stats_.connected = true;
      stats_.ready = false;
      stats_.sessionId = session_->sessionId();
      ++stats_.reconnects;
      return true;
    }
    {
      std::lock_guard lock(mutex_);
      stats_.lastError = "reconnecting: " + session.status().message();
    }
    delay = std::min(delay * 2, 5.0);
  }
  return false;
}

Connection::~Connection() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  session_->close();
}

RegionMap Connection::regions() const {
  std::lock_guard lock(mutex_);
  return published_;
}

ConnectionStats Connection::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::vector<Collaborator> Connection::collaborators() const {
  std::lock_guard lock(mutex_);
  return collaborators_.list();
}

void Connection::enqueue(wire::ClientMessage message, Sent kind) {
  std::lock_guard lock(mutex_);
  if (kind.edit) ++stats_.editsPending;
  outbox_.push_back({std::move(message), kind});
}

void Connection::enqueueEdit(wire::ClientMessage message, UndoHistory::StepId step) {
  std::lock_guard lock(mutex_);
  const bool own = step == 0;
  if (own) step = history_.open();
  history_.sent(step);
  if (own) history_.close(step);
  ++stats_.editsPending;
  outbox_.push_back({std::move(message),
                     {.at = {}, .edit = true, .undo = false, .redo = false, .step = step, .key = editKey_}});
}

void Connection::forget(const Sent& sent) {
  if (sent.step == 0) return;
  std::lock_guard lock(mutex_);
  history_.dropped(sent.step);
}

UndoHistory::StepId Connection::openStep() {
  std::lock_guard lock(mutex_);
  return history_.open();
}

void Connection::closeStep(UndoHistory::StepId step) {
  std::lock_guard lock(mutex_);
  history_.close(step);
}

void Connection::countPending() {
  uint64_t queued = 0;
  for (const Outgoing& o : outbox_) queued += o.sent.edit ? 1 : 0;
  stats_.editsPending = queued + inFlight_.size() + latency_.awaitingDelta();
}

void Connection::publishLatency() {
  const LatencyTracker::Summary& l = latency_.summary();
  stats_.lastLatencyMs = l.lastMs;
  stats_.maxLatencyMs = l.maxMs;
  stats_.latencySamples = l.samples;
}

void Connection::moveVertex(uint64_t packedVertex, const Vec3& target, UndoHistory::StepId step) {
  wire::ClientMessage m;
  auto* move = m.mutable_move_vertex();
  move->set_document_id(document_);
  move->add_vertex_ids(packedVertex);
  move->mutable_target()->set_x(target[0]);
  move->mutable_target()->set_y(target[1]);
  move->mutable_target()->set_z(target[2]);
  move->set_mode(wire::MOVE_MODE_DIRECT_MANIPULATION);
  setMorphKey(m, editKey_);
  enqueueEdit(std::move(m), step);
}

void Connection::setVertexType(uint64_t packedVertex, wire::VertexType type) {
  wire::ClientMessage m;
  m.mutable_set_vertex_type()->set_document_id(document_);
  m.mutable_set_vertex_type()->set_vertex_id(packedVertex);
  m.mutable_set_vertex_type()->set_type(type);
  setMorphKey(m, editKey_);
  enqueueEdit(std::move(m), 0);
}

void Connection::setInterpolation(uint64_t packedVertex, bool interpolating, double tension) {
  wire::ClientMessage m;
  auto* t = m.mutable_set_interpolation();
  t->set_document_id(document_);
  t->set_vertex_id(packedVertex);
  t->set_interpolating(interpolating);
  t->set_tension(tension);
  setMorphKey(m, editKey_);
  enqueueEdit(std::move(m), 0);
}

void Connection::setEdgeSharpness(uint64_t packedA, uint64_t packedB, float sharpness) {
  wire::ClientMessage m;
  auto* e = m.mutable_set_edge_sharpness();
  e->set_document_id(document_);
  e->set_edge_id(kEdgeIdNamedByEnds);
  e->add_end_vertex_ids(packedA);
  e->add_end_vertex_ids(packedB);
  e->set_sharpness(sharpness);
  setMorphKey(m, editKey_);
  enqueueEdit(std::move(m), 0);
}

void Connection::select(const std::vector<uint64_t>& packedVertices) {
  wire::ClientMessage m;
  m.mutable_select()->set_document_id(document_);
  for (uint64_t id : packedVertices) m.mutable_select()->mutable_selection()->add_vertex_ids(id);
  enqueue(std::move(m), {});
}

bool Connection::undo() {
  return step(true);
}
bool Connection::redo() {
  return step(false);
}

bool Connection::step(bool undo) {
  std::vector<uint64_t> ids;
  {
    std::lock_guard lock(mutex_);
    auto planned = undo ? history_.undo() : history_.redo();
    if (!planned.isOk()) {
      stats_.lastError = planned.status().message();
      return false;
    }
    ids = std::move(*planned);
  }
  for (uint64_t keyed : ids) {
    const KeyedEdit edit = splitKeyedEditId(keyed);
    wire::ClientMessage m;
    if (undo) {
      m.mutable_undo()->set_document_id(document_);
      m.mutable_undo()->set_edit_id(edit.editId);
      m.mutable_undo()->set_key(edit.key);
    } else {
      m.mutable_redo()->set_document_id(document_);
      m.mutable_redo()->set_edit_id(edit.editId);
      m.mutable_redo()->set_key(edit.key);
    }
    enqueue(std::move(m), {.at = {}, .edit = true, .undo = undo, .redo = !undo});
  }
  return true;
}

void Connection::changeProfile(uint32_t baseLevel, uint32_t maxLevel, double angle) {
  wire::ClientMessage un;
  un.mutable_unsubscribe()->set_document_id(document_);
  enqueue(std::move(un), {});
  wire::LodProfile p;
  p.set_base_level(baseLevel);
  p.set_max_level(maxLevel);
  p.set_angle_threshold_degrees(angle);
  {
    std::lock_guard lock(mutex_);
    wanted_ = p;
    if (morphT_) p.set_morph_t(*morphT_);
  }
  enqueue(subscribeMessage(document_, p, codec_), {});
}

void Connection::showMorphTime(double t) {
  wire::LodProfile p;
  {
    std::lock_guard lock(mutex_);
    morphT_ = t;
    p = wanted_;
  }
  p.set_morph_t(t);
  enqueue(subscribeMessage(document_, p, codec_), {});
}

void Connection::playMorphTime(double t) {
  wire::ClientMessage m;
  m.mutable_get_morph_control()->set_document_id(document_);
  m.mutable_get_morph_control()->set_t(t);
  enqueue(std::move(m), {});
}

void Connection::requestCage(int level) {
  wire::ClientMessage m;
  m.mutable_get_cage()->set_document_id(document_);
  m.mutable_get_cage()->set_level(static_cast<uint32_t>(std::max(level, 0)));
  enqueue(std::move(m), {});
}

std::shared_ptr<const ControlCage> Connection::cage() const {
  std::lock_guard lock(mutex_);
  return cage_;
}

void Connection::showCoarse(const wire::MorphControl& frame) {
  if (!coarseBase_) return;
  auto mesh = refineCoarseMorph(*coarseBase_, frame, static_cast<int>(profile_.max_level()));
  std::lock_guard lock(mutex_);
  if (!mesh.isOk()) {
    stats_.lastError = mesh.status().message();
    return;
  }
  // One region with an id no server region has (a face id's level bits
  // are at most 63 >> 58 = 63; this is all ones).
  published_.clear();
  published_[~uint64_t{0}] = std::make_shared<const RegionMesh>(std::move(*mesh));
  coarseShown_ = true;
  stats_.coarseShown = true;
  ++stats_.coarseFrames;
  ++stats_.regionUpdates;
}

void Connection::run() {
  while (!stop_) {
    std::deque<Outgoing> out;
    {
      pacer_.refill(Clock::now());
      std::lock_guard lock(mutex_);
      while (!outbox_.empty() && pacer_.take()) {
        out.push_back(std::move(outbox_.front()));
        outbox_.pop_front();
      }
    }
    for (auto it = out.begin(); it != out.end(); ++it) {
      Outgoing& o = *it;
      if (o.message.has_subscribe()) profile_ = o.message.subscribe().profile();
      const bool isView = o.message.has_set_view();
      auto seq = session_->send(std::move(o.message));
      if (seq.isOk() && isView) cameraSeq_ = *seq;
      if (!seq.isOk()) {
        lost(seq.status().message());
        for (; it != out.end(); ++it) forget(it->sent);  // dropped with the connection
        break;
      }
      o.sent.at = Clock::now();
      if (o.sent.edit) inFlight_[*seq] = o.sent;
    }
    if (!stats().connected) {
      // Commands not sent yet are dropped with the connection.
      if (!reconnect()) return;
      continue;
    }
    if (!out.empty()) {
      std::lock_guard lock(mutex_);
      for (const Outgoing& o : out) stats_.editsSent += o.sent.edit ? 1 : 0;
      countPending();
    }
    pollKeySessions();
    // Short waits keep queued edits from waiting long for the next send.
    auto message = session_->receive(0.005);
    if (!message.isOk()) {
      if (client::isReceiveTimeout(message.status())) continue;
      lost(message.status().message());
      if (!reconnect()) return;
      continue;
    }
    handle(*message);
    std::lock_guard lock(mutex_);
    countPending();
  }
}

void Connection::pollKeySessions() {
  if (!keys_) return;
  MorphKeyFollower::Polled polled = keys_->poll(profile_);
  if (polled.error.empty() && !polled.positions) return;
  std::lock_guard lock(mutex_);
  if (!polled.error.empty()) stats_.lastError = std::move(polled.error);
  if (polled.positions) keyPositions_ = std::move(polled.positions);
}

std::shared_ptr<const KeyPositionMap> Connection::keyPositions() const {
  std::lock_guard lock(mutex_);
  return keyPositions_;
}

std::optional<wire::View> Connection::cameraNow() const {
  std::lock_guard lock(mutex_);
  return camera_;
}

void Connection::setView(const View& view) {
  wire::ClientMessage m = client::setView(document_, view);
  {
    std::lock_guard lock(mutex_);
    camera_ = m.set_view().view();
    stats_.viewComplete = false;  // until a delta names this SetView
  }
  enqueue(std::move(m), {});
}

void Connection::publishClosedTiles() {
  coarseShown_ = false;
  std::map<uint64_t, std::vector<Vec3>> closed = view_.closedTilePositions();
  RegionMap next;
  for (auto& [id, positions] : closed) {
    const RegionMesh& tile = view_.regions().at(id);
    auto held = published_.find(id);
    if (held != published_.end() && held->second->positions == positions &&
        held->second->normals == tile.normals && held->second->vertexIds == tile.vertexIds) {
      next[id] = held->second;  // the same tile, closed the same way: no re-upload
      continue;
    }
    RegionMesh mesh = tile;
    mesh.positions = std::move(positions);
    next[id] = std::make_shared<const RegionMesh>(std::move(mesh));
  }
  published_.swap(next);
  ++stats_.regionUpdates;
}

void Connection::publishAll() {
  coarseShown_ = false;
  RegionMap all;
  for (const auto& [id, mesh] : view_.regions()) all[id] = std::make_shared<const RegionMesh>(mesh);
  std::lock_guard lock(mutex_);
  published_.swap(all);
  ++stats_.regionUpdates;
}

void Connection::handle(const wire::ServerMessage& m) {
  const Clock::time_point now = Clock::now();
  if (m.has_snapshot() || m.has_delta()) {
    const bool wasReady = view_.ready();
    const Status applied = view_.apply(m);
    if (!applied.isOk()) {
      // A gap: ask for a fresh snapshot with the same profile.
      auto resent = session_->send(subscribeMessage(document_, profile_, codec_, cameraNow()));
      cameraSeq_ = 0;  // the new subscription carries the latest camera
      std::lock_guard lock(mutex_);
      stats_.lastError = applied.message();
      if (!resent.isOk()) stats_.connected = false;
    } else if (viewDependent_ &&
               ((m.has_snapshot() && m.snapshot().remaining_parts() == 0 &&
                 m.snapshot().document_id() == document_) ||
                (m.has_delta() && wasReady && view_.ready() && m.delta().document_id() == document_))) {
      // Tiles: the cracks between levels are closed over every tile held.
      if (m.has_delta()) {
        const wire::Delta& d = m.delta();
        latency_.delta(d.from_version(), d.to_version(), d.author_session_id() == session_->sessionId(), now);
      }
      std::lock_guard lock(mutex_);
      if (m.has_delta()) publishLatency();
      publishClosedTiles();
      ++(m.has_snapshot() ? stats_.snapshots : stats_.deltas);
      // Complete for the latest camera sent; a resubscription (gap,
      // reconnect) carries that camera, so its deltas name no SetView.
      stats_.viewComplete = view_.viewComplete() && view_.viewSeq() == cameraSeq_;
    } else if (m.has_snapshot() && m.snapshot().remaining_parts() == 0 &&
               m.snapshot().document_id() == document_) {
      publishAll();
      std::lock_guard lock(mutex_);
      ++stats_.snapshots;
      stats_.coarseShown = false;
    } else if (m.has_delta() && wasReady && view_.ready() && m.delta().document_id() == document_ &&
               !coarseShown_) {
      const wire::Delta& d = m.delta();
      std::map<uint64_t, std::shared_ptr<const RegionMesh>> changed;
      for (const wire::Region& r : d.regions()) {
        auto it = view_.regions().find(r.region_id());
        if (it != view_.regions().end())
          changed[r.region_id()] = std::make_shared<const RegionMesh>(it->second);
      }
      latency_.delta(d.from_version(), d.to_version(), d.author_session_id() == session_->sessionId(), now);
      std::lock_guard lock(mutex_);
      publishLatency();
      for (auto& [id, mesh] : changed) published_[id] = std::move(mesh);
      for (uint64_t id : d.removed_region_ids()) published_.erase(id);
      ++stats_.deltas;
      ++stats_.regionUpdates;
    }
    const uint64_t hash = hashSurfaces_ ? view_.surfaceHash() : 0;
    std::lock_guard lock(mutex_);
    stats_.surfaceHash = hash;
    stats_.ready = view_.ready();
    stats_.version = view_.version();
    stats_.bytesReceived = view_.bytesReceived();
    stats_.dracoRegions = view_.regionsReceived(RegionCodec::kDraco);
    stats_.meshoptRegions = view_.regionsReceived(RegionCodec::kMeshopt);
    stats_.gaps = view_.gaps();
    return;
  }
  if (m.has_morph_control() && m.morph_control().document_id() == document_)
    return showCoarse(m.morph_control());
  if (m.has_cage() && m.cage().document_id() == document_) {
    auto cage = controlCageOf(m.cage());
    std::lock_guard lock(mutex_);
    if (!cage.isOk()) {
      stats_.lastError = cage.status().message();
      return;
    }
    cage_ = std::make_shared<const ControlCage>(std::move(*cage));
    return;
  }
  if (m.has_ack() || m.has_reject()) {
    const uint64_t seq = client::replyTo(m);
    auto it = inFlight_.find(seq);
    if (it == inFlight_.end()) {
      if (m.has_reject()) {
        std::lock_guard lock(mutex_);
        stats_.lastError = wire::RejectReason_Name(m.reject().reason()) + ": " + m.reject().message();
      }
      return;
    }
    const Sent sent = it->second;
    inFlight_.erase(it);
    if (m.has_reject()) {
      forget(sent);
      std::lock_guard lock(mutex_);
      stats_.lastError = wire::RejectReason_Name(m.reject().reason()) + ": " + m.reject().message();
      ++stats_.editsRejected;
      return;
    }
    latency_.acked(m.ack().version(), sent.at, view_.version());
    std::lock_guard lock(mutex_);
    publishLatency();
    if (sent.step != 0 && m.ack().edit_id() != 0)
      history_.acked(sent.step, keyedEditId(m.ack().edit_id(), sent.key));
    return;
  }
  if (m.has_presence() && m.presence().document_id() == document_) {
    std::lock_guard lock(mutex_);
    collaborators_.apply(m.presence(), session_->sessionId());
    return;
  }
  if (m.has_error()) {
    std::lock_guard lock(mutex_);
    stats_.lastError = m.error().message();
    if (m.error().fatal()) stats_.connected = false;
  }
}

}  // namespace tessera::view
