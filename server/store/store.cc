#include "server/store/store.h"

namespace tessera::store {

std::string toString(DocumentId id) {
  return "document " + std::to_string(id.value);
}

const char* roleName(Role role) {
  switch (role) {
    case Role::kViewer:
      return "viewer";
    case Role::kEditor:
      return "editor";
    case Role::kAdmin:
      return "admin";
  }
  return "unknown role";
}

const char* writeSyncName(WriteSync sync) {
  switch (sync) {
    case WriteSync::kEachWrite:
      return "each-write";
    case WriteSync::kNotEachWrite:
      return "not-each-write";
    case WriteSync::kConfigured:
      return "configured";
  }
  return "unknown";
}

Expected<Role> parseRole(std::string_view name) {
  for (Role role : {Role::kViewer, Role::kEditor, Role::kAdmin}) {
    if (name == roleName(role)) return role;
  }
  return invalidArgument("unknown role \"" + std::string(name) + "\" (expected viewer, editor or admin)");
}

std::string TokenScope::toString() const {
  return isAllDocuments() ? std::string("all documents") : store::toString(documentId());
}

uint64_t StoredDocument::latestVersion() const {
  if (!entries.empty()) return entries.back().version;
  return snapshot ? snapshot->version : 0;
}

}  // namespace tessera::store
