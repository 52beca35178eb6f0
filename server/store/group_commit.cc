#include "server/store/group_commit.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <utility>

namespace tessera::store {
namespace {

// Transaction control through cached statements: a batch of thousands of
// writes runs thousands of savepoints, which should not be parsed each time.
Status runCached(SqliteConnection& connection, const char* sql) {
  TESSERA_ASSIGN_OR_RETURN(SqliteStatement statement, connection.prepare(sql));
  return statement.run();
}

}  // namespace

GroupCommitWriter::GroupCommitWriter(SqliteConnection& connection, GroupCommitOptions options)
    : connection_(connection), path_(connection.path()), options_(options), thread_([this] { run(); }) {}

GroupCommitWriter::~GroupCommitWriter() {
  stop();
}

void GroupCommitWriter::submit(PendingWrite write) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!stopping_) {
      queue_.push_back(std::move(write));
      // Notify under the lock: stop() may otherwise join and the owner destroy
      // this object between our unlock and the notify.
      wakeWriter_.notify_one();
      return;
    }
  }
  if (write.done) write.done(ioError(path_ + ": the store is closed; write refused"));
}

void GroupCommitWriter::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wakeWriter_.notify_one();
  if (thread_.joinable() && !onWriterThread()) thread_.join();
}

StoreStats GroupCommitWriter::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

void GroupCommitWriter::run() {
  const size_t maxBatch = std::max<size_t>(1, options_.maxBatchWrites);
  std::vector<PendingWrite> batch;
  while (true) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wakeWriter_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, and everything queued is committed
      const size_t take = std::min(queue_.size(), maxBatch);
      const auto end = queue_.begin() + static_cast<std::ptrdiff_t>(take);
      batch.assign(std::make_move_iterator(queue_.begin()), std::make_move_iterator(end));
      queue_.erase(queue_.begin(), end);
    }
    commitBatch(batch);
    batch.clear();
  }
}

void GroupCommitWriter::commitBatch(std::vector<PendingWrite>& batch) {
  std::vector<Status> results(batch.size());
  const auto start = std::chrono::steady_clock::now();
  Status fatal = failure_;
  if (fatal.isOk()) fatal = runCached(connection_, "BEGIN IMMEDIATE");
  for (size_t i = 0; i < batch.size() && fatal.isOk(); ++i) results[i] = applyInSavepoint(batch[i], fatal);
  if (fatal.isOk()) fatal = runCached(connection_, "COMMIT");

  const bool committed = fatal.isOk();
  if (!committed) {
    if (connection_.inTransaction()) (void)connection_.exec("ROLLBACK");
    if (failure_.isOk()) {
      failure_ =
          Status(fatal.code(), "the store stopped writing after a failed transaction: " + fatal.message());
    }
    for (Status& result : results) result = failure_;
  }
  const auto latency =
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start);
  recordBatch(batch, results, latency, committed);
  for (size_t i = 0; i < batch.size(); ++i) {
    if (batch[i].done) batch[i].done(std::move(results[i]));
  }
}

Status GroupCommitWriter::applyInSavepoint(PendingWrite& write, Status& fatal) {
  fatal = runCached(connection_, "SAVEPOINT write");
  if (!fatal.isOk()) return fatal;
  Status result = write.apply(connection_);
  if (result.isOk()) {
    fatal = runCached(connection_, "RELEASE write");
    return fatal;
  }
  // Some SQLite errors (disk full, I/O) roll the whole transaction back on
  // their own; ROLLBACK TO then fails, and the batch fails as a whole.
  fatal = runCached(connection_, "ROLLBACK TO write");
  if (fatal.isOk()) fatal = runCached(connection_, "RELEASE write");
  return result;
}

void GroupCommitWriter::recordBatch(const std::vector<PendingWrite>& batch,
                                    const std::vector<Status>& results, std::chrono::microseconds latency,
                                    bool committed) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (size_t i = 0; i < batch.size(); ++i) {
    const bool kept = committed && results[i].isOk();
    if (kept) ++stats_.writesCommitted;
    if (batch[i].isJournalEntry) ++(kept ? stats_.entriesCommitted : stats_.entriesRejected);
  }
  if (committed) {
    ++stats_.batches;
    stats_.lastCommitLatency = latency;
    stats_.commitLatency.add(latency);
  }
  stats_.averageBatchSize =
      stats_.batches == 0 ? 0.0
                          : static_cast<double>(stats_.writesCommitted) / static_cast<double>(stats_.batches);
}

}  // namespace tessera::store
