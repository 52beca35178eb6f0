#include "core/util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

namespace tessera {

namespace {

std::atomic<unsigned> chosenThreads{0};

// Helper threads kept between calls: starting one costs tens of
// microseconds, about what building a small edit's region takes. They wait
// for tasks; the pool grows to the most helpers a call asked for. It lives
// as long as the process and is never destroyed: its threads, detached,
// end with the process, and a child forked from it (a test's) exits
// without joining threads it does not have.
class HelperPool {
 public:
  static HelperPool& instance() {
    static HelperPool& pool = *new HelperPool;
    return pool;
  }

  void post(size_t helpers, const std::function<void()>& task) {
    {
      std::lock_guard lock(mutex_);
      for (; started_ < std::min(helpers, kMostHelpers); ++started_) std::thread([this] { run(); }).detach();
      for (size_t k = 0; k < helpers; ++k) tasks_.push_back(task);
    }
    wake_.notify_all();
  }

 private:
  static constexpr size_t kMostHelpers = 8;

  [[noreturn]] void run() {
    for (;;) {
      std::function<void()> task;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return !tasks_.empty(); });
        task = std::move(tasks_.front());
        tasks_.pop_front();
      }
      task();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> tasks_;
  size_t started_ = 0;
};

// One call's items. The caller takes items too and, once none is left,
// closes the call and waits for the helpers already at work; a helper that
// starts later finds it closed and leaves. So a call never waits for a
// helper that is busy elsewhere (another call, or the one it is nested in).
struct Call {
  size_t n = 0;
  const std::function<void(size_t)>* body = nullptr;
  std::atomic<size_t> next{0};
  std::mutex mutex;
  std::condition_variable idle;
  int active = 0;
  bool closed = false;

  void work() {
    for (size_t i = next.fetch_add(1, std::memory_order_relaxed); i < n;
         i = next.fetch_add(1, std::memory_order_relaxed))
      (*body)(i);
  }
};

}  // namespace

unsigned workThreads() {
  const unsigned chosen = chosenThreads.load(std::memory_order_relaxed);
  return chosen > 0 ? chosen : std::clamp(std::thread::hardware_concurrency(), 1u, 4u);
}

void setWorkThreads(unsigned threads) {
  chosenThreads.store(threads, std::memory_order_relaxed);
}

void parallelFor(size_t n, unsigned threads, const std::function<void(size_t)>& body) {
  const size_t used = std::min<size_t>(n, threads);
  if (used < 2) {
    for (size_t i = 0; i < n; ++i) body(i);
    return;
  }
  auto call = std::make_shared<Call>();
  call->n = n;
  call->body = &body;
  HelperPool::instance().post(used - 1, [call] {
    {
      std::lock_guard lock(call->mutex);
      if (call->closed) return;
      ++call->active;
    }
    call->work();
    std::lock_guard lock(call->mutex);
    if (--call->active == 0) call->idle.notify_all();
  });
  call->work();
  std::unique_lock lock(call->mutex);
  call->closed = true;
  call->idle.wait(lock, [&] { return call->active == 0; });
}

}  // namespace tessera
