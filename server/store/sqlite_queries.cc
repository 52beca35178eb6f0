#include "server/store/sqlite_queries.h"

#include "server/store/store_checks.h"

#include <string>

namespace tessera::store {
namespace {

int64_t sqlId(DocumentId id) {
  return static_cast<int64_t>(id.value);
}

// Tokens for every document use scope 0, a value no document id takes.
int64_t sqlScope(TokenScope scope) {
  return scope.isAllDocuments() ? 0 : sqlId(scope.documentId());
}

// The document's latest journal version (0 before the first edit), or
// kNotFound. One statement: the existence check and the max share a lookup.
Expected<uint64_t> latestVersion(SqliteConnection& db, DocumentId id) {
  TESSERA_ASSIGN_OR_RETURN(
      SqliteStatement select,
      db.prepare(
          "SELECT (SELECT max(version) FROM journal WHERE document_id = ?1) FROM documents WHERE id = ?1"));
  select.bindInt(1, sqlId(id));
  TESSERA_ASSIGN_OR_RETURN(bool row, select.step());
  if (!row) return documentNotFound(id);
  return select.columnIsNull(0) ? uint64_t{0} : static_cast<uint64_t>(select.columnInt(0));
}

}  // namespace

Expected<DocumentId> insertDocument(SqliteConnection& db, std::string_view name, std::string_view baseBytes) {
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement insert,
                           db.prepare("INSERT INTO documents (name, base) VALUES (?1, ?2)"));
  insert.bindText(1, name).bindBlob(2, baseBytes);
  TESSERA_RETURN_IF_ERROR(insert.run());
  return DocumentId{static_cast<uint64_t>(db.lastInsertRowid())};
}

Status deleteDocumentRows(SqliteConnection& db, DocumentId id) {
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement document, db.prepare("DELETE FROM documents WHERE id = ?1"));
  document.bindInt(1, sqlId(id));
  TESSERA_RETURN_IF_ERROR(document.run());
  if (db.changes() == 0) return documentNotFound(id);
  for (const char* sql :
       {"DELETE FROM journal WHERE document_id = ?1", "DELETE FROM snapshots WHERE document_id = ?1",
        "DELETE FROM tokens WHERE scope = ?1"}) {
    TESSERA_ASSIGN_OR_RETURN(SqliteStatement statement, db.prepare(sql));
    statement.bindInt(1, sqlId(id));
    TESSERA_RETURN_IF_ERROR(statement.run());
  }
  return Status::ok();
}

Status insertJournalEntry(SqliteConnection& db, DocumentId id, uint64_t version, std::string_view author,
                          std::string_view bytes) {
  TESSERA_ASSIGN_OR_RETURN(uint64_t latest, latestVersion(db, id));
  if (version != latest + 1) {
    return versionNotNext(id, version, latest);
  }
  TESSERA_ASSIGN_OR_RETURN(
      SqliteStatement insert,
      db.prepare("INSERT INTO journal (document_id, version, author, entry) VALUES (?1, ?2, ?3, ?4)"));
  insert.bindInt(1, sqlId(id))
      .bindInt(2, static_cast<int64_t>(version))
      .bindText(3, author)
      .bindBlob(4, bytes);
  return insert.run();
}

Status insertSnapshot(SqliteConnection& db, DocumentId id, uint64_t version, std::string_view bytes) {
  TESSERA_ASSIGN_OR_RETURN(uint64_t latest, latestVersion(db, id));
  if (version > latest) {
    return snapshotPastEnd(id, version, latest);
  }
  TESSERA_ASSIGN_OR_RETURN(
      SqliteStatement insert,
      db.prepare("INSERT OR REPLACE INTO snapshots (document_id, version, state) VALUES (?1, ?2, ?3)"));
  insert.bindInt(1, sqlId(id)).bindInt(2, static_cast<int64_t>(version)).bindBlob(3, bytes);
  TESSERA_RETURN_IF_ERROR(insert.run());

  TESSERA_ASSIGN_OR_RETURN(SqliteStatement prune, db.prepare(R"sql(
      DELETE FROM snapshots WHERE document_id = ?1 AND version NOT IN (
        SELECT version FROM snapshots WHERE document_id = ?1 ORDER BY version DESC LIMIT ?2))sql"));
  prune.bindInt(1, sqlId(id)).bindInt(2, kSnapshotsKept);
  return prune.run();
}

Status insertToken(SqliteConnection& db, TokenScope scope, std::string_view tokenHash, Role role) {
  if (!scope.isAllDocuments()) {
    TESSERA_ASSIGN_OR_RETURN(uint64_t latest, latestVersion(db, scope.documentId()));
    (void)latest;  // only the existence check matters here
  }
  TESSERA_ASSIGN_OR_RETURN(
      SqliteStatement insert,
      db.prepare("INSERT OR REPLACE INTO tokens (token_hash, scope, role) VALUES (?1, ?2, ?3)"));
  insert.bindBlob(1, tokenHash).bindInt(2, sqlScope(scope)).bindInt(3, static_cast<int64_t>(role));
  return insert.run();
}

Status deleteToken(SqliteConnection& db, std::string_view tokenHash) {
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement remove, db.prepare("DELETE FROM tokens WHERE token_hash = ?1"));
  remove.bindBlob(1, tokenHash);
  TESSERA_RETURN_IF_ERROR(remove.run());
  // Never name the token: the caller knows which one it passed.
  if (db.changes() == 0) return notFound("no such access token");
  return Status::ok();
}

