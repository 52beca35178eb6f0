// Opening: the directory and file are created and configured (WAL, FULL
// sync, schema version); random bytes, damaged files, other programs'
// databases and newer schemas are refused with an error naming the path,
// without touching the file; a directory is used by one store at a time.
#include <gtest/gtest.h>

#include <sqlite3.h>

#include <filesystem>
#include <random>
#include <string>

#include "server/store/sqlite_schema.h"
#include "server/store/sqlite_store.h"
#include "server/store_test_support.h"

namespace tessera::store {
namespace {

using testing::entryBytes;
using testing::openStoreOrFail;
using testing::readFileBytes;
using testing::TempDataDir;
using testing::writeFileBytes;

// Runs SQL on a file with SQLite directly, as another program would.
void rawExec(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK) << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

std::string rawQueryText(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) return "cannot open";
  sqlite3_stmt* statement = nullptr;
  std::string result = "no row";
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr) == SQLITE_OK &&
      sqlite3_step(statement) == SQLITE_ROW) {
    result = reinterpret_cast<const char*>(sqlite3_column_text(statement, 0));
  }
  sqlite3_finalize(statement);
  sqlite3_close(db);
  return result;
}

std::string randomBytes(size_t size, uint32_t seed) {
  std::mt19937 random(seed);
  std::string bytes(size, '\0');
  for (char& byte : bytes) byte = static_cast<char>(random() & 0xff);
  return bytes;
}

// Expects open() to fail with `code`, a message naming the database file,
// and the file left byte for byte as it was.
void expectRefused(const TempDataDir& dir, ErrorCode code, const std::string& why) {
  const std::string path = dir.file("tessera.db");
  const std::string before = readFileBytes(path);
  auto store = SqliteStore::open(dir.path());
  ASSERT_FALSE(store.isOk()) << "opened " << why;
  EXPECT_EQ(store.status().code(), code) << store.status().toString();
  EXPECT_NE(store.status().message().find(path), std::string::npos) << store.status().message();
  EXPECT_EQ(readFileBytes(path), before) << "open() changed a file it refused";
  std::printf("[ refused %s ] %s\n", why.c_str(), store.status().toString().c_str());
}

TEST(StoreOpen, CreatesTheDirectoryWithWalFullSyncAndSchemaVersion) {
  TempDataDir parent;
  const std::string directory = parent.path() + "/nested/data";
  auto store = openStoreOrFail(directory);
  ASSERT_NE(store, nullptr);
  EXPECT_TRUE(std::filesystem::is_directory(directory));
  EXPECT_EQ(store->databasePath(), directory + "/tessera.db");
  // Owner-only: the directory holds documents and token hashes.
  const auto permissions = std::filesystem::status(directory).permissions();
  EXPECT_EQ(permissions & std::filesystem::perms::others_all, std::filesystem::perms::none);

  const std::string path = store->databasePath();
  EXPECT_EQ(rawQueryText(path, "PRAGMA journal_mode"), "wal");
  EXPECT_EQ(rawQueryText(path, "PRAGMA user_version"), std::to_string(kStoreSchemaVersion));
  EXPECT_EQ(rawQueryText(path, "PRAGMA application_id"), std::to_string(kStoreApplicationId));
}

TEST(StoreOpen, ADirectoryIsUsedByOneStoreAtATime) {
  TempDataDir dir;
  auto first = openStoreOrFail(dir.path());
  ASSERT_NE(first, nullptr);
  auto second = SqliteStore::open(dir.path());
  ASSERT_FALSE(second.isOk());
  EXPECT_EQ(second.status().code(), ErrorCode::kIoError);
  EXPECT_NE(second.status().message().find("in use"), std::string::npos) << second.status().message();
  first->close();
  EXPECT_NE(openStoreOrFail(dir.path()), nullptr);
}

TEST(StoreOpen, ADataDirectoryPathThatIsAFileIsRefused) {
  TempDataDir dir;
  writeFileBytes(dir.file("plain-file"), "not a directory");
  auto store = SqliteStore::open(dir.file("plain-file"));
  ASSERT_FALSE(store.isOk());
  EXPECT_EQ(store.status().code(), ErrorCode::kIoError);
  EXPECT_NE(store.status().message().find(dir.file("plain-file")), std::string::npos);
}

