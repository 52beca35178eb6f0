// Documents and snapshots: round trips, deletion, unknown ids, reopening,
// and calls after close().
#include <gtest/gtest.h>

#include <sqlite3.h>

#include <string>

#include "server/store/sqlite_store.h"
#include "server/store_test_support.h"

namespace tessera::store {
namespace {

using testing::entryBytes;
using testing::openStoreOrFail;
using testing::TempDataDir;

const std::string kBase = std::string("base\0mesh\xff bytes", 16);

TEST(StoreDocuments, CreateListLoadRoundTrip) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);

  auto first = store->createDocument("bracket", kBase);
  auto second = store->createDocument("empty base", "");
  ASSERT_TRUE(first.isOk()) << first.status().toString();
  ASSERT_TRUE(second.isOk()) << second.status().toString();
  EXPECT_LT(first->value, second->value);

  auto list = store->listDocuments();
  ASSERT_TRUE(list.isOk()) << list.status().toString();
  ASSERT_EQ(list->size(), 2u);
  EXPECT_EQ((*list)[0].id, *first);
  EXPECT_EQ((*list)[0].name, "bracket");
  EXPECT_EQ((*list)[0].latestVersion, 0u);
  EXPECT_EQ((*list)[1].id, *second);

  auto loaded = store->loadDocument(*first);
  ASSERT_TRUE(loaded.isOk()) << loaded.status().toString();
  EXPECT_EQ(loaded->id, *first);
  EXPECT_EQ(loaded->name, "bracket");
  EXPECT_EQ(loaded->baseBytes, kBase);
  EXPECT_FALSE(loaded->snapshot.has_value());
  EXPECT_TRUE(loaded->entries.empty());
  EXPECT_EQ(loaded->latestVersion(), 0u);

  auto empty = store->loadDocument(*second);
  ASSERT_TRUE(empty.isOk()) << empty.status().toString();
  EXPECT_EQ(empty->baseBytes, "");
}

TEST(StoreDocuments, RejectsBadNames) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  EXPECT_EQ(store->createDocument("", kBase).status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(store->createDocument(std::string(kMaxDocumentNameBytes + 1, 'n'), kBase).status().code(),
            ErrorCode::kInvalidArgument);
  EXPECT_TRUE(store->createDocument(std::string(kMaxDocumentNameBytes, 'n'), kBase).isOk());
}

TEST(StoreDocuments, UnknownIdsAreNotFoundAndNamed) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store->createDocument("one", kBase).isOk());

  for (DocumentId id : {DocumentId{42}, DocumentId{0}, DocumentId{~uint64_t{0}}}) {
    const std::string name = toString(id);
    auto loaded = store->loadDocument(id);
    EXPECT_EQ(loaded.status().code(), ErrorCode::kNotFound);
    EXPECT_NE(loaded.status().message().find(name), std::string::npos) << loaded.status().message();
    Status deleted = store->deleteDocument(id);
    EXPECT_EQ(deleted.code(), ErrorCode::kNotFound);
    EXPECT_NE(deleted.message().find(name), std::string::npos) << deleted.message();
    Status appended = store->appendSync(id, 1, "a", "x");
    EXPECT_EQ(appended.code(), ErrorCode::kNotFound);
    EXPECT_NE(appended.message().find(name), std::string::npos) << appended.message();
    EXPECT_EQ(store->putSnapshot(id, 1, "s").code(), ErrorCode::kNotFound);
    EXPECT_EQ(store->addToken(TokenScope::document(id), "0123456789abcdef0123", Role::kViewer).code(),
              ErrorCode::kNotFound);
  }
}

TEST(StoreDocuments, DeleteRemovesJournalSnapshotsAndTokensAndNeverReusesIds) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto keep = store->createDocument("keep", kBase);
  auto doomed = store->createDocument("doomed", kBase);
  ASSERT_TRUE(keep.isOk() && doomed.isOk());
  const std::string token = "doomed-document-editor-token";
  for (uint64_t v = 1; v <= 3; ++v) {
    ASSERT_TRUE(store->appendSync(*doomed, v, "a", entryBytes(v)).isOk());
    ASSERT_TRUE(store->appendSync(*keep, v, "a", entryBytes(v)).isOk());
  }
  ASSERT_TRUE(store->putSnapshot(*doomed, 2, "snapshot").isOk());
  ASSERT_TRUE(store->addToken(TokenScope::document(*doomed), token, Role::kEditor).isOk());

  ASSERT_TRUE(store->deleteDocument(*doomed).isOk());
  EXPECT_EQ(store->loadDocument(*doomed).status().code(), ErrorCode::kNotFound);
  EXPECT_EQ(store->deleteDocument(*doomed).code(), ErrorCode::kNotFound);
  EXPECT_EQ(store->roleFor(token, TokenScope::document(*doomed)).status().code(), ErrorCode::kNotFound);
  auto list = store->listDocuments();
  ASSERT_TRUE(list.isOk());
  ASSERT_EQ(list->size(), 1u);
  EXPECT_EQ((*list)[0].id, *keep);
  EXPECT_EQ((*list)[0].latestVersion, 3u);

  // A stale id held by a client must never name a newer document.
  auto next = store->createDocument("next", kBase);
  ASSERT_TRUE(next.isOk());
  EXPECT_GT(next->value, doomed->value);
  store->close();

  // Nothing of the deleted document is left in any table.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(dir.file("tessera.db").c_str(), &db), SQLITE_OK);
  for (const char* sql : {"SELECT count(*) FROM journal WHERE document_id = ?1",
                          "SELECT count(*) FROM snapshots WHERE document_id = ?1",
                          "SELECT count(*) FROM tokens WHERE scope = ?1"}) {
    sqlite3_stmt* statement = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, sql, -1, &statement, nullptr), SQLITE_OK) << sql;
    sqlite3_bind_int64(statement, 1, static_cast<int64_t>(doomed->value));
    ASSERT_EQ(sqlite3_step(statement), SQLITE_ROW);
    EXPECT_EQ(sqlite3_column_int64(statement, 0), 0) << sql;
    sqlite3_finalize(statement);
  }
  sqlite3_close(db);
}

