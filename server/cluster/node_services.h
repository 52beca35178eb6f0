// What one document of a cluster node (ClusterDocument) asks of its node:
// the node's name and leases, the registry of local hosts, the book of
// unanswered commands, and the way to other nodes. ClusterNode implements
// it; a ClusterDocument sees only this, so the document depends on the
// node's services and never on the node that routes to it
// (docs/CLUSTER.md describes both).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "protocol/cluster.pb.h"
#include "server/base/server_stats.h"
#include "server/cluster/cluster_relay.h"
#include "server/cluster/document_leases.h"
#include "server/document/document_registry.h"
#include "server/document/subscriber.h"
#include "server/store/store.h"

namespace tessera::cluster {

class ClusterDocument;

// The number of the node that made `session` (ClusterNode::firstSessionId).
inline uint64_t sessionIncarnation(uint64_t session) {
  return session >> 40;
}

class NodeServices {
 public:
  virtual ~NodeServices() = default;

  virtual const std::string& name() const = 0;
  virtual uint32_t maxFrameBytes() const = 0;
  virtual DocumentLeases& leases() = 0;
  virtual server::DocumentRegistry& registry() = 0;
  virtual server::ServerStats& stats() = 0;
  virtual store::Store& store() = 0;

  // Sends a request of a local session to the document's owner.
  virtual void forward(const std::string& owner, const Forward& request) = 0;
  virtual void addLocalSession(uint64_t session, std::weak_ptr<server::Subscriber> who) = 0;

  // The one book of this node's sessions' commands that have no answer
  // yet: forwarded to an owner elsewhere (until an Ack or a Reject with
  // their client_seq comes back), or undecided by a host here whose
  // journal write timed out. Whoever owns the document next answers them
  // (ClusterDocument::answerBookLocked).
  virtual void noteOutstanding(uint64_t session, uint64_t clientSeq, store::DocumentId document) = 0;
  struct Outstanding {
    std::shared_ptr<server::Subscriber> who;
    std::vector<uint64_t> clientSeqs;
  };
  // Those of `document`, per local session still connected; taken off the
  // book when `take` (answered here, where no answer passes the book),
  // otherwise marked as asked about now. Only those last asked about
  // before `askedBefore` when it is given.
  virtual std::vector<Outstanding> outstandingOf(
      store::DocumentId document, bool take,
      std::optional<std::chrono::steady_clock::time_point> askedBefore = {}) = 0;

  virtual std::shared_ptr<RemoteSubscriber> remoteSubscriber(const std::string& node, uint64_t session) = 0;
  // Kept open for other nodes' sessions, until unpinned.
  virtual void pin(const std::shared_ptr<ClusterDocument>& document) = 0;
  virtual void unpin(store::DocumentId id) = 0;
  // Tells `node` this node no longer serves its sessions of `document` as
  // before (they must rejoin `owner`).
  virtual void tellNotOwner(const std::string& node, store::DocumentId document,
                            const std::string& owner) = 0;
};

}  // namespace tessera::cluster
