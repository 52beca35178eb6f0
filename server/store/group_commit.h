// Group commit: one writer thread owns the write connection and commits every
// write queued while the previous commit was syncing in ONE transaction, so
// one fsync acknowledges many writes. Under load the batch grows by itself;
// alone, a write commits at once (no waiting for company).
//
// Each write runs in its own savepoint, so a write that fails (a version out
// of order, an unknown document) is rolled back alone and the rest of its
// batch still commits. Callbacks run on the writer thread after COMMIT has
// returned, i.e. after SQLite's fsync of the WAL (synchronous = FULL).
//
// A failed COMMIT fails every write of its batch and then every later write:
// after a failed fsync the kernel may have dropped dirty pages, so the only
// safe answer is to stop acknowledging anything (the operator restarts, and
// SQLite's recovery decides what the file holds).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/util/status.h"
#include "server/store/sqlite_connection.h"
#include "server/store/store.h"

namespace tessera::store {

struct PendingWrite {
  // Runs inside the batch transaction. Its changes are kept iff it returns ok.
  std::function<Status(SqliteConnection&)> apply;
  // Called exactly once with the write's outcome: ok only when durable.
  std::function<void(Status)> done;
  bool isJournalEntry = false;  // counted in StoreStats::entries*
};

struct GroupCommitOptions {
  // Bounds one transaction's size and thus the latency of its first write.
  // 1 disables grouping: one transaction (and fsync) per write.
  size_t maxBatchWrites = 4096;
};

class GroupCommitWriter {
 public:
  // Starts the writer thread, which uses `connection` exclusively until stop().
  GroupCommitWriter(SqliteConnection& connection, GroupCommitOptions options);
  ~GroupCommitWriter();  // stop()
  GroupCommitWriter(const GroupCommitWriter&) = delete;
  GroupCommitWriter& operator=(const GroupCommitWriter&) = delete;

  // Queues `write`. Once stopped, refuses it at once by calling its `done` on
  // this thread with a kIoError.
  void submit(PendingWrite write);

  // Refuses new writes, commits the queued ones (calling their callbacks) and
  // joins the thread. Idempotent.
  void stop();

  bool onWriterThread() const { return std::this_thread::get_id() == thread_.get_id(); }
  StoreStats stats() const;

 private:
  void run();
  void commitBatch(std::vector<PendingWrite>& batch);
  // Runs one write in a savepoint; an error returned in `fatal` means the
  // transaction itself is broken and the whole batch must fail.
  Status applyInSavepoint(PendingWrite& write, Status& fatal);
  void recordBatch(const std::vector<PendingWrite>& batch, const std::vector<Status>& results,
                   std::chrono::microseconds latency, bool committed);

  SqliteConnection& connection_;
  const std::string path_;  // for messages once the connection may be gone
  const GroupCommitOptions options_;

  mutable std::mutex mutex_;
  std::condition_variable wakeWriter_;
  std::deque<PendingWrite> queue_;
  bool stopping_ = false;
  Status failure_;  // sticky: set by a failed COMMIT, refuses everything after
  StoreStats stats_;

  std::thread thread_;  // last: starts once everything above is initialized
};

}  // namespace tessera::store
