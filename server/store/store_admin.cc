#include "server/store/store_admin.h"

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "server/store/data_directory.h"
#include "server/store/sqlite_connection.h"
#include "server/store/sqlite_queries.h"
#include "server/store/sqlite_schema.h"
#include "server/store/sqlite_store.h"
#include "server/store/token_hash.h"

namespace tessera::store {

namespace {

namespace fs = std::filesystem;

// A second process waits this long for the server's write transaction.
constexpr int kBusyTimeoutMs = 10'000;

Status syncPath(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), (directory ? O_DIRECTORY : 0) | O_RDONLY | O_CLOEXEC);
  if (fd < 0) return ioError(path + ": cannot open to sync: " + std::strerror(errno));
  const int result = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (result != 0) return ioError(path + ": fsync failed: " + std::strerror(error));
  return Status::ok();
}

std::string parentOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// Opens a store file that must already be a Tessera store; the schema check
// reads headers only (no whole-file integrity pass) unless asked.
Expected<std::unique_ptr<SqliteConnection>> openExisting(const std::string& path, bool verifyIntegrity) {
  TESSERA_ASSIGN_OR_RETURN(auto db, SqliteConnection::open(path));
  TESSERA_RETURN_IF_ERROR(db->setBusyTimeout(kBusyTimeoutMs));
  TESSERA_RETURN_IF_ERROR(prepareSchema(*db, SchemaOptions{verifyIntegrity}));
  return db;
}

}  // namespace

std::string storePath(const std::string& dataDirectory) {
  return (fs::path(dataDirectory) / "tessera.db").lexically_normal().string();
}

Status grantTokenInStore(const std::string& dataDirectory, TokenScope scope, std::string_view token,
                         Role role) {
  const std::string path = storePath(dataDirectory);
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    // No store yet: create it the way the server would (this takes the
    // directory lock, so a server starting at the same moment is refused).
    TESSERA_ASSIGN_OR_RETURN(auto store, SqliteStore::open(dataDirectory));
    TESSERA_RETURN_IF_ERROR(store->addToken(scope, token, role));
    store->close();
    return Status::ok();
  }
  TESSERA_ASSIGN_OR_RETURN(std::string hash, hashToken(token));
  TESSERA_ASSIGN_OR_RETURN(auto db, openExisting(path, false));
  // IMMEDIATE: take the write lock now (waiting for the server's commit),
  // so the document check and the insert see the same state.
  TESSERA_RETURN_IF_ERROR(db->exec("BEGIN IMMEDIATE"));
  Status status = insertToken(*db, scope, hash, role);
  if (status.isOk()) status = db->exec("COMMIT");
  if (!status.isOk() && db->inTransaction()) (void)db->exec("ROLLBACK");
  return status;
}

Status backupStore(const std::string& dataDirectory, const std::string& destination) {
  const std::string path = storePath(dataDirectory);
  std::error_code ec;
  if (!fs::exists(path, ec)) return notFound(path + ": no store to back up (is --data right?)");
  if (fs::exists(destination, ec))
    return invalidArgument(destination + ": exists; the backup never overwrites a file");
  const std::string partial = destination + ".partial";
  fs::remove(partial, ec);
  TESSERA_ASSIGN_OR_RETURN(auto db, openExisting(path, false));
  Status status = db->backupInto(partial);
  if (status.isOk()) {
    // The copy must itself be a healthy store before it takes the name.
    auto check = openExisting(partial, true);
    if (!check.isOk()) status = check.status().withContext("checking the backup");
  }
  if (status.isOk()) status = syncPath(partial, false);
  if (status.isOk() && std::rename(partial.c_str(), destination.c_str()) != 0) {
    status = ioError(destination + ": cannot rename the finished backup into place: " + std::strerror(errno));
  }
  if (status.isOk()) status = syncPath(parentOf(destination), true);
  if (!status.isOk()) {
    fs::remove(partial, ec);
    fs::remove(partial + "-wal", ec);
    fs::remove(partial + "-shm", ec);
  }
  return status;
}

Status restoreStore(const std::string& dataDirectory, const std::string& source) {
  std::error_code ec;
  if (!fs::is_regular_file(source, ec)) return notFound(source + ": no such backup file");
  TESSERA_ASSIGN_OR_RETURN(DataDirectoryLock lock, DataDirectoryLock::acquire(dataDirectory));
  const std::string path = storePath(dataDirectory);
  const std::string incoming = path + ".restore";
  fs::remove(incoming, ec);
  fs::copy_file(source, incoming, ec);
  if (ec) return ioError(source + ": cannot copy into " + incoming + ": " + ec.message());
  {
    // Checks ownership, version and integrity, and migrates an older store.
    auto check = openExisting(incoming, true);
    if (!check.isOk()) {
      fs::remove(incoming, ec);
      return check.status().withContext(source + " is not a usable backup");
    }
  }
  TESSERA_RETURN_IF_ERROR(syncPath(incoming, false));
  if (fs::exists(path, ec)) {
    {
      // Fold the old store's WAL into its file (a crashed server leaves one)
      // so the copy kept aside is complete on its own.
      TESSERA_ASSIGN_OR_RETURN(auto old, SqliteConnection::open(path));
      TESSERA_RETURN_IF_ERROR(old->exec("PRAGMA wal_checkpoint(TRUNCATE)"));
    }
    const std::string aside = path + ".before-restore";
    if (std::rename(path.c_str(), aside.c_str()) != 0) {
      return ioError(path + ": cannot move the current store aside: " + std::strerror(errno));
    }
    fs::remove(path + "-wal", ec);
    fs::remove(path + "-shm", ec);
  }
  if (std::rename(incoming.c_str(), path.c_str()) != 0) {
    return ioError(path + ": cannot move the restored store into place: " + std::strerror(errno));
  }
  return syncPath(parentOf(path), true);
}

}  // namespace tessera::store
