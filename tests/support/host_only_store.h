// The part of a Store a document host uses is append (and putSnapshot, which
// succeeds here); every other method answers an internal error, so a test
// or fuzz target that gives a host its own store writes only how appends
// complete (held, posted, failed). HeldStore is the one the server tests share.
#pragma once

#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "server/store/store.h"

namespace tessera::testing {

class HostOnlyStore : public store::Store {
 public:
  Expected<store::DocumentId> createDocument(std::string_view, std::string_view) override { return unused(); }
  Expected<std::vector<store::DocumentSummary>> listDocuments() override { return unused(); }
  Status deleteDocument(store::DocumentId) override { return unused(); }
  Expected<store::StoredDocument> loadDocument(store::DocumentId) override { return unused(); }
  Status appendSync(store::DocumentId, uint64_t, std::string, std::string) override { return unused(); }
  Status putSnapshot(store::DocumentId, uint64_t, std::string_view) override { return Status::ok(); }
  Status addToken(store::TokenScope, std::string_view, store::Role) override { return unused(); }
  Status revokeToken(std::string_view) override { return unused(); }
  Expected<store::Role> roleFor(std::string_view, store::TokenScope) override { return unused(); }
  Expected<bool> knowsToken(std::string_view) override { return unused(); }
  store::StoreStats stats() const override { return {}; }
  store::Durability durability() const override {
    return {"memory", "", store::WriteSync::kNotEachWrite, "nothing is durable"};
  }
  void close() override {}

 private:
  static Status unused() { return internalError("not used by a document host"); }
};

// Holds every append until the test completes them all with one status
// (thread-safe: a host may append from its workers).
class HeldStore final : public HostOnlyStore {
 public:
  void append(store::DocumentId, uint64_t, std::string, std::string, store::AppendCallback done) override {
    std::lock_guard lock(mutex_);
    held_.push_back(std::move(done));
  }
  size_t held() {
    std::lock_guard lock(mutex_);
    return held_.size();
  }
  void completeAll(const Status& status) {
    std::vector<store::AppendCallback> done;
    {
      std::lock_guard lock(mutex_);
      done.swap(held_);
    }
    for (auto& d : done) d(status);
  }

 private:
  std::mutex mutex_;
  std::vector<store::AppendCallback> held_;
};

}  // namespace tessera::testing
