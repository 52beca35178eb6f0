// A document's single writer that can run a task on either of
// two thread pools (docs/ARCHITECTURE.md, "Bulk work"). Tasks run one at a time, in the order they
// were posted, like an Asio strand; each goes to the executor of its lane:
// edits, flushes and presence on the interactive workers, a large
// profile's first tessellation or a large export on the bulk threads. While
// a bulk task runs, its document's later tasks wait (one writer), but other
// documents' tasks keep the interactive workers to themselves.
//
// A task posted with postWhenIdle runs on the interactive workers after
// every task posted with post that waits when it would start, those posted
// after it included: a camera turn goes behind the edits that came while
// it waited (docs/VIEWS.md "The server"). Idle tasks run in their own
// posting order. While tasks keep waiting, an idle task waits too.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>

namespace tessera::server {

enum class Lane { kInteractive, kBulk };

class SerialQueue {
 public:
  SerialQueue(boost::asio::any_io_executor interactive, boost::asio::any_io_executor bulk)
      : interactive_(std::move(interactive)), bulk_(std::move(bulk)) {}

  // Thread-safe. The task must keep what it uses alive (capture a shared_ptr
  // of the owner): the queue lives as long as its owner.
  void post(Lane lane, std::function<void()> task);
  // The same, on the interactive lane, once no task posted with post waits.
  void postWhenIdle(std::function<void()> task);

 private:
  struct Task {
    Lane lane;
    std::function<void()> run;
  };
  void enqueue(std::deque<Task>& into, Task task);
  // Starts the next task: the first of tasks_, else the first of idle_.
  void dispatchNext();
  void finished();

  const boost::asio::any_io_executor interactive_, bulk_;
  std::mutex mutex_;
  std::deque<Task> tasks_, idle_;
  std::optional<Task> current_;  // the task running while running_
  bool running_ = false;
};

}  // namespace tessera::server