TEST(StoreDocuments, ReopenAfterCloseKeepsEverything) {
  TempDataDir dir;
  DocumentId id;
  const std::string token = "an-admin-token-for-everything";
  {
    auto store = openStoreOrFail(dir.path());
    ASSERT_NE(store, nullptr);
    auto created = store->createDocument("persistent", kBase);
    ASSERT_TRUE(created.isOk());
    id = *created;
    for (uint64_t v = 1; v <= 7; ++v)
      ASSERT_TRUE(store->appendSync(id, v, "author" + std::to_string(v), entryBytes(v)).isOk());
    ASSERT_TRUE(store->putSnapshot(id, 5, "state at 5").isOk());
    ASSERT_TRUE(store->addToken(TokenScope::allDocuments(), token, Role::kAdmin).isOk());
    store->close();
  }
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto list = store->listDocuments();
  ASSERT_TRUE(list.isOk());
  ASSERT_EQ(list->size(), 1u);
  EXPECT_EQ((*list)[0].name, "persistent");
  EXPECT_EQ((*list)[0].latestVersion, 7u);

  auto loaded = store->loadDocument(id);
  ASSERT_TRUE(loaded.isOk()) << loaded.status().toString();
  EXPECT_EQ(loaded->baseBytes, kBase);
  ASSERT_TRUE(loaded->snapshot.has_value());
  EXPECT_EQ(loaded->snapshot->version, 5u);
  EXPECT_EQ(loaded->snapshot->bytes, "state at 5");
  ASSERT_EQ(loaded->entries.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const uint64_t v = 6 + i;
    EXPECT_EQ(loaded->entries[i].version, v);
    EXPECT_EQ(loaded->entries[i].author, "author" + std::to_string(v));
    EXPECT_EQ(loaded->entries[i].bytes, entryBytes(v));
  }
  EXPECT_EQ(loaded->latestVersion(), 7u);

  auto role = store->roleFor(token, TokenScope::document(id));
  ASSERT_TRUE(role.isOk()) << role.status().toString();
  EXPECT_EQ(*role, Role::kAdmin);
  // The journal continues where it stopped.
  EXPECT_TRUE(store->appendSync(id, 8, "a", entryBytes(8)).isOk());
  EXPECT_EQ(store->appendSync(id, 8, "a", entryBytes(8)).code(), ErrorCode::kInvalidArgument);
}

TEST(StoreDocuments, CallsAfterCloseFailCleanly) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto id = store->createDocument("doc", kBase);
  ASSERT_TRUE(id.isOk());
  store->close();
  store->close();  // idempotent

  EXPECT_EQ(store->listDocuments().status().code(), ErrorCode::kIoError);
  EXPECT_EQ(store->loadDocument(*id).status().code(), ErrorCode::kIoError);
  EXPECT_EQ(store->createDocument("late", kBase).status().code(), ErrorCode::kIoError);
  EXPECT_EQ(store->appendSync(*id, 1, "a", "x").code(), ErrorCode::kIoError);
  int calls = 0;
  store->append(*id, 1, "a", "x", [&](Status status) {
    ++calls;
    EXPECT_EQ(status.code(), ErrorCode::kIoError);
  });
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(store->roleFor("some-token-that-is-long", TokenScope::allDocuments()).status().code(),
            ErrorCode::kIoError);
}

TEST(StoreSnapshots, LoadStartsFromTheNewestAndTwoAreKept) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto id = store->createDocument("snapshots", kBase);
  ASSERT_TRUE(id.isOk());
  for (uint64_t v = 1; v <= 10; ++v) ASSERT_TRUE(store->appendSync(*id, v, "a", entryBytes(v)).isOk());

  EXPECT_EQ(store->putSnapshot(*id, 11, "future").code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(store->putSnapshot(*id, 0, "zero").code(), ErrorCode::kInvalidArgument);
  for (uint64_t v : {3u, 9u, 6u}) {
    ASSERT_TRUE(store->putSnapshot(*id, v, "state " + std::to_string(v)).isOk());
  }
  ASSERT_TRUE(store->putSnapshot(*id, 9, "state 9, again").isOk());  // replaces

  auto loaded = store->loadDocument(*id);
  ASSERT_TRUE(loaded.isOk()) << loaded.status().toString();
  ASSERT_TRUE(loaded->snapshot.has_value());
  EXPECT_EQ(loaded->snapshot->version, 9u);
  EXPECT_EQ(loaded->snapshot->bytes, "state 9, again");
  ASSERT_EQ(loaded->entries.size(), 1u);
  EXPECT_EQ(loaded->entries[0].version, 10u);
  EXPECT_EQ(loaded->latestVersion(), 10u);
  store->close();

  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(dir.file("tessera.db").c_str(), &db), SQLITE_OK);
  sqlite3_stmt* statement = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(
                db, "SELECT group_concat(version) FROM (SELECT version FROM snapshots ORDER BY version)", -1,
                &statement, nullptr),
            SQLITE_OK);
  ASSERT_EQ(sqlite3_step(statement), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(statement, 0)), "6,9");
  sqlite3_finalize(statement);
  sqlite3_close(db);
}

}  // namespace
}  // namespace tessera::store
