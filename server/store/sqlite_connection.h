// A thin RAII layer over one SQLite connection: prepared statements cached by
// their SQL text, and SQLite result codes turned into Status values that name
// the database file.
//
// A connection is not shared between threads at the same time: the store
// gives the writer thread one and guards a second one (for reads) by a mutex,
// so SQLite's own per-connection mutex is switched off.
//
//   TESSERA_ASSIGN_OR_RETURN(SqliteStatement select, db.prepare("SELECT name FROM documents WHERE id = ?1"));
//   select.bindInt(1, id);
//   TESSERA_ASSIGN_OR_RETURN(bool row, select.step());
//   if (row) name = select.columnText(0);
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>

#include "core/util/status.h"

struct sqlite3;
struct sqlite3_stmt;

namespace tessera::store {

class SqliteConnection;

// A cached statement on loan: resetting it and clearing its bindings when the
// loan ends keeps a half-stepped statement from holding a read snapshot open.
class SqliteStatement {
 public:
  SqliteStatement(SqliteConnection& connection, sqlite3_stmt* statement)
      : connection_(&connection), statement_(statement) {}
  SqliteStatement(SqliteStatement&& other) noexcept;
  SqliteStatement& operator=(SqliteStatement&&) = delete;
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;
  ~SqliteStatement();

  // Parameters are numbered from 1. Values are copied, so temporaries are
  // fine. A failed bind is reported by the next step().
  SqliteStatement& bindInt(int index, int64_t value);
  SqliteStatement& bindText(int index, std::string_view text);
  SqliteStatement& bindBlob(int index, std::string_view bytes);  // empty stays an empty blob, not NULL

  // True when a result row is ready, false when the statement is done.
  Expected<bool> step();
  // Steps to completion, ignoring rows: for statements that return none.
  Status run();

  bool columnIsNull(int column) const;
  int64_t columnInt(int column) const;
  std::string columnText(int column) const;
  std::string columnBlob(int column) const;

 private:
  SqliteConnection* connection_;
  sqlite3_stmt* statement_;
  int bindResult_ = 0;  // SQLITE_OK
};

class SqliteConnection {
 public:
  // Opens (creating if needed) the database file. Nothing is read yet, so a
  // file that is not a database is only reported by the first statement.
  static Expected<std::unique_ptr<SqliteConnection>> open(const std::string& path);
  ~SqliteConnection();
  SqliteConnection(const SqliteConnection&) = delete;
  SqliteConnection& operator=(const SqliteConnection&) = delete;

  // Runs one or more statements that return no rows (BEGIN, PRAGMA x = y, DDL).
  Status exec(const std::string& sql);
  // The cached prepared statement for `sql`, prepared on first use.
  Expected<SqliteStatement> prepare(const std::string& sql);
  // The first column of the first row of `sql`, e.g. a PRAGMA's value.
  Expected<int64_t> queryInt(const std::string& sql);
  Expected<std::string> queryText(const std::string& sql);

  int64_t lastInsertRowid() const;
  int64_t changes() const;  // rows changed by the last statement
  bool inTransaction() const;
  Status setBusyTimeout(int milliseconds);
  // Copies the whole database, as of one instant, into a new file at
  // `destination` with SQLite's online backup API: other connections (a
  // running server's included) keep reading and writing meanwhile.
  Status backupInto(const std::string& destination);

  // A Status for SQLite result `code`: "<path>: <SQLite's message> (<what>)",
  // with a code that says whether the file, the disk or Tessera is at fault.
  Status error(int code, std::string_view what) const;
  const std::string& path() const { return path_; }

 private:
  SqliteConnection(sqlite3* db, std::string path) : db_(db), path_(std::move(path)) {}

  sqlite3* db_;
  std::string path_;
  std::unordered_map<std::string, sqlite3_stmt*> statements_;  // finalized by the destructor
};

}  // namespace tessera::store
