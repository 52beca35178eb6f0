// A document's serial queue (server/serial_queue.h): tasks run one at a
// time in posting order whichever lane they take, and a bulk task does not
// occupy the interactive pool, so another queue's interactive tasks run
// while it does.
#include <gtest/gtest.h>

#include <atomic>
#include <boost/asio/thread_pool.hpp>
#include <chrono>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include "server/base/serial_queue.h"

namespace tessera::server {
namespace {

TEST(SerialQueue, TasksRunOneAtATimeInOrderAcrossLanes) {
  boost::asio::thread_pool interactive(2), bulk(2);
  SerialQueue queue(interactive.get_executor(), bulk.get_executor());
  std::vector<int> order;
  std::atomic<int> running{0}, overlaps{0};
  std::promise<void> done;
  constexpr int kTasks = 2000;
  for (int i = 0; i < kTasks; ++i) {
    queue.post(i % 3 == 0 ? Lane::kBulk : Lane::kInteractive, [&, i] {
      if (running.fetch_add(1) != 0) ++overlaps;
      order.push_back(i);  // unsynchronised on purpose: the queue must order it
      running.fetch_sub(1);
      if (i == kTasks - 1) done.set_value();
    });
  }
  ASSERT_EQ(done.get_future().wait_for(std::chrono::seconds(30)), std::future_status::ready);
  EXPECT_EQ(overlaps.load(), 0);
  ASSERT_EQ(order.size(), static_cast<size_t>(kTasks));
  for (int i = 0; i < kTasks; ++i) ASSERT_EQ(order[i], i);
  interactive.join();
  bulk.join();
}

TEST(SerialQueue, ABulkTaskLeavesTheInteractivePoolToOthers) {
  boost::asio::thread_pool interactive(1), bulk(1);
  SerialQueue large(interactive.get_executor(), bulk.get_executor());
  SerialQueue small(interactive.get_executor(), bulk.get_executor());
  std::promise<void> release;
  auto released = release.get_future().share();
  std::promise<void> bulkStarted, smallRan;
  large.post(Lane::kBulk, [&, released] {
    bulkStarted.set_value();
    released.wait();  // a long import
  });
  bulkStarted.get_future().wait();
  small.post(Lane::kInteractive, [&] { smallRan.set_value(); });
  // The one interactive thread is free: the small document's edit runs now.
  EXPECT_EQ(smallRan.get_future().wait_for(std::chrono::seconds(10)), std::future_status::ready);
  // The large document's own next task waits for its bulk task.
  std::atomic<bool> largeNext{false};
  std::promise<void> largeRan;
  large.post(Lane::kInteractive, [&] {
    largeNext = true;
    largeRan.set_value();
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(largeNext.load());
  release.set_value();
  EXPECT_EQ(largeRan.get_future().wait_for(std::chrono::seconds(10)), std::future_status::ready);
  interactive.join();
  bulk.join();
}

}  // namespace
}  // namespace tessera::server
