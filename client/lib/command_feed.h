// The commands of one document as a subscriber that asked for them
// (Subscribe.with_commands) receives them: each AppliedCommand is checked to
// follow the previous one's version, so a recording has no hole.
//
//   CommandFeed feed(doc, ackVersion);            // the subscribe's Ack
//   auto c = feed.apply(message);                 // nullptr: not a command of doc
//   if (c.isOk() && *c) record(**c);
#pragma once

#include <cstdint>

#include "core/util/status.h"
#include "protocol/tessera.pb.h"

namespace tessera::client {

class CommandFeed {
 public:
  // `fromVersion`: the version the subscription started at (its Ack's).
  CommandFeed(uint64_t documentId, uint64_t fromVersion) : documentId_(documentId), version_(fromVersion) {}

  // The AppliedCommand in `message` if it is one of this document, else
  // nullptr. Errors: a version that does not follow the last one.
  Expected<const wire::AppliedCommand*> apply(const wire::ServerMessage& message);

  uint64_t documentId() const { return documentId_; }
  // The version of the last command received (the start version before any).
  uint64_t version() const { return version_; }
  uint64_t received() const { return received_; }

 private:
  uint64_t documentId_;
  uint64_t version_;
  uint64_t received_ = 0;
};

}  // namespace tessera::client