TEST(StoreOpen, AnEmptyFileIsMigrated) {
  TempDataDir dir;
  writeFileBytes(dir.file("tessera.db"), "");
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  EXPECT_TRUE(store->createDocument("fresh", "base").isOk());
}

TEST(StoreOpen, RandomBytesAreRefused) {
  for (size_t size : {size_t{10}, size_t{100}, size_t{4096}, size_t{65536}}) {
    TempDataDir dir;
    writeFileBytes(dir.file("tessera.db"), randomBytes(size, static_cast<uint32_t>(size)));
    expectRefused(dir, ErrorCode::kParseError, std::to_string(size) + " random bytes");
  }
}

TEST(StoreOpen, AnotherProgramsDatabaseIsRefused) {
  TempDataDir dir;
  rawExec(dir.file("tessera.db"),
          "CREATE TABLE accounts (id INTEGER PRIMARY KEY, owner TEXT);"
          "INSERT INTO accounts (owner) VALUES ('someone');");
  expectRefused(dir, ErrorCode::kUnsupported, "a foreign schema");
}

TEST(StoreOpen, AForeignApplicationIdIsRefused) {
  TempDataDir dir;
  rawExec(dir.file("tessera.db"), "PRAGMA application_id = 1234; CREATE TABLE documents (x);");
  expectRefused(dir, ErrorCode::kUnsupported, "a foreign application id");
}

TEST(StoreOpen, ANewerSchemaVersionIsRefused) {
  TempDataDir dir;
  {
    auto store = openStoreOrFail(dir.path());
    ASSERT_NE(store, nullptr);
    ASSERT_TRUE(store->createDocument("doc", "base").isOk());
  }
  rawExec(dir.file("tessera.db"), "PRAGMA user_version = " + std::to_string(kStoreSchemaVersion + 1));
  expectRefused(dir, ErrorCode::kUnsupported, "a newer schema");
}

TEST(StoreOpen, ATesseraFileWithAMissingTableIsRefused) {
  TempDataDir dir;
  {
    auto store = openStoreOrFail(dir.path());
    ASSERT_NE(store, nullptr);
  }
  rawExec(dir.file("tessera.db"), "DROP TABLE tokens");
  expectRefused(dir, ErrorCode::kParseError, "a missing table");
}

TEST(StoreOpen, DamagedPagesAreRefused) {
  TempDataDir dir;
  {
    auto store = openStoreOrFail(dir.path());
    ASSERT_NE(store, nullptr);
    auto id = store->createDocument("doc", std::string(20000, 'b'));
    ASSERT_TRUE(id.isOk());
    for (uint64_t v = 1; v <= 300; ++v) ASSERT_TRUE(store->appendSync(*id, v, "a", entryBytes(v)).isOk());
  }
  // Keep the 100-byte header (so the file is still recognisably SQLite and
  // Tessera's) and overwrite the rest of the first pages with noise.
  std::string bytes = readFileBytes(dir.file("tessera.db"));
  ASSERT_GT(bytes.size(), 16384u);
  const std::string noise = randomBytes(12000, 7);
  bytes.replace(200, noise.size(), noise);
  writeFileBytes(dir.file("tessera.db"), bytes);
  expectRefused(dir, ErrorCode::kParseError, "damaged pages");
}

TEST(StoreOpen, AJournalGapIsReportedByLoad) {
  TempDataDir dir;
  DocumentId id;
  {
    auto store = openStoreOrFail(dir.path());
    ASSERT_NE(store, nullptr);
    auto created = store->createDocument("doc", "base");
    ASSERT_TRUE(created.isOk());
    id = *created;
    for (uint64_t v = 1; v <= 5; ++v) ASSERT_TRUE(store->appendSync(id, v, "a", "x").isOk());
  }
  rawExec(dir.file("tessera.db"), "DELETE FROM journal WHERE version = 3");
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto loaded = store->loadDocument(id);
  ASSERT_FALSE(loaded.isOk());
  EXPECT_EQ(loaded.status().code(), ErrorCode::kParseError);
  EXPECT_NE(loaded.status().message().find("jumps from version 2 to 4"), std::string::npos)
      << loaded.status().message();
}

}  // namespace
}  // namespace tessera::store
