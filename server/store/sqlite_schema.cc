#include "server/store/sqlite_schema.h"

#include "core/util/hex.h"

#include <array>
#include <cstdio>
#include <string>

namespace tessera::store {
namespace {

// Migration i takes a file from version i to i + 1. Never edit a released
// step: append a new one and raise kStoreSchemaVersion.
constexpr std::array<const char*, kStoreSchemaVersion> kMigrations = {
    // 0 -> 1
    R"sql(
      CREATE TABLE documents (
        id INTEGER PRIMARY KEY AUTOINCREMENT,  -- AUTOINCREMENT: ids are never reused
        name TEXT NOT NULL,
        base BLOB NOT NULL                     -- last, so listing never reads it
      );
      -- Small rows keyed by (document, version): WITHOUT ROWID keeps an append
      -- to one b-tree insert instead of a table row plus an index entry.
      CREATE TABLE journal (
        document_id INTEGER NOT NULL,
        version INTEGER NOT NULL CHECK (version >= 1),
        author TEXT NOT NULL,
        entry BLOB NOT NULL,
        PRIMARY KEY (document_id, version)
      ) WITHOUT ROWID;
      CREATE TABLE snapshots (
        document_id INTEGER NOT NULL,
        version INTEGER NOT NULL CHECK (version >= 1),
        state BLOB NOT NULL,
        PRIMARY KEY (document_id, version)
      );
      CREATE TABLE tokens (
        token_hash BLOB NOT NULL CHECK (length(token_hash) = 32),  -- SHA-256, never the token
        scope INTEGER NOT NULL,                                    -- a document id, 0 = all documents
        role INTEGER NOT NULL CHECK (role BETWEEN 1 AND 3),
        PRIMARY KEY (token_hash, scope)
      ) WITHOUT ROWID;
      CREATE INDEX tokens_by_scope ON tokens (scope);
    )sql",
};

constexpr std::array<const char*, 4> kTables = {"documents", "journal", "snapshots", "tokens"};

std::string hex32(int64_t value) {
  return hexNumber(static_cast<uint64_t>(value) & 0xffffffff, 8);
}

// Refuses, without writing, a file that is not a Tessera store this build reads.
Status checkOwnership(const SqliteConnection& db, int64_t objects, int64_t applicationId, int64_t version) {
  if (applicationId != kStoreApplicationId) {
    return unsupported(db.path() + ": not a Tessera store: application_id is " + hex32(applicationId) +
                       " (Tessera writes " + hex32(kStoreApplicationId) + ") and it holds " +
                       std::to_string(objects) +
                       " tables and indexes of another program; refusing to use it");
  }
  if (version > kStoreSchemaVersion) {
    return unsupported(db.path() + ": written by a newer Tessera: schema version " + std::to_string(version) +
                       ", this build understands up to " + std::to_string(kStoreSchemaVersion));
  }
  if (version < 1) {
    return parseError(db.path() + ": marked as a Tessera store but has no schema version (" +
                      std::to_string(version) + "); the file is damaged");
  }
  return Status::ok();
}

Status checkIntegrity(SqliteConnection& db) {
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement check, db.prepare("PRAGMA quick_check(1)"));
  TESSERA_ASSIGN_OR_RETURN(bool row, check.step());
  const std::string verdict = row ? check.columnText(0) : std::string("no verdict");
  if (verdict != "ok") return parseError(db.path() + ": integrity check failed: " + verdict);
  return Status::ok();
}

Status useWal(SqliteConnection& db) {
  TESSERA_ASSIGN_OR_RETURN(std::string mode, db.queryText("PRAGMA journal_mode = WAL"));
  if (mode != "wal") {
    return ioError(db.path() + ": cannot switch to WAL journaling (still \"" + mode +
                   "\"); the file system may not support shared memory");
  }
  return Status::ok();
}

Status migrate(SqliteConnection& db, int64_t fromVersion) {
  // The header fields change in the same transaction as the tables, so a
  // crash leaves either the old version or the new one, never a mix.
  TESSERA_RETURN_IF_ERROR(db.exec("BEGIN IMMEDIATE"));
  Status status = db.exec(kMigrations[fromVersion]);
  if (status.isOk()) {
    status = db.exec("PRAGMA application_id = " + std::to_string(kStoreApplicationId) +
                     "; PRAGMA user_version = " + std::to_string(fromVersion + 1));
  }
  if (status.isOk()) status = db.exec("COMMIT");
  if (!status.isOk()) {
    if (db.inTransaction()) (void)db.exec("ROLLBACK");
    return status.withContext("migrating the schema from version " + std::to_string(fromVersion));
  }
  return Status::ok();
}

Status checkTables(SqliteConnection& db) {
  for (const char* table : kTables) {
    TESSERA_ASSIGN_OR_RETURN(
        SqliteStatement find,
        db.prepare("SELECT count(*) FROM sqlite_schema WHERE type = 'table' AND name = ?1"));
    find.bindText(1, table);
    TESSERA_ASSIGN_OR_RETURN(bool row, find.step());
    if (!row || find.columnInt(0) != 1) {
      return parseError(db.path() + ": Tessera store without its \"" + table +
                        "\" table; the file is damaged");
    }
  }
  return Status::ok();
}

}  // namespace

Status prepareSchema(SqliteConnection& db, const SchemaOptions& options) {
  // The first read of the file: random bytes or a damaged header fail here.
  auto objects = db.queryInt("SELECT count(*) FROM sqlite_schema");
  if (!objects) return objects.status().withContext("opening the store");
  TESSERA_ASSIGN_OR_RETURN(int64_t applicationId, db.queryInt("PRAGMA application_id"));
  TESSERA_ASSIGN_OR_RETURN(int64_t version, db.queryInt("PRAGMA user_version"));

  const bool fresh = *objects == 0 && applicationId == 0 && version == 0;
  if (!fresh) {
    TESSERA_RETURN_IF_ERROR(checkOwnership(db, *objects, applicationId, version));
    if (options.verifyIntegrity) TESSERA_RETURN_IF_ERROR(checkIntegrity(db));
  }
  TESSERA_RETURN_IF_ERROR(useWal(db));
  for (int64_t from = fresh ? 0 : version; from < kStoreSchemaVersion; ++from) {
    TESSERA_RETURN_IF_ERROR(migrate(db, from));
  }
  return checkTables(db);
}

}  // namespace tessera::store
