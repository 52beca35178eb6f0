// A document's single writer that can run a task on either of
// two thread pools (docs/ARCHITECTURE.md, "Bulk work"). Tasks run one at a time, in the order they
// were posted, like an Asio strand; each goes to the executor of its lane:
// edits, flushes and presence on the interactive workers, a large
// profile's first tessellation or a large export on the bulk threads. While
// a bulk task runs, its document's later tasks wait (one writer), but other
// documents' tasks keep the interactive workers to themselves.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <deque>
#include <functional>
#include <mutex>

namespace tessera::server {

enum class Lane { kInteractive, kBulk };

class SerialQueue {
 public:
  SerialQueue(boost::asio::any_io_executor interactive, boost::asio::any_io_executor bulk)
      : interactive_(std::move(interactive)), bulk_(std::move(bulk)) {}

  // Thread-safe. The task must keep what it uses alive (capture a shared_ptr
  // of the owner): the queue lives as long as its owner.
  void post(Lane lane, std::function<void()> task);

 private:
  struct Task {
    Lane lane;
    std::function<void()> run;
  };
  void dispatchFront();
  void finished();

  const boost::asio::any_io_executor interactive_, bulk_;
  std::mutex mutex_;
  std::deque<Task> tasks_;  // the front is running while running_
  bool running_ = false;
};

}  // namespace tessera::server
