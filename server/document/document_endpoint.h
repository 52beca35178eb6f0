// What a connection asks of an open document. On a single node the
// document's host answers itself; in a cluster (docs/CLUSTER.md) a ClusterDocument
// answers, passing the calls to the host when this node owns the document
// and forwarding them to the owner when another node does. Either way the
// replies reach the connection through its Subscriber.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/util/status.h"
#include "protocol/tessera.pb.h"
#include "server/document/subscriber.h"
#include "server/store/store.h"

namespace tessera::server {

class DocumentEndpoint {
 public:
  virtual ~DocumentEndpoint() = default;

  // None of these block: each queues work and answers through `who`.
  virtual void join(std::shared_ptr<Subscriber> who, std::string name, wire::Role role) = 0;
  virtual void leave(uint64_t session) = 0;
  virtual void select(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::Selection selection) = 0;
  virtual void resendPresence(uint64_t session) = 0;
  // `request`: its profile, or its view (a view-dependent subscription),
  // and whether it records commands.
  virtual void subscribe(std::shared_ptr<Subscriber> who, const wire::Subscribe& request, uint64_t clientSeq,
                         bool resync) = 0;
  virtual void unsubscribe(uint64_t session) = 0;
  // A view-dependent subscriber's camera moved (SetView).
  virtual void setView(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::View view) = 0;
  virtual void command(std::shared_ptr<Subscriber> author, std::string authorName,
                       wire::ClientMessage message) = 0;
  virtual void exportGlb(std::shared_ptr<Subscriber> who, uint64_t clientSeq,
                         wire::ExportDocument request) = 0;
  virtual void morphControl(std::shared_ptr<Subscriber> who, uint64_t clientSeq,
                            wire::GetMorphControl request) = 0;
  // The polygons of one level of the control mesh (Cage).
  virtual void cage(std::shared_ptr<Subscriber> who, uint64_t clientSeq, wire::GetCage request) = 0;
};

// Opens documents for connections: the registry of hosts on a single node,
// the cluster node's router in a cluster.
class DocumentOpener {
 public:
  virtual ~DocumentOpener() = default;
  // Called on a bulk thread: loading may replay a long journal.
  virtual Expected<std::shared_ptr<DocumentEndpoint>> openEndpoint(store::DocumentId id) = 0;
  // A deleted document: forget what is open of it.
  virtual void forget(store::DocumentId id) = 0;
};

}  // namespace tessera::server
