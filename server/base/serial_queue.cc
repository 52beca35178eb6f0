#include "server/base/serial_queue.h"

#include <boost/asio/post.hpp>

namespace tessera::server {

void SerialQueue::post(Lane lane, std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    tasks_.push_back({lane, std::move(task)});
    if (running_) return;
    running_ = true;
  }
  dispatchFront();
}

// The mutex orders every task after the one before it, whichever threads
// they run on, so a task sees all its predecessors' writes.
void SerialQueue::dispatchFront() {
  Task* front = nullptr;
  {
    std::lock_guard lock(mutex_);
    front = &tasks_.front();  // stays put: deque push_back keeps references
  }
  const auto& executor = front->lane == Lane::kBulk ? bulk_ : interactive_;
  boost::asio::post(executor, [this, front] {
    front->run();
    finished();
  });
}

void SerialQueue::finished() {
  std::function<void()> done;  // destroyed outside the lock: it may own the queue's owner
  bool more = false;
  {
    std::lock_guard lock(mutex_);
    done = std::move(tasks_.front().run);
    tasks_.pop_front();
    more = !tasks_.empty();
    running_ = more;
  }
  if (more) dispatchFront();
  // Past this point `this` may be gone (the last task dropped its owner).
}

}  // namespace tessera::server
