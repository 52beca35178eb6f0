// The journal: round trips, contiguity, one bad append inside a batch, close
// flushing pending appends, statistics, and the callback re-entrancy guard.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <vector>

#include "server/store/sqlite_store.h"
#include "server/store_test_support.h"

namespace tessera::store {
namespace {

using testing::entryBytes;
using testing::openStoreOrFail;
using testing::TempDataDir;

// Counts callbacks and lets a test wait for a number of them.
class CallbackLatch {
 public:
  AppendCallback record(std::vector<Status>& into, size_t slot) {
    return [this, &into, slot](Status status) {
      std::lock_guard<std::mutex> lock(mutex_);
      into[slot] = std::move(status);
      ++calls_;
      changed_.notify_all();
    };
  }
  bool waitFor(size_t calls) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, std::chrono::seconds(30), [&] { return calls_ >= calls; });
  }
  size_t calls() {
    std::lock_guard<std::mutex> lock(mutex_);
    return calls_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  size_t calls_ = 0;
};

TEST(StoreJournal, AppendRoundTrip) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto id = store->createDocument("journal", "base");
  ASSERT_TRUE(id.isOk());
  for (uint64_t v = 1; v <= 20; ++v) {
    Status status = store->appendSync(*id, v, v % 2 ? "alice" : "bob", entryBytes(v));
    ASSERT_TRUE(status.isOk()) << status.toString();
  }
  ASSERT_TRUE(store->appendSync(*id, 21, "", "").isOk());  // empty author and bytes are kept as such

  auto loaded = store->loadDocument(*id);
  ASSERT_TRUE(loaded.isOk()) << loaded.status().toString();
  ASSERT_EQ(loaded->entries.size(), 21u);
  for (uint64_t v = 1; v <= 20; ++v) {
    const JournalEntry& entry = loaded->entries[v - 1];
    EXPECT_EQ(entry.version, v);
    EXPECT_EQ(entry.author, v % 2 ? "alice" : "bob");
    EXPECT_EQ(entry.bytes, entryBytes(v));
  }
  EXPECT_EQ(loaded->entries[20].author, "");
  EXPECT_EQ(loaded->entries[20].bytes, "");
}

