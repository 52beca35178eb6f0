#include "server/store/store_checks.h"

#include <string>

namespace tessera::store {

Status checkDocumentId(DocumentId id) {
  if (id.value == 0 || id.value > kMaxStoredInteger) return documentNotFound(id);
  return Status::ok();
}

Status checkVersion(DocumentId id, uint64_t version, const char* what) {
  if (version == 0 || version > kMaxStoredInteger) {
    return invalidArgument(toString(id) + ": " + what + " version " + std::to_string(version) +
                           " is out of range (versions start at 1)");
  }
  return Status::ok();
}

Status checkDocumentName(std::string_view name) {
  if (name.empty() || name.size() > kMaxDocumentNameBytes) {
    return invalidArgument("document name of " + std::to_string(name.size()) +
                           " bytes refused: names need 1 to " + std::to_string(kMaxDocumentNameBytes) +
                           " bytes");
  }
  return Status::ok();
}

Status checkAuthor(DocumentId id, std::string_view author) {
  if (author.size() > kMaxAuthorBytes) {
    return invalidArgument(toString(id) + ": author name of " + std::to_string(author.size()) +
                           " bytes refused (at most " + std::to_string(kMaxAuthorBytes) + ")");
  }
  return Status::ok();
}

Status checkTokenToGrant(std::string_view token) {
  if (token.size() < kMinTokenBytes || token.size() > kMaxTokenBytes) {
    return invalidArgument("access token of " + std::to_string(token.size()) +
                           " bytes refused: tokens need " + std::to_string(kMinTokenBytes) + " to " +
                           std::to_string(kMaxTokenBytes) + " bytes");
  }
  return Status::ok();
}

Status checkRole(Role role) {
  if (role != Role::kViewer && role != Role::kEditor && role != Role::kAdmin) {
    return invalidArgument("unknown role " + std::to_string(static_cast<int>(role)) + " for an access token");
  }
  return Status::ok();
}

Status documentNotFound(DocumentId id) {
  return notFound(toString(id) + " does not exist");
}

Status versionNotNext(DocumentId id, uint64_t version, uint64_t latest) {
  return invalidArgument(toString(id) + ": journal entry version " + std::to_string(version) +
                         " refused: the next version is " + std::to_string(latest + 1));
}

Status snapshotPastEnd(DocumentId id, uint64_t version, uint64_t latest) {
  return invalidArgument(toString(id) + ": snapshot at version " + std::to_string(version) +
                         " refused: the journal ends at version " + std::to_string(latest));
}

}  // namespace tessera::store
