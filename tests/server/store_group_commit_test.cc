// Group commit under concurrency: 8 producer threads x 500 asynchronous
// appends over 4 documents. Every callback runs once, every entry lands in
// its document's order, and the writer grouped them (batches < entries).
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "server/store/sqlite_store.h"
#include "server/store_test_support.h"

namespace tessera::store {
namespace {

using testing::entryBytes;
using testing::openStoreOrFail;
using testing::TempDataDir;

constexpr int kThreads = 8;
constexpr int kAppendsPerThread = 500;
constexpr int kDocuments = 4;

// What a server's per-document strand does: the version is chosen and the
// append queued under one lock, so queue order is version order.
struct DocumentWriter {
  std::mutex mutex;
  DocumentId id;
  uint64_t latest = 0;
  std::vector<int> authorOfVersion{0};  // index = version
};

TEST(StoreGroupCommit, ConcurrentProducersAreBatchedAndKeepPerDocumentOrder) {
  TempDataDir dir;
  auto store = openStoreOrFail(dir.path());
  ASSERT_NE(store, nullptr);
  std::array<DocumentWriter, kDocuments> documents;
  for (int d = 0; d < kDocuments; ++d) {
    auto id = store->createDocument("doc" + std::to_string(d), "base");
    ASSERT_TRUE(id.isOk());
    documents[d].id = *id;
  }
  const StoreStats before = store->stats();

  constexpr int kTotal = kThreads * kAppendsPerThread;
  std::vector<std::atomic<int>> calls(kTotal);
  std::atomic<int> failures{0};
  std::mutex doneMutex;
  std::condition_variable allDone;
  int done = 0;

  std::vector<std::thread> producers;
  for (int t = 0; t < kThreads; ++t) {
    producers.emplace_back([&, t] {
      for (int i = 0; i < kAppendsPerThread; ++i) {
        const int slot = t * kAppendsPerThread + i;
        DocumentWriter& document = documents[(t + i) % kDocuments];
        std::lock_guard<std::mutex> lock(document.mutex);
        const uint64_t version = ++document.latest;
        document.authorOfVersion.push_back(t);
        store->append(document.id, version, "thread" + std::to_string(t),
                      entryBytes(version, document.id.value), [&, slot](Status status) {
                        calls[slot].fetch_add(1);
                        if (!status.isOk()) {
                          failures.fetch_add(1);
                          ADD_FAILURE() << status.toString();
                        }
                        std::lock_guard<std::mutex> doneLock(doneMutex);
                        ++done;
                        allDone.notify_all();
                      });
      }
    });
  }
  for (std::thread& producer : producers) producer.join();
  {
    std::unique_lock<std::mutex> lock(doneMutex);
    ASSERT_TRUE(allDone.wait_for(lock, std::chrono::seconds(60), [&] { return done == kTotal; }))
        << done << " of " << kTotal << " callbacks";
  }

  for (int slot = 0; slot < kTotal; ++slot) ASSERT_EQ(calls[slot].load(), 1) << "append " << slot;
  EXPECT_EQ(failures.load(), 0);

  for (DocumentWriter& document : documents) {
    auto loaded = store->loadDocument(document.id);
    ASSERT_TRUE(loaded.isOk()) << loaded.status().toString();
    ASSERT_EQ(loaded->entries.size(), document.latest);
    for (uint64_t v = 1; v <= document.latest; ++v) {
      const JournalEntry& entry = loaded->entries[v - 1];
      ASSERT_EQ(entry.version, v);
      EXPECT_EQ(entry.author, "thread" + std::to_string(document.authorOfVersion[v]));
      EXPECT_EQ(entry.bytes, entryBytes(v, document.id.value));
    }
  }

  const StoreStats stats = store->stats();
  const uint64_t entries = stats.entriesCommitted - before.entriesCommitted;
  const uint64_t batches = stats.batches - before.batches;
  EXPECT_EQ(entries, static_cast<uint64_t>(kTotal));
  EXPECT_EQ(stats.entriesRejected, 0u);
  EXPECT_LT(batches, entries) << "no batching happened";
  EXPECT_GT(stats.averageBatchSize, 1.0);
  std::printf("[ group commit ] %llu entries in %llu batches (%.1f per batch)\n",
              static_cast<unsigned long long>(entries), static_cast<unsigned long long>(batches),
              static_cast<double>(entries) / static_cast<double>(batches));
}

}  // namespace
}  // namespace tessera::store
