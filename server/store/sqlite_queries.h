// The store's SQL, one function per operation, over a connection whose
// transaction the caller owns: the writes run inside the group-commit batch
// (each in its own savepoint), the reads inside one read transaction so that
// a document is always seen at a single commit.
//
// Arguments are already validated by SqliteStore; these check only what
// needs the database (does the document exist, is the version next).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "core/util/status.h"
#include "server/store/sqlite_connection.h"
#include "server/store/store.h"

namespace tessera::store {

// Snapshots kept per document: the newest, plus one in case the newest
// turns out to be unreadable by the server.
inline constexpr int kSnapshotsKept = 2;

// Writes.
Expected<DocumentId> insertDocument(SqliteConnection& db, std::string_view name, std::string_view baseBytes);
Status deleteDocumentRows(SqliteConnection& db, DocumentId id);
Status insertJournalEntry(SqliteConnection& db, DocumentId id, uint64_t version, std::string_view author,
                          std::string_view bytes);
Status insertSnapshot(SqliteConnection& db, DocumentId id, uint64_t version, std::string_view bytes);
Status insertToken(SqliteConnection& db, TokenScope scope, std::string_view tokenHash, Role role);
Status deleteToken(SqliteConnection& db, std::string_view tokenHash);

// Reads.
Expected<std::vector<DocumentSummary>> selectDocuments(SqliteConnection& db);
Expected<StoredDocument> selectDocument(SqliteConnection& db, DocumentId id);
// The highest role `tokenHash` holds for `scope`, or nothing.
Expected<std::optional<Role>> selectRole(SqliteConnection& db, std::string_view tokenHash, TokenScope scope);
// Whether any grant of any scope names the token.
Expected<bool> selectTokenKnown(SqliteConnection& db, std::string_view tokenHash);

}  // namespace tessera::store
