// What every connection shares: settings, the store, where documents are
// opened, counters, and the worker pool that runs document strands.
#pragma once

#include <boost/asio/any_io_executor.hpp>

#include "server/base/config.h"
#include "server/base/server_stats.h"
#include "server/document/document_endpoint.h"
#include "server/net/auth_throttle.h"
#include "server/store/store.h"

namespace tessera::server {

struct ServerContext {
  const ServerConfig& config;
  store::Store& store;
  // Where connections open documents: the registry of hosts on a single
  // node, the cluster node's router in a cluster.
  DocumentOpener& opener;
  ServerStats& stats;
  boost::asio::any_io_executor workers;
  // Imports and loads (docs/ARCHITECTURE.md, "Bulk work"): off the workers
  // that run documents' strands.
  boost::asio::any_io_executor bulk;
  AuthThrottle& authThrottle;
};

}  // namespace tessera::server
