// --ws-port (docs/WEB_VIEWER.md, "Serving it"): one port for browsers. Plain HTTP GETs of the
// viewer's files (static_files.h) and WebSocket upgrades on /ws that become
// protocol connections (websocket_transport.h), plain or, with TLS on,
// https and wss. What reaches a Connection has passed the origin check;
// the server then applies the same connection limits as on its protocol
// port (Server::overLimits) before accepting the upgrade.
//
// Before its upgrade a peer is an HTTP client: a request of at most 8 KiB
// of headers and no body, read within the handshake deadline, at most
// --unauthenticated-per-address such peers per address and
// --unauthenticated-total in all.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ssl/context.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/util/status.h"
#include "server/base/config.h"
#include "server/net/static_files.h"
#include "server/net/transport.h"

namespace tessera::server {

// A WebSocket upgrade that passed the web port's checks, waiting for the
// server's decision. Exactly one of accept() and refuse() is called, from
// any thread.
class PendingUpgrade {
 public:
  virtual ~PendingUpgrade() = default;
  virtual const std::string& address() const = 0;
  // The transport over this connection, bound to `strand`; its start()
  // answers the upgrade.
  virtual std::unique_ptr<Transport> accept(const ConnectionStrand& strand) = 0;
  // Answers the upgrade with HTTP 503 and `reason`, then closes.
  virtual void refuse(const std::string& reason) = 0;
  // The executor of the connection's socket (for its strand).
  virtual boost::asio::any_io_executor executor() = 0;
};

struct WebPortOptions {
  std::string address;
  int port = 0;
  boost::asio::ssl::context* tls = nullptr;
  // Origins allowed besides the page's own (--ws-allowed-origin; "*" any).
  std::vector<std::string> allowedOrigins;
  Limits limits;
  Timeouts timeouts;
};

class WebPort {
 public:
  using OnUpgrade = std::function<void(std::shared_ptr<PendingUpgrade>)>;

  // Binds at once (a taken port fails start-up), then accepts on `io`.
  static Expected<std::unique_ptr<WebPort>> start(boost::asio::io_context& io, WebPortOptions options,
                                                  StaticFiles files, OnUpgrade onUpgrade);
  ~WebPort();

  uint16_t port() const;
  void stop();  // stops accepting; connections already upgraded go on

  struct Impl;  // public only so that web_port.cc's sessions can name it

 private:
  explicit WebPort(std::shared_ptr<Impl> impl);
  std::shared_ptr<Impl> impl_;
};

}  // namespace tessera::server
