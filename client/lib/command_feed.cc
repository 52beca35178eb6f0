#include "client/lib/command_feed.h"

namespace tessera::client {

Expected<const wire::AppliedCommand*> CommandFeed::apply(const wire::ServerMessage& message) {
  if (!message.has_applied_command() || message.applied_command().document_id() != documentId_) {
    return static_cast<const wire::AppliedCommand*>(nullptr);
  }
  const wire::AppliedCommand& c = message.applied_command();
  if (c.version() != version_ + 1) {
    return invalidArgument("document " + std::to_string(documentId_) + ": command of version " +
                           std::to_string(c.version()) + " does not follow version " +
                           std::to_string(version_));
  }
  version_ = c.version();
  ++received_;
  return &c;
}

}  // namespace tessera::client