TEST(StoreJournal, RefusesVersionsThatAreNotNext) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto id = store->createDocument("contiguous", "base");
  ASSERT_TRUE(id.isOk());

  Status gap = store->appendSync(*id, 2, "a", "x");
  EXPECT_EQ(gap.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(gap.message().find(toString(*id)), std::string::npos) << gap.message();
  EXPECT_NE(gap.message().find("next version is 1"), std::string::npos) << gap.message();
  EXPECT_EQ(store->appendSync(*id, 0, "a", "x").code(), ErrorCode::kInvalidArgument);
  ASSERT_TRUE(store->appendSync(*id, 1, "a", "first").isOk());
  EXPECT_EQ(store->appendSync(*id, 1, "a", "duplicate").code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(store->appendSync(*id, 3, "a", "gap").code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(store->appendSync(*id, 2, std::string(kMaxAuthorBytes + 1, 'a'), "x").code(),
            ErrorCode::kInvalidArgument);
  ASSERT_TRUE(store->appendSync(*id, 2, "a", "second").isOk());

  auto loaded = store->loadDocument(*id);
  ASSERT_TRUE(loaded.isOk());
  ASSERT_EQ(loaded->entries.size(), 2u);
  EXPECT_EQ(loaded->entries[0].bytes, "first");
  EXPECT_EQ(loaded->entries[1].bytes, "second");
}

// The appends queued from inside a callback are exactly the next batch: the
// writer calls callbacks after a commit and only then takes the queue.
TEST(StoreJournal, OneBadAppendInABatchDoesNotAffectTheOthers) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto a = store->createDocument("a", "base");
  auto b = store->createDocument("b", "base");
  auto c = store->createDocument("c", "base");
  ASSERT_TRUE(a.isOk() && b.isOk() && c.isOk());

  std::vector<Status> results(6);
  CallbackLatch latch;
  uint64_t batchesBefore = 0;
  store->append(*a, 1, "seed", "a1", [&](Status status) {
    results[0] = status;
    batchesBefore = store->stats().batches;
    store->append(*a, 2, "w", "a2", latch.record(results, 1));
    store->append(*b, 2, "w", "b2 too early", latch.record(results, 2));  // bad: b is empty
    store->append(*b, 1, "w", "b1", latch.record(results, 3));
    store->append(DocumentId{999}, 1, "w", "nowhere", latch.record(results, 4));  // bad: no document
    store->append(*c, 1, "w", "c1", latch.record(results, 5));
  });
  ASSERT_TRUE(latch.waitFor(5));

  EXPECT_TRUE(results[0].isOk()) << results[0].toString();
  EXPECT_TRUE(results[1].isOk()) << results[1].toString();
  EXPECT_EQ(results[2].code(), ErrorCode::kInvalidArgument) << results[2].toString();
  EXPECT_TRUE(results[3].isOk()) << results[3].toString();
  EXPECT_EQ(results[4].code(), ErrorCode::kNotFound) << results[4].toString();
  EXPECT_TRUE(results[5].isOk()) << results[5].toString();
  EXPECT_EQ(store->stats().batches, batchesBefore + 1) << "the five appends were not one batch";

  auto loadedA = store->loadDocument(*a);
  auto loadedB = store->loadDocument(*b);
  auto loadedC = store->loadDocument(*c);
  ASSERT_TRUE(loadedA.isOk() && loadedB.isOk() && loadedC.isOk());
  ASSERT_EQ(loadedA->entries.size(), 2u);
  EXPECT_EQ(loadedA->entries[1].bytes, "a2");
  ASSERT_EQ(loadedB->entries.size(), 1u);
  EXPECT_EQ(loadedB->entries[0].bytes, "b1");
  ASSERT_EQ(loadedC->entries.size(), 1u);
  EXPECT_EQ(loadedC->entries[0].bytes, "c1");
}

TEST(StoreJournal, CloseCommitsPendingAppendsAndCallsTheirCallbacks) {
  TempDataDir dir;
  constexpr size_t kAppends = 300;
  DocumentId id;
  std::vector<Status> results(kAppends, Status(ErrorCode::kInternal, "callback not called"));
  CallbackLatch latch;
  {
    auto store = openStoreOrFail(dir.path());
    ASSERT_NE(store, nullptr);
    auto created = store->createDocument("flush", "base");
    ASSERT_TRUE(created.isOk());
    id = *created;
    for (uint64_t v = 1; v <= kAppends; ++v)
      store->append(id, v, "a", entryBytes(v), latch.record(results, v - 1));
    store->close();
    EXPECT_EQ(latch.calls(), kAppends);  // close() returns only after every callback
  }
  for (const Status& status : results) EXPECT_TRUE(status.isOk()) << status.toString();

  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto loaded = store->loadDocument(id);
  ASSERT_TRUE(loaded.isOk());
  EXPECT_EQ(loaded->entries.size(), kAppends);
}

TEST(StoreJournal, StatsCountEntriesBatchesAndLatency) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto id = store->createDocument("stats", "base");
  ASSERT_TRUE(id.isOk());
  for (uint64_t v = 1; v <= 5; ++v) ASSERT_TRUE(store->appendSync(*id, v, "a", "x").isOk());
  EXPECT_FALSE(store->appendSync(*id, 9, "a", "x").isOk());

  const StoreStats stats = store->stats();
  EXPECT_EQ(stats.entriesCommitted, 5u);
  EXPECT_EQ(stats.entriesRejected, 1u);
  EXPECT_EQ(stats.writesCommitted, 6u);  // the document and five entries
  EXPECT_EQ(stats.batches, 7u);          // one writer at a time: nothing to group
  EXPECT_NEAR(stats.averageBatchSize, 6.0 / 7.0, 1e-9);
  EXPECT_GT(stats.lastCommitLatency.count(), 0);
}

TEST(StoreJournal, SynchronousCallFromACallbackIsRefusedNotDeadlocked) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  auto id = store->createDocument("reentrant", "base");
  ASSERT_TRUE(id.isOk());
  std::vector<Status> results(1);
  CallbackLatch latch;
  Status nested;
  store->append(*id, 1, "a", "x", [&](Status) {
    nested = store->appendSync(*id, 2, "a", "y");
    latch.record(results, 0)(Status::ok());
  });
  ASSERT_TRUE(latch.waitFor(1));
  EXPECT_EQ(nested.code(), ErrorCode::kInternal);
}

}  // namespace
}  // namespace tessera::store
