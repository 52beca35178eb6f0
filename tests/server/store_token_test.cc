// Access tokens: roles resolve per document and for all documents, only
// SHA-256 hashes reach the disk, and no error message contains a token.
#include <gtest/gtest.h>

#include <openssl/sha.h>

#include <string>

#include "server/store/sqlite_store.h"
#include "server/store/token_hash.h"
#include "server/store_test_support.h"

namespace tessera::store {
namespace {

using testing::openStoreOrFail;
using testing::readFileBytes;
using testing::TempDataDir;

const std::string kViewerToken = "viewer-token-7f3a9c1e5b2d4f60";
const std::string kEditorToken = "editor-token-0c8e2a4b6d1f3e57";
const std::string kAdminToken = "admin-token-all-documents-9b1d";
const std::string kWrongToken = "wrong-token-that-was-never-granted";

void expectNoToken(const Status& status, const std::string& token) {
  EXPECT_EQ(status.message().find(token), std::string::npos) << "the message echoes the token";
  EXPECT_EQ(status.toString().find(token), std::string::npos);
}

TEST(StoreTokens, HashIsSha256) {
  auto hash = hashToken("abc");
  ASSERT_TRUE(hash.isOk());
  unsigned char expected[SHA256_DIGEST_LENGTH];
  SHA256(reinterpret_cast<const unsigned char*>("abc"), 3, expected);
  EXPECT_EQ(*hash, std::string(reinterpret_cast<const char*>(expected), sizeof expected));
}

// A Hello's token is a failed authentication when no grant of any scope
// names it (docs/PROTOCOL.md §4.1).
TEST(StoreTokens, KnowsTokensGrantedForAnyScopeOnly) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto one = store->createDocument("one", "base");
  ASSERT_TRUE(one.isOk());
  ASSERT_TRUE(store->addToken(TokenScope::document(*one), kViewerToken, Role::kViewer).isOk());
  ASSERT_TRUE(store->addToken(TokenScope::allDocuments(), kAdminToken, Role::kAdmin).isOk());
  EXPECT_TRUE(store->knowsToken(kViewerToken).value());
  EXPECT_TRUE(store->knowsToken(kAdminToken).value());
  EXPECT_FALSE(store->knowsToken(kWrongToken).value());
  EXPECT_FALSE(store->knowsToken("").value());
  EXPECT_FALSE(store->knowsToken(std::string(5000, 'x')).value());
  // Revoked: no longer known.
  ASSERT_TRUE(store->revokeToken(kViewerToken).isOk());
  EXPECT_FALSE(store->knowsToken(kViewerToken).value());
}

TEST(StoreTokens, RolesResolvePerDocumentAndForAllDocuments) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto one = store->createDocument("one", "base");
  auto two = store->createDocument("two", "base");
  ASSERT_TRUE(one.isOk() && two.isOk());
  ASSERT_TRUE(store->addToken(TokenScope::document(*one), kViewerToken, Role::kViewer).isOk());
  ASSERT_TRUE(store->addToken(TokenScope::document(*one), kEditorToken, Role::kEditor).isOk());
  ASSERT_TRUE(store->addToken(TokenScope::document(*two), kEditorToken, Role::kViewer).isOk());
  ASSERT_TRUE(store->addToken(TokenScope::allDocuments(), kAdminToken, Role::kAdmin).isOk());

  auto roleOf = [&](const std::string& token, TokenScope scope) {
    auto role = store->roleFor(token, scope);
    return role.isOk() ? std::string(roleName(*role)) : role.status().toString();
  };
  EXPECT_EQ(roleOf(kViewerToken, TokenScope::document(*one)), "viewer");
  EXPECT_EQ(roleOf(kEditorToken, TokenScope::document(*one)), "editor");
  EXPECT_EQ(roleOf(kEditorToken, TokenScope::document(*two)), "viewer");
  EXPECT_EQ(roleOf(kAdminToken, TokenScope::document(*one)), "admin");
  EXPECT_EQ(roleOf(kAdminToken, TokenScope::document(*two)), "admin");
  EXPECT_EQ(roleOf(kAdminToken, TokenScope::allDocuments()), "admin");
  // A grant for one document says nothing about another, or about all.
  EXPECT_EQ(store->roleFor(kViewerToken, TokenScope::document(*two)).status().code(), ErrorCode::kNotFound);
  EXPECT_EQ(store->roleFor(kEditorToken, TokenScope::allDocuments()).status().code(), ErrorCode::kNotFound);

