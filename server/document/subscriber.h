// What a document host needs from a connection: its identity and a
// thread-safe way to queue messages to it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "server/document/delta.h"

namespace tessera::server {

class Subscriber {
 public:
  virtual ~Subscriber() = default;
  virtual uint64_t sessionId() const = 0;
  // Thread-safe: queues the message on the connection's own strand.
  virtual void send(Outgoing message) = 0;
};

}  // namespace tessera::server
