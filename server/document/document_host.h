// One open document on the server: its single writer. Every
// command runs on the host's strand, on the worker pool, never on network
// threads, so the document has a total order of versions.
//
// An edit is applied, checked against the grid and journaled at once; its
// ack goes out when the journal commit is durable (edits are applied while
// earlier commits are in flight). The views follow in flushes: a flush,
// posted behind the commands already queued and paced by flushInterval(),
// updates every LOD profile's tessellation from the union of the edits'
// changed limits, encodes the changed regions once per profile and sends
// one delta spanning every version since the last flush (or, with
// --deltas-after-durable, queues it until its last edit is durable). Acks
// and recorders' commands always wait for durability. Under light load a
// flush follows each edit; under heavy
// load one covers a burst, so the tessellation, encode and fan-out cost
// follows the delta rate, not the edit rate.
//
// The host keeps the order of things (its serial queue, the flushes and
// their pacing, the presence broadcasts' timer) and composes the stages
// (docs/ARCHITECTURE.md, "One edit, end to end"): command_application.h
// applies, commit_log.h acknowledges once durable, document_views.h keeps
// the views and who watches them (lod_view.h tessellates and encodes one),
// document_presence.h says who is here, document_admission.h judges a
// request's size and picks its lane, bulk_release.h frees memory off the
// interactive workers.
//
// A morph document (docs/PROTOCOL.md §14) holds a second key: edits name their key,
// and a view may follow the document at a time t (LodProfile.morph_t),
// tessellated from KeyedDocument::at(t) and rebuilt whole when either key
// changes (a morph moves every region); its changed regions are still
// encoded once and shared by every subscriber at that t (morph_view.h). The
// coarse stream of control points is morph_control.h's.
#pragma once

#include <atomic>
#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/morph/keyed_document.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/tessellation.h"
#include "protocol/tessera.pb.h"
#include "server/base/config.h"
#include "server/base/serial_queue.h"
#include "server/base/server_stats.h"
#include "server/document/command_application.h"
#include "server/document/commit_log.h"
#include "server/document/document_endpoint.h"
#include "server/document/document_presence.h"
#include "server/document/document_views.h"
#include "server/document/lod_view.h"
#include "server/document/profile_request.h"
#include "server/document/subscriber.h"
#include "server/document/tile_cache.h"
#include "server/document/tile_streams.h"
#include "server/store/store.h"

namespace tessera::server {

class DocumentHost : public DocumentEndpoint, public std::enable_shared_from_this<DocumentHost> {
 public:
  // Commands run on `workers`; the heavy ones of a large document (a
  // profile's first tessellation, an export) on `bulk` (serial_queue.h).
  DocumentHost(store::DocumentId id, std::string name, KeyedDocument doc, uint64_t version,
               boost::asio::any_io_executor workers, boost::asio::any_io_executor bulk, store::Store& store,
               const ServerConfig& config, ServerStats& stats);
  // Frees the document and its views on a bulk thread, which then trims the
  // heap (bulk_release.h).
  ~DocumentHost() override;

  store::DocumentId id() const { return id_; }

  // All of these post onto the host's strand and answer through the
  // subscriber; they never block the caller.
  void join(std::shared_ptr<Subscriber> who, std::string name, wire::Role role) override;
  void leave(uint64_t session) override;
  // Checked: at most --selection-max-ids ids, each existing in the
  // document; a refused selection gets a Reject for `clientSeq`.
  void select(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::Selection selection) override;
  // A participant whose presence changes were dropped (its queue was full)
  // gets the whole list again.
  void resendPresence(uint64_t session) override;
  // `withCommands`: also an AppliedCommand per command after the Ack's
  // version (docs/PROTOCOL.md, AppliedCommand); a later subscribe without it stops them.
  // With a view, a view-dependent subscription (tile_streams.h); else the
  // profile's view.
  void subscribe(std::shared_ptr<Subscriber> who, const wire::Subscribe& request, uint64_t clientSeq,
                 bool resync) override;
  void unsubscribe(uint64_t session) override;
  // Checked on the caller's thread; applied at most once per
  // --view-interval-ms per subscriber, a newer view replacing a waiting one.
  void setView(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::View view) override;
  void command(std::shared_ptr<Subscriber> author, std::string authorName,
               wire::ClientMessage message) override;
  void exportGlb(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::ExportDocument request) override;
  // The coarse morph stream: the control points at t (MorphControl).
  void morphControl(std::shared_ptr<Subscriber> who, uint64_t clientSeq,
                    wire::GetMorphControl request) override;
  // Refused from the level's face count (--max-triangles, as an export)
  // before anything is evaluated.
  void cage(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::GetCage request) override;

  // In a cluster, the journal entries loaded with the document that name
  // the client command they came from (session, client_seq) -> its Ack.
  // `fromVersion`: the version the load started from (its snapshot's), the
  // outcomes cover the entries after it.
  void setLoadedOutcomes(std::map<OutcomeBook::Key, CommandOutcome> outcomes, uint64_t fromVersion);
  // A session asks what became of commands it got no answer for (its
  // document moved here, or its node lost frames in a NATS reconnect): an
  // Ack for each in the journal as loaded or acknowledged here lately, a
  // Reject for each that is not; none yet for one still waiting for its
  // commit (its Ack follows).
  void answerOutcomes(std::shared_ptr<Subscriber> who, std::vector<uint64_t> clientSeqs);

  // Commands whose journal write's outcome is unknown (the store timed
  // out) at the failure go to `handler` (on the host's strand), unanswered
  // by this host: whoever reloads the document answers them from the
  // journal (answerOutcomes). Without a handler (one server: its store
  // always knows), they are refused as possibly lost, like the others.
  using Undecided = CommitLog::Undecided;
  void onUndecided(std::function<void(Undecided)> handler);