  // Granting again replaces the role; revoking removes every grant.
  ASSERT_TRUE(store->addToken(TokenScope::document(*one), kViewerToken, Role::kEditor).isOk());
  EXPECT_EQ(roleOf(kViewerToken, TokenScope::document(*one)), "editor");
  ASSERT_TRUE(store->revokeToken(kEditorToken).isOk());
  EXPECT_EQ(store->roleFor(kEditorToken, TokenScope::document(*one)).status().code(), ErrorCode::kNotFound);
  EXPECT_EQ(store->roleFor(kEditorToken, TokenScope::document(*two)).status().code(), ErrorCode::kNotFound);
  Status again = store->revokeToken(kEditorToken);
  EXPECT_EQ(again.code(), ErrorCode::kNotFound);
  expectNoToken(again, kEditorToken);
}

TEST(StoreTokens, WrongTokensAreRefusedWithoutEchoingThem) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto id = store->createDocument("doc", "base");
  ASSERT_TRUE(id.isOk());
  ASSERT_TRUE(store->addToken(TokenScope::document(*id), kEditorToken, Role::kEditor).isOk());

  for (const std::string& token : {kWrongToken, kEditorToken.substr(0, kEditorToken.size() - 1),
                                   kEditorToken + "x", std::string(kMaxTokenBytes + 1, 'q')}) {
    auto role = store->roleFor(token, TokenScope::document(*id));
    ASSERT_FALSE(role.isOk());
    EXPECT_EQ(role.status().code(), ErrorCode::kNotFound);
    EXPECT_NE(role.status().message().find(toString(*id)), std::string::npos) << role.status().message();
    expectNoToken(role.status(), token);
  }
  EXPECT_EQ(store->roleFor("", TokenScope::document(*id)).status().code(), ErrorCode::kNotFound);

  // Weak or absurd tokens are refused when granted, again without echo.
  for (const std::string& token : {std::string("short-secret"), std::string(kMaxTokenBytes + 1, 'z')}) {
    Status granted = store->addToken(TokenScope::document(*id), token, Role::kViewer);
    EXPECT_EQ(granted.code(), ErrorCode::kInvalidArgument);
    expectNoToken(granted, token);
  }
  Status badRole = store->addToken(TokenScope::document(*id), kViewerToken, static_cast<Role>(9));
  EXPECT_EQ(badRole.code(), ErrorCode::kInvalidArgument);
  expectNoToken(badRole, kViewerToken);
}

TEST(StoreTokens, OnlyHashesReachTheDisk) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto id = store->createDocument("doc", "base");
  ASSERT_TRUE(id.isOk());
  ASSERT_TRUE(store->addToken(TokenScope::document(*id), kEditorToken, Role::kEditor).isOk());
  ASSERT_TRUE(store->addToken(TokenScope::allDocuments(), kAdminToken, Role::kAdmin).isOk());
  ASSERT_TRUE(store->roleFor(kEditorToken, TokenScope::document(*id)).isOk());

  auto editorHash = hashToken(kEditorToken);
  ASSERT_TRUE(editorHash.isOk());
  // While open, the grants are in the WAL; after close, in the main file.
  const std::string live = readFileBytes(dir.file("tessera.db")) + readFileBytes(dir.file("tessera.db-wal"));
  EXPECT_NE(live.find(*editorHash), std::string::npos) << "the hash is not where the grant went";
  for (const std::string& token : {kEditorToken, kAdminToken}) EXPECT_EQ(live.find(token), std::string::npos);

  store->close();
  EXPECT_FALSE(std::filesystem::exists(dir.file("tessera.db-wal")));  // checkpointed on close
  const std::string closed = readFileBytes(dir.file("tessera.db"));
  EXPECT_NE(closed.find(*editorHash), std::string::npos);
  for (const std::string& token : {kEditorToken, kAdminToken})
    EXPECT_EQ(closed.find(token), std::string::npos);
}

}  // namespace
}  // namespace tessera::store
