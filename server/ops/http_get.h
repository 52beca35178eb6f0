// One plain-HTTP GET with a deadline (Boost.Beast, the server's one HTTP
// stack): how `tessera-server health` asks a running server's /healthz
// (docs/OPERATIONS.md, "Health and metrics"). Blocking; it runs its own
// io_context for the one exchange.
#pragma once

#include <chrono>
#include <string>

#include "core/util/status.h"

namespace tessera::server {

struct HttpReply {
  int status = 0;
  std::string contentType;
  std::string body;
};

// GETs `url`, http://HOST[:PORT][/PATH] (HOST a name, an IPv4 address or
// [an IPv6 one]; PORT 80 unless given), with the whole exchange --
// resolving, connecting, sending, reading the answer -- within `timeout`.
// Every error names the URL: a malformed one is an invalid argument, a
// failed exchange an I/O error, no answer in time a timeout.
Expected<HttpReply> httpGet(const std::string& url, std::chrono::milliseconds timeout);

}  // namespace tessera::server
