// A document's serial queue (server/serial_queue.h): tasks run one at a
// time in posting order whichever lane they take, and a bulk task does not
// occupy the interactive pool, so another queue's interactive tasks run
// while it does. A task posted to run when idle waits for every other task
// waiting when it would start.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/thread_pool.hpp>
#include <chrono>
#include <future>
#include <mutex>
#include <string>
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

TEST(SerialQueue, AnIdleTaskGoesBehindTasksPostedWhileItWaited) {
  boost::asio::thread_pool interactive(2), bulk(1);
  SerialQueue queue(interactive.get_executor(), bulk.get_executor());
  std::promise<void> release, started;
  auto released = release.get_future().share();
  std::vector<std::string> order;  // written by the queue's tasks only
  queue.post(Lane::kInteractive, [&, released] {
    started.set_value();
    released.wait();  // a flush in progress
    order.push_back("busy");
  });
  started.get_future().wait();
  queue.postWhenIdle([&] { order.push_back("camera 1"); });
  queue.post(Lane::kInteractive, [&] { order.push_back("edit 1"); });
  queue.postWhenIdle([&] { order.push_back("camera 2"); });
  queue.post(Lane::kBulk, [&] { order.push_back("edit 2"); });
  std::promise<void> done;
  queue.postWhenIdle([&] {
    order.push_back("camera 3");
    done.set_value();
  });
  release.set_value();
  ASSERT_EQ(done.get_future().wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_EQ(order,
            (std::vector<std::string>{"busy", "edit 1", "edit 2", "camera 1", "camera 2", "camera 3"}));
  interactive.join();
  bulk.join();
}

TEST(SerialQueue, IdleTasksAloneRunInOrderOneAtATime) {
  boost::asio::thread_pool interactive(2), bulk(1);
  SerialQueue queue(interactive.get_executor(), bulk.get_executor());
  std::vector<int> order;
  std::atomic<int> running{0}, overlaps{0}, ran{0};
  std::promise<void> done;
  constexpr int kTasks = 500;
  for (int i = 0; i < kTasks; ++i) {
    auto task = [&, i] {
      if (running.fetch_add(1) != 0) ++overlaps;
      order.push_back(i);
      running.fetch_sub(1);
      if (ran.fetch_add(1) == kTasks - 1) done.set_value();
    };
    if (i % 2 == 0) {
      queue.postWhenIdle(task);
    } else {
      queue.post(Lane::kInteractive, task);
    }
  }
  ASSERT_EQ(done.get_future().wait_for(std::chrono::seconds(30)), std::future_status::ready);
  EXPECT_EQ(overlaps.load(), 0);
  ASSERT_EQ(order.size(), static_cast<size_t>(kTasks));
  // Each kind in its own order.
  std::vector<int> idle, plain;
  for (int i : order) (i % 2 == 0 ? idle : plain).push_back(i);
  EXPECT_TRUE(std::is_sorted(idle.begin(), idle.end()));
  EXPECT_TRUE(std::is_sorted(plain.begin(), plain.end()));
  interactive.join();
  bulk.join();
}

}  // namespace
}  // namespace tessera::server
