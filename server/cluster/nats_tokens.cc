#include "server/cluster/nats_tokens.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/util/hex.h"
#include "server/store/store_checks.h"
#include "server/store/token_hash.h"

namespace tessera::cluster {

namespace {

std::string tokenKey(const std::string& hashHex, store::TokenScope scope) {
  return hashHex + (scope.isAllDocuments() ? ".all" : ".doc" + std::to_string(scope.documentId().value));
}

// <hash>.known exists while any grant of the token does: knowsToken, asked
// at every Hello, is then one direct read instead of a listing.
std::string knownKey(const std::string& hashHex) {
  return hashHex + ".known";
}

}  // namespace

Status NatsTokens::add(store::TokenScope scope, std::string_view token, store::Role role) {
  TESSERA_RETURN_IF_ERROR(store::checkTokenToGrant(token));
  TESSERA_RETURN_IF_ERROR(store::checkRole(role));
  TESSERA_ASSIGN_OR_RETURN(std::string hash, store::hashToken(token));
  uint64_t revision = 0;
  natsStatus s = kvStore_PutString(&revision, bucket_.get(), tokenKey(hexBytes(hash), scope).c_str(),
                                   store::roleName(role));
  if (s == NATS_OK) s = kvStore_PutString(&revision, bucket_.get(), knownKey(hexBytes(hash)).c_str(), "1");
  if (s != NATS_OK) return link_.error(s, "granting an access token for " + scope.toString());
  return Status::ok();
}

Status NatsTokens::revoke(std::string_view token) {
  TESSERA_ASSIGN_OR_RETURN(std::string hash, store::hashToken(token));
  const std::string prefix = hexBytes(hash) + ".";
  kvKeysList keys{};
  natsStatus s = kvStore_Keys(&keys, bucket_.get(), nullptr);
  if (s == NATS_NOT_FOUND) return notFound("no such access token");
  if (s != NATS_OK) return link_.error(s, "listing access tokens");
  int removed = 0;
  Status result;
  for (int i = 0; i < keys.Count; ++i) {
    const std::string key = keys.Keys[i];
    if (key.substr(0, prefix.size()) != prefix || key == knownKey(hexBytes(hash))) continue;
    s = kvStore_Delete(bucket_.get(), key.c_str());
    if (s == NATS_OK) {
      ++removed;
    } else if (result.isOk()) {
      result = link_.error(s, "revoking an access token");
    }
  }
  kvKeysList_Destroy(&keys);
  TESSERA_RETURN_IF_ERROR(result);
  s = kvStore_Delete(bucket_.get(), knownKey(hexBytes(hash)).c_str());
  if (s != NATS_OK) return link_.error(s, "revoking an access token");
  // Never name the token: the caller knows which one it passed.
  if (removed == 0) return notFound("no such access token");
  return Status::ok();
}

Expected<store::Role> NatsTokens::roleFor(std::string_view token, store::TokenScope scope) {
  const Status refused = notFound("access token not valid for " + scope.toString());
  if (token.empty()) return notFound("no access token given");
  if (token.size() > kMaxTokenBytes) return refused;
  TESSERA_ASSIGN_OR_RETURN(std::string hash, store::hashToken(token));
  const std::string h = hexBytes(hash);
  std::optional<store::Role> best;
  std::vector<std::string> keys = {tokenKey(h, store::TokenScope::allDocuments())};
  if (!scope.isAllDocuments()) keys.push_back(tokenKey(h, scope));
  for (const std::string& key : keys) {
    kvEntry* raw = nullptr;
    const natsStatus s = kvStore_Get(&raw, bucket_.get(), key.c_str());
    KvEntryPtr entry(raw);
    if (s == NATS_NOT_FOUND) continue;
    if (s != NATS_OK) return link_.error(s, "checking an access token for " + scope.toString());
    auto role = store::parseRole(kvEntry_ValueString(entry.get()));
    if (role.isOk() && (!best || *role > *best)) best = *role;
  }
  if (!best) return refused;
  return *best;
}

Expected<bool> NatsTokens::knows(std::string_view token) {
  if (token.empty() || token.size() > kMaxTokenBytes) return false;
  TESSERA_ASSIGN_OR_RETURN(std::string hash, store::hashToken(token));
  kvEntry* raw = nullptr;
  const natsStatus s = kvStore_Get(&raw, bucket_.get(), knownKey(hexBytes(hash)).c_str());
  KvEntryPtr entry(raw);
  if (s == NATS_NOT_FOUND) return false;
  if (s != NATS_OK) return link_.error(s, "looking up an access token");
  return true;
}

Status NatsTokens::revokeDocument(store::DocumentId id) {
  natsStatus s = NATS_OK;
  kvKeysList keys{};
  s = kvStore_Keys(&keys, bucket_.get(), nullptr);
  if (s == NATS_NOT_FOUND) return Status::ok();
  if (s != NATS_OK) return link_.error(s, "listing the tokens of " + toString(id));
  // The document's grants go; a token left with no grant at all is
  // forgotten, as the SQLite store forgets it.
  const std::string suffix = ".doc" + std::to_string(id.value);
  std::map<std::string, int> grantsLeft;  // hash -> grants other than this document's
  std::vector<std::string> revoked;
  for (int i = 0; i < keys.Count; ++i) {
    const std::string key = keys.Keys[i];
    const size_t dot = key.find('.');
    if (dot == std::string::npos) continue;
    const std::string hash = key.substr(0, dot);
    if (key == knownKey(hash)) continue;
    if (key.substr(dot) == suffix) {
      revoked.push_back(key);
      grantsLeft.emplace(hash, 0);
    } else {
      ++grantsLeft[hash];
    }
  }
  kvKeysList_Destroy(&keys);
  for (const std::string& key : revoked) {
    s = kvStore_Delete(bucket_.get(), key.c_str());
    if (s != NATS_OK) return link_.error(s, "revoking a token of " + toString(id));
  }
  for (const auto& [hash, left] : grantsLeft) {
    if (left > 0) continue;
    s = kvStore_Delete(bucket_.get(), knownKey(hash).c_str());
    if (s != NATS_OK) return link_.error(s, "revoking a token of " + toString(id));
  }
  return Status::ok();
}

}  // namespace tessera::cluster
