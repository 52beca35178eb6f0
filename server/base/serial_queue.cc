#include "server/base/serial_queue.h"

#include <boost/asio/post.hpp>

namespace tessera::server {

void SerialQueue::post(Lane lane, std::function<void()> task) {
  enqueue(tasks_, {lane, std::move(task)});
}

void SerialQueue::postWhenIdle(std::function<void()> task) {
  enqueue(idle_, {Lane::kInteractive, std::move(task)});
}

void SerialQueue::enqueue(std::deque<Task>& into, Task task) {
  {
    std::lock_guard lock(mutex_);
    into.push_back(std::move(task));
    if (running_) return;
    running_ = true;
  }
  dispatchNext();
}

// The mutex orders every task after the one before it, whichever threads
// they run on, so a task sees all its predecessors' writes.
void SerialQueue::dispatchNext() {
  Lane lane;
  {
    std::lock_guard lock(mutex_);
    std::deque<Task>& from = tasks_.empty() ? idle_ : tasks_;
    current_ = std::move(from.front());
    from.pop_front();
    lane = current_->lane;
  }
  const auto& executor = lane == Lane::kBulk ? bulk_ : interactive_;
  boost::asio::post(executor, [this] {
    current_->run();  // only the running task's thread touches current_
    finished();
  });
}

void SerialQueue::finished() {
  std::function<void()> done;  // destroyed outside the lock: it may own the queue's owner
  bool more = false;
  {
    std::lock_guard lock(mutex_);
    done = std::move(current_->run);
    current_.reset();
    more = !tasks_.empty() || !idle_.empty();
    running_ = more;
  }
  if (more) dispatchNext();
  // Past this point `this` may be gone (the last task dropped its owner).
}

}  // namespace tessera::server