Expected<std::vector<DocumentSummary>> selectDocuments(SqliteConnection& db) {
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement select, db.prepare(R"sql(
      SELECT id, name, (SELECT max(version) FROM journal WHERE document_id = documents.id)
      FROM documents ORDER BY id)sql"));
  std::vector<DocumentSummary> documents;
  while (true) {
    TESSERA_ASSIGN_OR_RETURN(bool row, select.step());
    if (!row) break;
    DocumentSummary summary;
    summary.id = DocumentId{static_cast<uint64_t>(select.columnInt(0))};
    summary.name = select.columnText(1);
    summary.latestVersion = select.columnIsNull(2) ? 0 : static_cast<uint64_t>(select.columnInt(2));
    documents.push_back(std::move(summary));
  }
  return documents;
}

Expected<StoredDocument> selectDocument(SqliteConnection& db, DocumentId id) {
  StoredDocument document;
  document.id = id;
  {
    TESSERA_ASSIGN_OR_RETURN(SqliteStatement select,
                             db.prepare("SELECT name, base FROM documents WHERE id = ?1"));
    select.bindInt(1, sqlId(id));
    TESSERA_ASSIGN_OR_RETURN(bool row, select.step());
    if (!row) return documentNotFound(id);
    document.name = select.columnText(0);
    document.baseBytes = select.columnBlob(1);
  }
  {
    TESSERA_ASSIGN_OR_RETURN(
        SqliteStatement select,
        db.prepare(
            "SELECT version, state FROM snapshots WHERE document_id = ?1 ORDER BY version DESC LIMIT 1"));
    select.bindInt(1, sqlId(id));
    TESSERA_ASSIGN_OR_RETURN(bool row, select.step());
    if (row) document.snapshot = Snapshot{static_cast<uint64_t>(select.columnInt(0)), select.columnBlob(1)};
  }
  const uint64_t after = document.snapshot ? document.snapshot->version : 0;
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement select, db.prepare(R"sql(
      SELECT version, author, entry FROM journal WHERE document_id = ?1 AND version > ?2 ORDER BY version)sql"));
  select.bindInt(1, sqlId(id)).bindInt(2, static_cast<int64_t>(after));
  while (true) {
    TESSERA_ASSIGN_OR_RETURN(bool row, select.step());
    if (!row) break;
    JournalEntry entry{static_cast<uint64_t>(select.columnInt(0)), select.columnText(1),
                       select.columnBlob(2)};
    // Appends are checked to be contiguous, so a gap means the file was
    // altered behind the store's back; replaying across it would be wrong.
    const uint64_t expected = after + document.entries.size() + 1;
    if (entry.version != expected) {
      return parseError(db.path() + ": " + toString(id) + ": journal jumps from version " +
                        std::to_string(expected - 1) + " to " + std::to_string(entry.version));
    }
    document.entries.push_back(std::move(entry));
  }
  return document;
}

Expected<std::optional<Role>> selectRole(SqliteConnection& db, std::string_view tokenHash, TokenScope scope) {
  // A grant for one document or for all of them; the strongest one wins.
  TESSERA_ASSIGN_OR_RETURN(
      SqliteStatement select,
      db.prepare("SELECT max(role) FROM tokens WHERE token_hash = ?1 AND (scope = ?2 OR scope = 0)"));
  select.bindBlob(1, tokenHash).bindInt(2, sqlScope(scope));
  TESSERA_ASSIGN_OR_RETURN(bool row, select.step());
  if (!row || select.columnIsNull(0)) return std::optional<Role>();
  const int64_t role = select.columnInt(0);
  if (role < static_cast<int64_t>(Role::kViewer) || role > static_cast<int64_t>(Role::kAdmin)) {
    return parseError(db.path() + ": an access token has unknown role " + std::to_string(role));
  }
  return std::optional<Role>(static_cast<Role>(role));
}

Expected<bool> selectTokenKnown(SqliteConnection& db, std::string_view tokenHash) {
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement select,
                           db.prepare("SELECT 1 FROM tokens WHERE token_hash = ?1 LIMIT 1"));
  select.bindBlob(1, tokenHash);
  return select.step();
}

}  // namespace tessera::store