  // Whether a journal write failed: the host applies nothing more. In a
  // cluster this means another node wrote to the journal (it owns the
  // document now) or NATS lost quorum; the node then moves the sessions.
  bool journalFailed() const { return journalFailed_.load(); }

 private:
  // The replies of exportGlb and cage at version_, built on the document's
  // queue; replyOrReject (replies.h) frames them or says why not.
  Expected<wire::ServerMessage> exportMessage(uint64_t clientSeq, uint64_t sessionId,
                                              const wire::ExportDocument& request) const;
  Expected<wire::ServerMessage> cageMessage(uint64_t clientSeq, uint32_t level) const;
  // The document a view's tessellation follows.
  const Document& sourceOf(const LodView& view) const { return view.source ? *view.source : doc_.key0(); }
  // The view a checked profile asks for, tessellated at version_ with its
  // regions hashed; a morph view at its time (morph_view.h).
  Expected<LodView> buildView(const ProfileRequest& checked, const wire::LodProfile& requested);
  // Checks an applied command against the grid, then journals it.
  void afterApply(const std::shared_ptr<Subscriber>& author, uint64_t clientSeq, const AppliedChange& applied,
                  const std::string& authorName, const wire::ClientMessage& command);
  void scheduleFlush();
  std::chrono::steady_clock::duration flushInterval() const;
  // Posts a task an edit's Ack or delta waits for (the command, its
  // commit, a flush), counted while it waits: a turn of camera moves that
  // runs meanwhile builds no further tiles (docs/VIEWS.md "The server").
  void postEditTask(Lane lane, std::function<void()> task);
  // Updates every view from the limits changed since the last flush,
  // encodes the changed regions once and queues them as one batch.
  void flush();
  void committed(uint64_t version, Status status);
  // Releases what the commit log holds that is durable now.
  void release();
  void sendSnapshot(LodView& view, const std::shared_ptr<Subscriber>& who, bool resync, RegionCodec codec);
  void subscribeProfile(const std::shared_ptr<Subscriber>& who, const wire::LodProfile& requested,
                        uint64_t clientSeq, bool resync, bool withCommands, RegionCodec codec);
  // On the strand: a view-dependent subscription (tile_streams.h).
  void subscribeView(const std::shared_ptr<Subscriber>& who, const wire::Subscribe& request, const View& view,
                     uint64_t clientSeq, bool resync);
  // A view subscription goes ahead: the subscriber's profile goes, and the
  // Ack (not on a resync) starts its commands, if it asked for them.
  void acceptView(const std::shared_ptr<Subscriber>& who, const wire::Subscribe& request, uint64_t clientSeq,
                  bool resync);
  // After its Ack, a view's tiles could not be encoded: an Error, and its
  // stream goes.
  void viewFailed(const std::shared_ptr<Subscriber>& who, const Status& status);
  // The tile cache, made on the first view (on key 0 as it is now).
  TileCache& tileCache();
  // Applies the views that are due, and waits for the next.
  void scheduleViews();
  void applyViews();
  // After a flush sent the tiles edits reached: the streams whose camera
  // read them choose again, in a turn behind any waiting edit
  // (TileStreams::settle).
  void scheduleSettle();
  void settleViews();
  // Presence changed: one broadcast within 100 ms carries every change.
  void presenceChanged();
  // Frees the views dropped from views_ on a bulk thread (bulk_release.h).
  void releaseViews(DocumentViews::Views dropped);
  // What is freed off the interactive workers when the document closes.
  struct Released {
    std::optional<KeyedDocument> doc;
    DocumentViews::Views views;
  };
  // How the views' regions are encoded now (lod_view.h).
  EncodeContext encodeContext(const LodView& view) { return {version_, grid_, sourceOf(view), stats_}; }
  void maybeSnapshot();

  const store::DocumentId id_;
  const std::string name_;
  KeyedDocument doc_;
  bool keysChanged_ = false;  // a morph document changed since the last flush: its morph views rebuild
  uint64_t version_;          // applied
  uint64_t lastSnapshot_;
  uint64_t flushedVersion_;  // the version views' encoded regions and the last delta reach
  bool flushScheduled_ = false;
  bool failed_ = false;
  std::atomic<bool> journalFailed_{false};  // failed_, readable off the strand
  // Edits' tasks posted and not started (postEditTask): read by a running
  // turn of camera moves, off the posting threads.
  std::atomic<int> editTasksWaiting_{0};
  Status journalFailure_;      // why, for later commands' Rejects
  std::mutex undecidedMutex_;  // the handler is set off the strand
  std::function<void(Undecided)> undecidedHandler_;
  const LevelCounts counts_;  // the document's uniform level sizes, for estimates
  boost::asio::any_io_executor bulk_;
  SerialQueue queue_;  // the single writer; every member below is touched only in its tasks
  boost::asio::steady_timer presenceTimer_;
  bool presencePending_ = false;
  DocumentPresence presence_;
  store::Store& store_;
  const ServerConfig& config_;
  ServerStats& stats_;
  QuantizationGrid grid_;
  DocumentViews views_;
  boost::asio::steady_timer flushTimer_;
  std::chrono::steady_clock::time_point lastFlush_{};
  std::vector<VertexId> changedLimits_;  // by the edits applied since the last flush
  CommitLog commits_;  // applied, waiting for durability; Acks, recorders and outcome answers
  // View-dependent subscribers (docs/VIEWS.md "The server"), their tiles and
  // the timer that applies their cameras.
  std::unique_ptr<TileCache> tileCache_;
  TileStreams tileStreams_;
  boost::asio::steady_timer viewTimer_;
  bool viewsScheduled_ = false, settleScheduled_ = false;
};

}  // namespace tessera::server
