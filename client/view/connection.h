// Connection: tessera-view's link to the server, its session I/O. It
// connects, opens the document and subscribes with the LOD profile, then a
// background thread owns the Session: it sends queued commands, receives
// snapshots, deltas, replies and presence and hands each to what keeps it
// (docs/VIEWER.md, "Look", last paragraph): it keeps a DocumentView current
// (resubscribing after a gap) and publishes immutable region meshes for the
// render thread. When the connection is lost it connects, opens and
// subscribes again, with backoff. Beside it, as in client/web's
// DocumentSession: the undo steps of this viewer's edits (undo_history.h),
// the edit-to-delta latency (latency_tracker.h), the collaborators from
// Presence (collaborators.h), the pacing of what it sends (pacer.h) and, on
// a 2D morph document, the sessions that follow its keys
// (morph_key_follower.h).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "client/view/coarse_morph.h"
#include "client/view/collaborators.h"
#include "client/view/latency_tracker.h"
#include "client/view/morph_key_follower.h"
#include "client/view/pacer.h"
#include "client/view/undo_history.h"
#include "client/view/view_options.h"
#include "core/view/view.h"

namespace tessera::view {

struct ControlCage;  // control_cage.h

// Region id -> decoded mesh. A changed region gets a new pointer, so the
// renderer re-uploads exactly the regions whose pointer changed.
using RegionMap = std::map<uint64_t, std::shared_ptr<const RegionMesh>>;

struct ConnectionStats {
  bool connected = true;
  bool ready = false;  // a snapshot has arrived
  uint64_t sessionId = 0;
  uint64_t version = 0;
  uint64_t bytesReceived = 0;  // region bytes
  // Regions received in each codec (--codec; their header's, as decoded),
  // since the latest connection: which codec the server sent.
  uint64_t dracoRegions = 0, meshoptRegions = 0;
  uint64_t gaps = 0;
  uint64_t snapshots = 0, deltas = 0;
  uint64_t coarseFrames = 0;   // morph frames refined here from control points (coarse_morph.h)
  bool coarseShown = false;    // the surface shown is one of them
  uint64_t regionUpdates = 0;  // bumps whenever the published regions change
  double lastLatencyMs = -1;   // edit to delta (latency_tracker.h); -1 before the first
  double maxLatencyMs = 0;
  uint64_t latencySamples = 0;
  uint64_t reconnects = 0;  // after a lost connection: connect, open, subscribe again
  uint64_t editsSent = 0, editsRejected = 0;
  // Edits queued, unanswered, or acked without their delta yet.
  uint64_t editsPending = 0;
  std::string lastError;  // the latest Reject or Error, or why undo waits, for the HUD
  // DocumentView::surfaceHash() after the latest snapshot or delta; only
  // with ViewOptions::hashSurfaces (a pass over every region per delta).
  uint64_t surfaceHash = 0;
  // A view-dependent subscription: its tiles are all here (Delta.view_complete)
  // for the latest camera sent (Delta.view_seq names its SetView).
  bool viewComplete = false;
};

class Connection {
 public:
  // Blocking: connect, open, subscribe (each bounded by options.timeoutSeconds).
  static Expected<std::unique_ptr<Connection>> open(const ViewOptions& options);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  uint64_t documentId() const { return document_; }
  RegionMap regions() const;
  ConnectionStats stats() const;
  std::vector<Collaborator> collaborators() const;

  // Undo steps (undo_history.h): a drag opens one and closes it on release.
  UndoHistory::StepId openStep();
  void closeStep(UndoHistory::StepId step);

  // Queued for the network thread. An edit without a step is a step of its own.
  void moveVertex(uint64_t packedVertex, const Vec3& target, UndoHistory::StepId step = 0);
  void setVertexType(uint64_t packedVertex, wire::VertexType type);
  void setInterpolation(uint64_t packedVertex, bool interpolating, double tension);
  // The edge joining two vertices of one level, named by its ends: the
  // server finds it (SetEdgeSharpness.end_vertex_ids).
  void setEdgeSharpness(uint64_t packedA, uint64_t packedB, float sharpness);
  void select(const std::vector<uint64_t>& packedVertices);  // empty clears the selection
  // Undo or redo this viewer's newest step. False, with stats().lastError
  // saying why, when there is none or it is not finished.
  bool undo();
  bool redo();

  // Unsubscribe and subscribe again with another profile.
  void changeProfile(uint32_t baseLevel, uint32_t maxLevel, double angle);

  // A view-dependent subscription (--views): the camera moved. The regions
  // published are then tiles, each with the cracks towards coarser
  // neighbours closed (docs/VIEWS.md "Assembling tiles").
  bool viewDependent() const { return viewDependent_; }
  void setView(const View& view);

