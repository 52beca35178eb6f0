// SqliteStore: the embedded default Store, one SQLite file per data directory.
//
//   <dataDirectory>/tessera.db      the database (WAL journaling)
//   <dataDirectory>/tessera.db-wal  committed writes not yet checkpointed
//   <dataDirectory>/tessera.lock    held while a store has the directory open
//
// Durability: synchronous = FULL in WAL mode fsyncs the WAL at every commit,
// so an acknowledged write survives kill -9 and, as far as the disk honours
// fsync, power loss. All writes go through one writer thread that commits
// whatever is queued in one transaction (group commit, see group_commit.h);
// reads use a second connection, which WAL lets run beside the writer.
//
// Thread-safe: every method may be called from any thread, except that a
// callback (which runs on the writer thread) must not call a synchronous
// method, close() or the destructor.
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "core/util/status.h"
#include "server/store/data_directory.h"
#include "server/store/group_commit.h"
#include "server/store/sqlite_connection.h"
#include "server/store/store.h"
#include "server/store/store_checks.h"

namespace tessera::store {

struct SqliteStoreOptions {
  int busyTimeoutMs = 5000;      // waits for another connection's lock (e.g. an admin's sqlite3 shell)
  size_t maxBatchWrites = 4096;  // 1: one transaction per write (no group commit)
  bool verifyOnOpen = true;      // PRAGMA quick_check on open: reads the whole file
};

class SqliteStore final : public Store {
 public:
  // Creates the directory and an empty store if needed. Refuses (naming the
  // path) a file that is not a Tessera store, is damaged, or comes from a
  // newer Tessera, and a directory another store has open.
  static Expected<std::unique_ptr<SqliteStore>> open(const std::string& dataDirectory,
                                                     const SqliteStoreOptions& options = {});
  ~SqliteStore() override;

  Expected<DocumentId> createDocument(std::string_view name, std::string_view baseBytes) override;
  Expected<std::vector<DocumentSummary>> listDocuments() override;
  Status deleteDocument(DocumentId id) override;
  Expected<StoredDocument> loadDocument(DocumentId id) override;

  void append(DocumentId id, uint64_t version, std::string author, std::string bytes,
              AppendCallback done) override;
  Status appendSync(DocumentId id, uint64_t version, std::string author, std::string bytes) override;

  Status putSnapshot(DocumentId id, uint64_t version, std::string_view bytes) override;

  Status addToken(TokenScope scope, std::string_view token, Role role) override;
  Status revokeToken(std::string_view token) override;
  Expected<Role> roleFor(std::string_view token, TokenScope scope) override;
  Expected<bool> knowsToken(std::string_view token) override;

  StoreStats stats() const override;
  Durability durability() const override;
  void close() override;

  const std::string& databasePath() const { return databasePath_; }

 private:
  SqliteStore(std::string databasePath, DataDirectoryLock lock,
              std::unique_ptr<SqliteConnection> writeConnection,
              std::unique_ptr<SqliteConnection> readConnection, const SqliteStoreOptions& options);

  // Queues `apply` for the writer and waits until it is durable or refused.
  Status writeAndWait(std::function<Status(SqliteConnection&)> apply);
  // Runs `read` in one read transaction on the read connection.
  template <typename T>
  Expected<T> readConsistent(const std::function<Expected<T>(SqliteConnection&)>& read);

  Status closedError() const;

  const std::string databasePath_;
  DataDirectoryLock lock_;
  std::unique_ptr<SqliteConnection> writeConnection_;  // used only by writer_'s thread
  std::unique_ptr<GroupCommitWriter> writer_;

  std::mutex readMutex_;
  std::unique_ptr<SqliteConnection> readConnection_;  // null once closed
};

}  // namespace tessera::store
