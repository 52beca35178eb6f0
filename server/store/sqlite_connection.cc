#include "server/store/sqlite_connection.h"

#include <sqlite3.h>

#include <utility>

namespace tessera::store {
namespace {

// Statement text in messages: enough to recognise it, never a bound value
// (tokens and payloads are always bound, never spliced into SQL).
std::string shortSql(const char* sql) {
  std::string text = sql == nullptr ? std::string("statement") : std::string(sql);
  constexpr size_t kMaxChars = 60;
  if (text.size() > kMaxChars) text = text.substr(0, kMaxChars) + "...";
  return text;
}

}  // namespace

SqliteStatement::SqliteStatement(SqliteStatement&& other) noexcept
    : connection_(other.connection_),
      statement_(std::exchange(other.statement_, nullptr)),
      bindResult_(other.bindResult_) {}

SqliteStatement::~SqliteStatement() {
  if (statement_ == nullptr) return;
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

SqliteStatement& SqliteStatement::bindInt(int index, int64_t value) {
  const int result = sqlite3_bind_int64(statement_, index, value);
  if (bindResult_ == SQLITE_OK) bindResult_ = result;
  return *this;
}

SqliteStatement& SqliteStatement::bindText(int index, std::string_view text) {
  // An empty view may carry a null pointer, which SQLite would bind as NULL.
  const char* data = text.empty() ? "" : text.data();
  const int result = sqlite3_bind_text64(statement_, index, data, text.size(), SQLITE_TRANSIENT, SQLITE_UTF8);
  if (bindResult_ == SQLITE_OK) bindResult_ = result;
  return *this;
}

SqliteStatement& SqliteStatement::bindBlob(int index, std::string_view bytes) {
  const int result =
      bytes.empty() ? sqlite3_bind_zeroblob(statement_, index, 0)
                    : sqlite3_bind_blob64(statement_, index, bytes.data(), bytes.size(), SQLITE_TRANSIENT);
  if (bindResult_ == SQLITE_OK) bindResult_ = result;
  return *this;
}

Expected<bool> SqliteStatement::step() {
  if (bindResult_ != SQLITE_OK) {
    return connection_->error(bindResult_, "binding " + shortSql(sqlite3_sql(statement_)));
  }
  const int result = sqlite3_step(statement_);
  if (result == SQLITE_ROW) return true;
  if (result == SQLITE_DONE) return false;
  return connection_->error(result, shortSql(sqlite3_sql(statement_)));
}

Status SqliteStatement::run() {
  while (true) {
    TESSERA_ASSIGN_OR_RETURN(bool row, step());
    if (!row) return Status::ok();
  }
}

bool SqliteStatement::columnIsNull(int column) const {
  return sqlite3_column_type(statement_, column) == SQLITE_NULL;
}

int64_t SqliteStatement::columnInt(int column) const {
  return sqlite3_column_int64(statement_, column);
}

std::string SqliteStatement::columnText(int column) const {
  const unsigned char* text = sqlite3_column_text(statement_, column);
  const int size = sqlite3_column_bytes(statement_, column);
  return text == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(text), size);
}

std::string SqliteStatement::columnBlob(int column) const {
  const void* bytes = sqlite3_column_blob(statement_, column);
  const int size = sqlite3_column_bytes(statement_, column);
  return bytes == nullptr ? std::string() : std::string(static_cast<const char*>(bytes), size);
}

Expected<std::unique_ptr<SqliteConnection>> SqliteConnection::open(const std::string& path) {
  sqlite3* db = nullptr;
  // NOMUTEX: each connection is used by one thread at a time (see header).
  const int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX;
  const int result = sqlite3_open_v2(path.c_str(), &db, flags, nullptr);
  if (result != SQLITE_OK) {
    std::string message = db != nullptr ? sqlite3_errmsg(db) : sqlite3_errstr(result);
    sqlite3_close(db);
    return ioError(path + ": cannot open: " + message);
  }
  sqlite3_extended_result_codes(db, 1);
  return std::unique_ptr<SqliteConnection>(new SqliteConnection(db, path));
}

SqliteConnection::~SqliteConnection() {
  for (auto& [sql, statement] : statements_) sqlite3_finalize(statement);
  // The last connection to close checkpoints the WAL into the main file.
  sqlite3_close(db_);
}

Status SqliteConnection::backupInto(const std::string& destination) {
  sqlite3* target = nullptr;
  int result =
      sqlite3_open_v2(destination.c_str(), &target, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  if (result != SQLITE_OK) {
    std::string message = target != nullptr ? sqlite3_errmsg(target) : sqlite3_errstr(result);
    sqlite3_close(target);
    return ioError(destination + ": cannot create the backup file: " + message);
  }
  sqlite3_backup* backup = sqlite3_backup_init(target, "main", db_, "main");
  if (backup == nullptr) {
    std::string message = sqlite3_errmsg(target);
    sqlite3_close(target);
    return ioError(destination + ": cannot start the backup of " + path_ + ": " + message);
  }
  // All pages in one step: the copy is one read transaction on the source,
  // so it is consistent even while a server commits (WAL readers never
  // block writers, and the copy never restarts).
  result = sqlite3_backup_step(backup, -1);
  sqlite3_backup_finish(backup);
  const int closed = sqlite3_close(target);
  if (result != SQLITE_DONE) return error(result, "backing up into " + destination);
  if (closed != SQLITE_OK)
    return ioError(destination + ": cannot close the backup file: " + sqlite3_errstr(closed));
  return Status::ok();
}

Status SqliteConnection::exec(const std::string& sql) {
  const int result = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr);
  if (result != SQLITE_OK) return error(result, shortSql(sql.c_str()));
  return Status::ok();
}

Expected<SqliteStatement> SqliteConnection::prepare(const std::string& sql) {
  auto found = statements_.find(sql);
  if (found == statements_.end()) {
    sqlite3_stmt* statement = nullptr;
    const int result = sqlite3_prepare_v3(db_, sql.c_str(), static_cast<int>(sql.size()),
                                          SQLITE_PREPARE_PERSISTENT, &statement, nullptr);
    if (result != SQLITE_OK) return error(result, "preparing " + shortSql(sql.c_str()));
    found = statements_.emplace(sql, statement).first;
  }
  return SqliteStatement(*this, found->second);
}

Expected<int64_t> SqliteConnection::queryInt(const std::string& sql) {
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement statement, prepare(sql));
  TESSERA_ASSIGN_OR_RETURN(bool row, statement.step());
  if (!row) return internalError(path_ + ": " + shortSql(sql.c_str()) + ": returned no row");
  return statement.columnInt(0);
}

