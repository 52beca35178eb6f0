// The catalogue commands (server/net/catalogue_commands.h) refuse with the
// one Status-to-reason mapping of replies.h: what the caller named and is
// missing is NOT_FOUND, what the caller sent wrong is INVALID_ARGUMENT, and
// a store that fails on its own (a disk error) is INTERNAL, never blamed on
// the caller's argument.
#include <gtest/gtest.h>

#include <string>

#include "server/net/catalogue_commands.h"
#include "support/host_only_store.h"

namespace tessera::server {
namespace {

// A store whose catalogue calls all fail with one status.
class FailingStore final : public testing::HostOnlyStore {
 public:
  explicit FailingStore(Status status) : status_(std::move(status)) {}
  Expected<std::vector<store::DocumentSummary>> listDocuments() override { return status_; }
  Status deleteDocument(store::DocumentId) override { return status_; }
  Status addToken(store::TokenScope, std::string_view, store::Role) override { return status_; }
  void append(store::DocumentId, uint64_t, std::string, std::string, store::AppendCallback done) override {
    done(status_);
  }

 private:
  Status status_;
};

class NoOpener final : public DocumentOpener {
 public:
  Expected<std::shared_ptr<DocumentEndpoint>> openEndpoint(store::DocumentId) override {
    return internalError("not used");
  }
  void forget(store::DocumentId) override { ++forgotten; }
  int forgotten = 0;
};

CatalogueCaller admin() {
  return {.session = 1, .globalRole = store::Role::kAdmin, .roleOn = [](store::DocumentId) {
            return store::Role::kAdmin;
          }};
}

wire::GrantToken grant(const std::string& token) {
  wire::GrantToken g;
  g.set_token(token);
  g.set_role(wire::ROLE_EDITOR);
  g.set_document_id(4);
  return g;
}

TEST(CatalogueCommands, AStoreFailureIsInternal) {
  FailingStore store(ioError("disk I/O error"));
  NoOpener opener;
  const wire::ServerMessage granted = grantToken(store, admin(), 7, grant("tok"));
  ASSERT_TRUE(granted.has_reject());
  EXPECT_EQ(granted.reject().reason(), wire::REJECT_REASON_INTERNAL);
  EXPECT_EQ(granted.reject().message(), "disk I/O error");
  EXPECT_EQ(deleteDocument(store, opener, admin(), 8, store::DocumentId{4}).reject().reason(),
            wire::REJECT_REASON_INTERNAL);
  EXPECT_EQ(listDocuments(store, admin(), 9).reject().reason(), wire::REJECT_REASON_INTERNAL);
  EXPECT_EQ(opener.forgotten, 0);
}

TEST(CatalogueCommands, WhatTheCallerNamedAndIsMissingIsNotFound) {
  FailingStore store(notFound("document 4 does not exist"));
  NoOpener opener;
  EXPECT_EQ(grantToken(store, admin(), 7, grant("tok")).reject().reason(), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_EQ(deleteDocument(store, opener, admin(), 8, store::DocumentId{4}).reject().reason(),
            wire::REJECT_REASON_NOT_FOUND);
}

TEST(CatalogueCommands, WhatTheCallerSentWrongIsAnInvalidArgument) {
  FailingStore store(invalidArgument("unknown role 9 for an access token"));
  NoOpener opener;
  EXPECT_EQ(grantToken(store, admin(), 7, grant("tok")).reject().reason(),
            wire::REJECT_REASON_INVALID_ARGUMENT);
  // Refused before the store: an empty token, no role.
  EXPECT_EQ(grantToken(store, admin(), 7, grant("")).reject().reason(), wire::REJECT_REASON_INVALID_ARGUMENT);
  wire::GrantToken noRole = grant("tok");
  noRole.set_role(wire::ROLE_UNSPECIFIED);
  EXPECT_EQ(grantToken(store, admin(), 7, noRole).reject().message(), "grant: no role given");
}

TEST(CatalogueCommands, RolesAreCheckedBeforeTheStore) {
  FailingStore store(ioError("must not be reached"));
  NoOpener opener;
  CatalogueCaller editor{.session = 2, .globalRole = store::Role::kEditor, .roleOn = [](store::DocumentId) {
                           return std::optional<store::Role>(store::Role::kEditor);
                         }};
  EXPECT_EQ(grantToken(store, editor, 7, grant("tok")).reject().reason(),
            wire::REJECT_REASON_PERMISSION_DENIED);
  const wire::ServerMessage deleted = deleteDocument(store, opener, editor, 8, store::DocumentId{4});
  EXPECT_EQ(deleted.reject().reason(), wire::REJECT_REASON_PERMISSION_DENIED);
  EXPECT_EQ(deleted.reject().message(), "deleting document 4 needs the admin role");
}

}  // namespace
}  // namespace tessera::server