  // A morph document (docs/VIEWER.md, "Morph documents"; found out at open,
  // by asking for its control points): its images (empty for a 3D morph)
  // and the time shown.
  bool isMorph() const { return morph_; }
  const std::string& imageFrom() const { return imageFrom_; }
  const std::string& imageTo() const { return imageTo_; }
  // With images: where each displayed vertex is under either key
  // (morph_key_follower.h); null until both keys have their snapshot. A new
  // pointer whenever it changes.
  std::shared_ptr<const KeyPositionMap> keyPositions() const;
  // Subscribes again at time t (LodProfile.morph_t): a snapshot of the
  // surface at t follows.
  void showMorphTime(double t);
  // The coarse stream (coarse_morph.h): asks for the control points at t;
  // the surface refined from them replaces the regions shown until the
  // next snapshot. False when the document sent no usable topology.
  bool canStreamCoarse() const { return coarseBase_.has_value(); }
  void playMorphTime(double t);
  // The key this viewer's edits, undos and redos go to (0 or 1).
  void setEditKey(uint32_t key) { editKey_ = key; }
  uint32_t editKey() const { return editKey_; }

  // The control cage of `level` (control_cage.h): asks the server for the
  // level's faces; cage() holds the latest that arrived, nothing before.
  void requestCage(int level);
  std::shared_ptr<const ControlCage> cage() const;

 private:
  struct Sent {
    std::chrono::steady_clock::time_point at;
    bool edit = false;  // an edit, undo or redo: its Ack names a version
    bool undo = false, redo = false;
    UndoHistory::StepId step = 0;  // edits only
    uint32_t key = 0;              // edits only: the morph key it was sent to
  };
  struct Outgoing {
    wire::ClientMessage message;
    Sent sent;
  };

  Connection(std::unique_ptr<client::Session> session, uint64_t document);
  void run();
  void enqueue(wire::ClientMessage message, Sent kind);
  void enqueueEdit(wire::ClientMessage message, UndoHistory::StepId step);
  // Sends Undo (or Redo) for each of the history's ids, in its order.
  bool step(bool undo);
  // Edits whose answer will never come leave their undo step.
  void forget(const Sent& sent);
  void handle(const wire::ServerMessage& message);
  void publishAll();
  void publishLatency();  // with mutex_ held
  void countPending();    // with mutex_ held
  void lost(const std::string& why);
  // Tries again with backoff until it succeeds (true) or the destructor stops it.
  bool reconnect();

  // A 2D morph's key sessions (network thread only), and what they show.
  std::unique_ptr<MorphKeyFollower> keys_;
  std::shared_ptr<const KeyPositionMap> keyPositions_;  // guarded by mutex_
  // Reads what the key sessions received; republishes keyPositions_.
  void pollKeySessions();

  std::optional<CoarseMorphBase> coarseBase_;  // set at open, read-only after
  bool coarseShown_ = false;                   // network thread only: the regions shown are a coarse frame
  void showCoarse(const wire::MorphControl& frame);

  bool viewDependent_ = false;  // set at open, read-only after
  // Subscribe.codec of every subscription of the shown document (--codec);
  // set at open, read-only after. A 2D morph's key sessions stay Draco.
  wire::RegionCodec codec_ = wire::REGION_CODEC_DRACO;
  std::optional<wire::View> camera_;  // guarded by mutex_: the latest view sent, for resubscribing
  uint64_t cameraSeq_ = 0;            // network thread only: the client_seq of the latest SetView sent
  std::optional<wire::View> cameraNow() const;
  // Publishes every tile with its cracks closed; a tile whose positions did
  // not change keeps its pointer (with mutex_ held).
  void publishClosedTiles();
  bool morph_ = false;  // set at open, read-only after
  std::string imageFrom_, imageTo_;
  std::atomic<uint32_t> editKey_{0};
  std::optional<double> morphT_;  // guarded by mutex_: the time subscribed at, if any
  wire::LodProfile wanted_;       // guarded by mutex_: the profile chosen, without morph_t

  std::unique_ptr<client::Session> session_;  // network thread only
  client::SessionOptions sessionOptions_;
  const uint64_t document_;
  client::DocumentView view_;          // network thread only
  wire::LodProfile profile_;           // network thread only
  std::map<uint64_t, Sent> inFlight_;  // by client_seq; network thread only
  Pacer pacer_{Pacer::Clock::now()};   // network thread only
  LatencyTracker latency_;             // network thread only

  mutable std::mutex mutex_;  // guards everything below
  std::deque<Outgoing> outbox_;
  RegionMap published_;
  std::shared_ptr<const ControlCage> cage_;
  ConnectionStats stats_;
  Collaborators collaborators_;
  UndoHistory history_;

  std::atomic<bool> stop_{false};
  bool hashSurfaces_ = false;
  std::thread thread_;
};

}  // namespace tessera::view
