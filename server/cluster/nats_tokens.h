// The access tokens of a cluster, in the TESSERA_TOKENS key-value bucket
// (docs/CLUSTER.md, "What is stored where"): one key per grant,
// <hash>.all or <hash>.doc<id>, holding the role, and <hash>.known while the
// token has any grant. Only a token's hash is stored (token_hash.h), so the
// bucket never holds a token a reader could use.
#pragma once

#include <string_view>

#include "core/util/status.h"
#include "server/cluster/nats_link.h"
#include "server/store/store.h"

namespace tessera::cluster {

class NatsTokens {
 public:
  NatsTokens(NatsLink& link, KvStorePtr bucket) : link_(link), bucket_(std::move(bucket)) {}

  // The caller checked that a document scope names a document that exists.
  Status add(store::TokenScope scope, std::string_view token, store::Role role);
  Status revoke(std::string_view token);
  Expected<store::Role> roleFor(std::string_view token, store::TokenScope scope);
  Expected<bool> knows(std::string_view token);
  // A deleted document's grants; a token left with no grant is forgotten,
  // as the SQLite store forgets it.
  Status revokeDocument(store::DocumentId id);

 private:
  NatsLink& link_;
  KvStorePtr bucket_;
};

}  // namespace tessera::cluster
