// Polling with a deadline, for the view tests that watch a connection
// follow the server.
#pragma once

#include <chrono>
#include <functional>
#include <thread>

namespace tessera::testing {

// Polls `done` every few milliseconds for up to `seconds`; its last answer.
inline bool waitFor(const std::function<bool()>& done, double seconds = 30) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

}  // namespace tessera::testing
