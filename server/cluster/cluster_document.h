// One open document on a node of a cluster (docs/CLUSTER.md): the endpoint
// its local connections talk to, whoever owns the document.
//
// When this node holds the document's lease, the calls go straight to the
// local DocumentHost (which journals to JetStream and acknowledges only
// durable edits), and sessions of other nodes join that host as
// RemoteSubscribers. Otherwise every call is forwarded to the owner as a
// Forward, and the owner's frames come back through the node.
//
// When the owner changes (its lease expired, this node lost its own, or an
// append was refused because another node wrote), rehome() moves every
// local session to the new owner: each is told that the document moved and
// that an edit without its Ack may be lost, and each subscription gets a
// resync snapshot from the new owner, so no viewer sees a gap it is not
// told of.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>

#include "protocol/cluster.pb.h"
#include "server/cluster/node_services.h"
#include "server/document/document_endpoint.h"
#include "server/document/document_host.h"

namespace tessera::cluster {

class ClusterDocument : public server::DocumentEndpoint,
                        public std::enable_shared_from_this<ClusterDocument> {
 public:
  ClusterDocument(store::DocumentId id, NodeServices& node) : id_(id), node_(node) {}
  ~ClusterDocument() override;

  // Takes the lease and loads the document, or finds its owner, unless an
  // owner is known already.
  Status resolve();
  // The last resolve failed only because the lease is still under this
  // node's name from before (DocumentLeases::acquire): the monitor's next
  // tries will succeed within the lease time, so a new session may wait.
  bool ownerExpectedSoon();

  void join(std::shared_ptr<server::Subscriber> who, std::string name, wire::Role role) override;
  void leave(uint64_t session) override;
  void select(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq,
              wire::Selection selection) override;
  void resendPresence(uint64_t session) override;
  void subscribe(std::shared_ptr<server::Subscriber> who, const wire::Subscribe& request, uint64_t clientSeq,
                 bool resync) override;
  void setView(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq, wire::View view) override;
  void unsubscribe(uint64_t session) override;
  void command(std::shared_ptr<server::Subscriber> author, std::string authorName,
               wire::ClientMessage message) override;
  void exportGlb(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq,
                 wire::ExportDocument request) override;
  void morphControl(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq,
                    wire::GetMorphControl request) override;
  void cage(std::shared_ptr<server::Subscriber> who, uint64_t clientSeq, wire::GetCage request) override;

  // The owner's side: a request of another node's session. False when this
  // node does not own the document (the sender is told NotOwner).
  bool serveRemote(const Forward& request);

  // For the node's lease monitor.
  store::DocumentId id() const { return id_; }
  bool ownedHere();
  std::string owner();   // the owner node, "" when unknown
  bool journalFailed();  // the local host's journal refused a write: it applies nothing more
  bool notOwnerReported() const { return notOwner_.load(); }  // a NotOwner came back for a Forward
  void markNotOwner() { notOwner_ = true; }
  // Moves every local session to the document's current owner.
  void rehome(const std::string& why);
  bool hasRemoteSessions();
  std::vector<uint64_t> remoteSessionIds();  // other nodes' sessions joined here
  // After this node's NATS connection came back: asks the owner what became
  // of the local sessions' commands still unanswered (their answers may
  // have been lost meanwhile); answerBookLocked.
  void askOutcomes();
  // Owned elsewhere: asks the owner again about the local sessions'
  // commands forwarded or last asked about before `before`, still
  // unanswered (the answer, or the command, may have been lost in NATS).
  void askOverdue(std::chrono::steady_clock::time_point before);
  // The owner's side: a node died (or restarted as a new incarnation):
  // its sessions leave the document, as if each had closed it.
  void dropRemoteSessions(const std::string& node, uint64_t incarnation);

 private:
  struct LocalSession {
    std::weak_ptr<server::Subscriber> who;
    std::string name;
    wire::Role role = wire::ROLE_VIEWER;
    std::optional<wire::Subscribe> subscription;  // its latest view, if it has one
    // A Subscribe sent while there was no owner, not yet answered: the
    // owner found later acknowledges it (rejoinLocked) instead of a resync.
    uint64_t unansweredSubscribe = 0;
  };
  // Under mutex_: a Forward of `kind` for `session` to the owner.
  void forward(uint64_t session, Forward::Kind kind, const std::function<void(Forward&)>& fill);
  Status resolveLocked();
  // Undecided commands (the host's journal write timed out) of this node's
  // sessions: into the node's book of unanswered commands.
  void undecidedArrived(server::DocumentHost::Undecided undecided);
  // Under mutex_: the book's commands of this document are answered by the
  // host here or asked of the owner elsewhere, once there is an owner that
  // has not failed; otherwise they stay for the next rehome.
  void answerBookLocked();
  // Under mutex_: asks the owner elsewhere what became of `seqs`.
  void askOwnerLocked(uint64_t session, const std::vector<uint64_t>& seqs);
  void dropHostLocked();
  // rehome's steps, under mutex_: leaving the old owner (returns the nodes
  // whose sessions were on the dropped host), the notice every local
  // session gets (a frame), and one session's move to the new owner.
  std::set<std::string> leaveOwnerLocked();
  std::shared_ptr<const std::string> movedNotice(const std::string& from, const std::string& why,
                                                 const Status& resolved);
  void rejoinLocked(uint64_t session, const std::shared_ptr<server::Subscriber>& who, LocalSession& s);

  const store::DocumentId id_;
  NodeServices& node_;
  std::mutex mutex_;
  std::shared_ptr<server::DocumentHost> host_;  // set while this node owns the document
  std::string owner_;                           // otherwise: the owner's node name
  std::string whyUnowned_;                      // no owner: why the last attempt to find or load one failed
  bool ownLeaseStale_ = false;                  // ... and that was this node's lease from before
  std::string whyLost_;                         // no owner: why the last one was given up (rehome), if it was
  std::map<uint64_t, LocalSession> sessions_;
  std::map<uint64_t, std::string> remoteSessions_;  // other nodes' sessions joined to host_ -> their node
  std::atomic<bool> notOwner_{false};
};

}  // namespace tessera::cluster