Expected<std::string> SqliteConnection::queryText(const std::string& sql) {
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement statement, prepare(sql));
  TESSERA_ASSIGN_OR_RETURN(bool row, statement.step());
  if (!row) return internalError(path_ + ": " + shortSql(sql.c_str()) + ": returned no row");
  return statement.columnText(0);
}

int64_t SqliteConnection::lastInsertRowid() const {
  return sqlite3_last_insert_rowid(db_);
}

int64_t SqliteConnection::changes() const {
  return sqlite3_changes64(db_);
}

bool SqliteConnection::inTransaction() const {
  return sqlite3_get_autocommit(db_) == 0;
}

Status SqliteConnection::setBusyTimeout(int milliseconds) {
  const int result = sqlite3_busy_timeout(db_, milliseconds);
  if (result != SQLITE_OK) return error(result, "setting the busy timeout");
  return Status::ok();
}

Status SqliteConnection::error(int code, std::string_view what) const {
  // The connection's message describes its most recent failure, which is this
  // one when called right after it; the code's generic text is the fallback.
  const char* detail = sqlite3_errcode(db_) == code ? sqlite3_errmsg(db_) : sqlite3_errstr(code);
  // The reason first; the statement last, as context for whoever debugs it.
  std::string message = path_ + ": " + detail;
  const std::string context = " (" + std::string(what) + ")";
  switch (code & 0xff) {
    case SQLITE_NOTADB:
    case SQLITE_CORRUPT:
      return parseError(message + "; not a healthy SQLite database, restore it from a backup" + context);
    case SQLITE_IOERR:
    case SQLITE_FULL:
    case SQLITE_CANTOPEN:
    case SQLITE_READONLY:
    case SQLITE_PERM:
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
    case SQLITE_PROTOCOL:
    case SQLITE_NOLFS:
      return ioError(message + context);
    case SQLITE_TOOBIG:
      return invalidArgument(message + context);
    default:
      return internalError(message + context);
  }
}

}  // namespace tessera::store
