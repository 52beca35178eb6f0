#include "server/store/sqlite_store.h"

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <future>
#include <limits>
#include <utility>

#include "server/store/sqlite_queries.h"
#include "server/store/sqlite_schema.h"
#include "server/store/store_checks.h"
#include "server/store/token_hash.h"

namespace tessera::store {
namespace {

Status openConnection(const std::string& path, const SqliteStoreOptions& options,
                      std::unique_ptr<SqliteConnection>& connection) {
  TESSERA_ASSIGN_OR_RETURN(connection, SqliteConnection::open(path));
  return connection->setBusyTimeout(options.busyTimeoutMs);
}

}  // namespace

Expected<std::unique_ptr<SqliteStore>> SqliteStore::open(const std::string& dataDirectory,
                                                         const SqliteStoreOptions& options) {
  TESSERA_ASSIGN_OR_RETURN(DataDirectoryLock lock, DataDirectoryLock::acquire(dataDirectory));
  const std::string path = (std::filesystem::path(dataDirectory) / "tessera.db").lexically_normal().string();

  std::unique_ptr<SqliteConnection> writeConnection;
  TESSERA_RETURN_IF_ERROR(openConnection(path, options, writeConnection));
  TESSERA_RETURN_IF_ERROR(prepareSchema(*writeConnection, SchemaOptions{options.verifyOnOpen}));
  // FULL, not WAL's usual NORMAL: NORMAL syncs only at checkpoints, so a
  // power loss could drop commits that were already acknowledged.
  TESSERA_RETURN_IF_ERROR(writeConnection->exec("PRAGMA synchronous = FULL"));
  TESSERA_ASSIGN_OR_RETURN(int64_t synchronous, writeConnection->queryInt("PRAGMA synchronous"));
  if (synchronous != 2)
    return internalError(path + ": PRAGMA synchronous is " + std::to_string(synchronous) + ", not FULL");

  std::unique_ptr<SqliteConnection> readConnection;
  TESSERA_RETURN_IF_ERROR(openConnection(path, options, readConnection));
  // Belt and braces: every write must go through the writer's transactions.
  TESSERA_RETURN_IF_ERROR(readConnection->exec("PRAGMA query_only = ON"));

  return std::unique_ptr<SqliteStore>(
      new SqliteStore(path, std::move(lock), std::move(writeConnection), std::move(readConnection), options));
}

SqliteStore::SqliteStore(std::string databasePath, DataDirectoryLock lock,
                         std::unique_ptr<SqliteConnection> writeConnection,
                         std::unique_ptr<SqliteConnection> readConnection, const SqliteStoreOptions& options)
    : databasePath_(std::move(databasePath)),
      lock_(std::move(lock)),
      writeConnection_(std::move(writeConnection)),
      writer_(
          std::make_unique<GroupCommitWriter>(*writeConnection_, GroupCommitOptions{options.maxBatchWrites})),
      readConnection_(std::move(readConnection)) {}

SqliteStore::~SqliteStore() {
  close();
}

void SqliteStore::close() {
  writer_->stop();
  if (writer_->onWriterThread()) return;  // from a callback: cannot join ourselves (see header)
  std::lock_guard<std::mutex> lock(readMutex_);
  if (!readConnection_ && !writeConnection_) return;
  // The writer is joined, so nothing uses its connection any more. Closing it
  // last lets SQLite checkpoint the WAL into tessera.db and remove the WAL;
  // only then may another process take the directory.
  readConnection_.reset();
  writeConnection_.reset();
  lock_.release();
}

Status SqliteStore::closedError() const {
  return ioError(databasePath_ + ": the store is closed");
}

Status SqliteStore::writeAndWait(std::function<Status(SqliteConnection&)> apply) {
  if (writer_->onWriterThread()) {
    return internalError(databasePath_ +
                         ": a synchronous store call from a store callback would wait for itself");
  }
  // Shared, so the promise outlives set_value even if the waiter returns first.
  auto promise = std::make_shared<std::promise<Status>>();
  std::future<Status> result = promise->get_future();
  writer_->submit(PendingWrite{std::move(apply),
                               [promise](Status status) { promise->set_value(std::move(status)); },
                               /*isJournalEntry=*/false});
  return result.get();
}

template <typename T>
Expected<T> SqliteStore::readConsistent(const std::function<Expected<T>(SqliteConnection&)>& read) {
  std::lock_guard<std::mutex> lock(readMutex_);
  if (!readConnection_) return closedError();
  // One read transaction: every statement sees the same commit.
  TESSERA_RETURN_IF_ERROR(readConnection_->exec("BEGIN"));
  Expected<T> result = read(*readConnection_);
  Status end = readConnection_->exec("COMMIT");
  // A read transaction left open would make every later BEGIN fail.
  if (!end.isOk() && readConnection_->inTransaction()) (void)readConnection_->exec("ROLLBACK");
  if (!result.isOk()) return result;
  TESSERA_RETURN_IF_ERROR(end);
  return result;
}

Expected<DocumentId> SqliteStore::createDocument(std::string_view name, std::string_view baseBytes) {
  TESSERA_RETURN_IF_ERROR(checkDocumentName(name));
  DocumentId id;
  TESSERA_RETURN_IF_ERROR(writeAndWait([&](SqliteConnection& db) -> Status {
    TESSERA_ASSIGN_OR_RETURN(id, insertDocument(db, name, baseBytes));
    return Status::ok();
  }));
  return id;
}

Expected<std::vector<DocumentSummary>> SqliteStore::listDocuments() {
  return readConsistent<std::vector<DocumentSummary>>(selectDocuments);
}

Status SqliteStore::deleteDocument(DocumentId id) {
  TESSERA_RETURN_IF_ERROR(checkDocumentId(id));
  return writeAndWait([id](SqliteConnection& db) { return deleteDocumentRows(db, id); });
}

Expected<StoredDocument> SqliteStore::loadDocument(DocumentId id) {
  TESSERA_RETURN_IF_ERROR(checkDocumentId(id));
  return readConsistent<StoredDocument>([id](SqliteConnection& db) { return selectDocument(db, id); });
}

void SqliteStore::append(DocumentId id, uint64_t version, std::string author, std::string bytes,
                         AppendCallback done) {
  // Invalid arguments are refused by the writer too, so that `done` always
  // runs on the writer thread while the store is open.
  Status valid = checkDocumentId(id);
  if (valid.isOk()) valid = checkVersion(id, version, "journal entry");
  if (valid.isOk()) valid = checkAuthor(id, author);
  PendingWrite write;
  write.apply = [id, version, valid = std::move(valid), author = std::move(author),
                 bytes = std::move(bytes)](SqliteConnection& db) -> Status {
    TESSERA_RETURN_IF_ERROR(valid);
    return insertJournalEntry(db, id, version, author, bytes);
  };
  write.done = std::move(done);
  write.isJournalEntry = true;
  writer_->submit(std::move(write));
}

Status SqliteStore::appendSync(DocumentId id, uint64_t version, std::string author, std::string bytes) {
  if (writer_->onWriterThread()) {
    return internalError(databasePath_ +
                         ": a synchronous store call from a store callback would wait for itself");
  }
  auto promise = std::make_shared<std::promise<Status>>();
  std::future<Status> result = promise->get_future();
  append(id, version, std::move(author), std::move(bytes),
         [promise](Status status) { promise->set_value(std::move(status)); });
  return result.get();
}

Status SqliteStore::putSnapshot(DocumentId id, uint64_t version, std::string_view bytes) {
  TESSERA_RETURN_IF_ERROR(checkDocumentId(id));
  TESSERA_RETURN_IF_ERROR(checkVersion(id, version, "snapshot"));
  return writeAndWait([&](SqliteConnection& db) { return insertSnapshot(db, id, version, bytes); });
}

Status SqliteStore::addToken(TokenScope scope, std::string_view token, Role role) {
  if (!scope.isAllDocuments()) TESSERA_RETURN_IF_ERROR(checkDocumentId(scope.documentId()));
  TESSERA_RETURN_IF_ERROR(checkTokenToGrant(token));
  TESSERA_RETURN_IF_ERROR(checkRole(role));
  TESSERA_ASSIGN_OR_RETURN(std::string hash, hashToken(token));
  return writeAndWait([&](SqliteConnection& db) { return insertToken(db, scope, hash, role); });
}

Status SqliteStore::revokeToken(std::string_view token) {
  TESSERA_ASSIGN_OR_RETURN(std::string hash, hashToken(token));
  return writeAndWait([&](SqliteConnection& db) { return deleteToken(db, hash); });
}

Expected<Role> SqliteStore::roleFor(std::string_view token, TokenScope scope) {
  const Status refused = notFound("access token not valid for " + scope.toString());
  if (token.empty()) return notFound("no access token given");
  // Nothing this long was ever granted; skip hashing attacker-sized input.
  if (token.size() > kMaxTokenBytes) return refused;
  TESSERA_ASSIGN_OR_RETURN(std::string hash, hashToken(token));
  TESSERA_ASSIGN_OR_RETURN(
      std::optional<Role> role,
      readConsistent<std::optional<Role>>([&](SqliteConnection& db) { return selectRole(db, hash, scope); }));
  if (!role) return refused;
  return *role;
}

Expected<bool> SqliteStore::knowsToken(std::string_view token) {
  if (token.empty() || token.size() > kMaxTokenBytes) return false;
  TESSERA_ASSIGN_OR_RETURN(std::string hash, hashToken(token));
  return readConsistent<bool>([&](SqliteConnection& db) { return selectTokenKnown(db, hash); });
}

StoreStats SqliteStore::stats() const {
  return writer_->stats();
}

Durability SqliteStore::durability() const {
  return {"sqlite", sqlite3_libversion(), WriteSync::kEachWrite,
          "each acknowledged edit was fsynced to this machine's disk before its acknowledgement"};
}

}  // namespace tessera::store
