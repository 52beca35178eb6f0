// The open documents of one node: each loaded from the store (its journal
// replayed onto its last snapshot) on first use, and shared by every
// connection that opened it. On a single node the hosts are the endpoints
// connections talk to; in a cluster the node's router wraps them.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <map>
#include <memory>
#include <mutex>

#include "server/base/config.h"
#include "server/base/server_stats.h"
#include "server/document/document_endpoint.h"
#include "server/document/document_host.h"
#include "server/store/store.h"

namespace tessera::server {

// Open documents, loaded from the store on first use and shared by every
// connection that opened them.
class DocumentRegistry : public DocumentOpener {
 public:
  DocumentRegistry(store::Store& store, boost::asio::any_io_executor workers,
                   boost::asio::any_io_executor bulk, const ServerConfig& config, ServerStats& stats)
      : store_(store), workers_(workers), bulk_(bulk), config_(config), stats_(stats) {}

  // Loads (on the calling thread) or shares the host of a document.
  Expected<std::shared_ptr<DocumentHost>> open(store::DocumentId id);
  // A single node's endpoints are its hosts.
  Expected<std::shared_ptr<DocumentEndpoint>> openEndpoint(store::DocumentId id) override;
  // Forgets a deleted document's host.
  void forget(store::DocumentId id) override;
  // Documents whose host is alive (held by a session or still loading).
  int64_t openCount();

 private:
  store::Store& store_;
  boost::asio::any_io_executor workers_, bulk_;
  const ServerConfig& config_;
  ServerStats& stats_;
  std::mutex mutex_;
  std::map<uint64_t, std::weak_ptr<DocumentHost>> hosts_;
};

}  // namespace tessera::server
