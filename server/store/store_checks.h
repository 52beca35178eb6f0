// Argument checks every Store engine makes the same way, with the same
// messages, so that a client cannot tell the embedded SQLite store from the
// cluster's JetStream one by its refusals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>

#include "core/util/status.h"
#include "protocol/token_limits.h"
#include "server/store/store.h"

namespace tessera::store {

inline constexpr size_t kMaxDocumentNameBytes = 1024;
inline constexpr size_t kMaxAuthorBytes = 1024;
// Tokens are bearer secrets compared by hash: short ones could be guessed
// offline from a stolen store, so they are refused when granted.
inline constexpr size_t kMinTokenBytes = 16;
// Ids and versions fit SQLite's signed 64-bit integers in every engine, so a
// document can move between engines (tessera store export/import).
inline constexpr uint64_t kMaxStoredInteger = static_cast<uint64_t>(std::numeric_limits<int64_t>::max());

// kNotFound naming the id for ids no engine ever hands out (0, > 2^63-1).
Status checkDocumentId(DocumentId id);
// kInvalidArgument for versions outside 1..2^63-1; `what` names the write.
Status checkVersion(DocumentId id, uint64_t version, const char* what);
Status checkDocumentName(std::string_view name);
Status checkAuthor(DocumentId id, std::string_view author);
// Messages about tokens give sizes and scopes, never the token's text.
Status checkTokenToGrant(std::string_view token);
Status checkRole(Role role);

Status documentNotFound(DocumentId id);  // "document 7 does not exist"
// The refusal of a journal entry whose version is not the next one.
Status versionNotNext(DocumentId id, uint64_t version, uint64_t latest);
// The refusal of a snapshot past the journal's end.
Status snapshotPastEnd(DocumentId id, uint64_t version, uint64_t latest);

}  // namespace tessera::store
