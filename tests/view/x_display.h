// An X display for the viewer tests that need a window: a private Xvfb
// server, the viewer's environment on it (Mesa's llvmpipe), the environment
// with no display for --screenshot, and child processes bounded in time.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tessera::testing {

using Environment = std::vector<std::pair<std::string, std::string>>;

// The program's path on PATH, if it is installed.
std::optional<std::string> findProgram(const std::string& name);

// No display at all: DISPLAY and WAYLAND_DISPLAY unset, for --screenshot,
// which renders with EGL on Mesa's surfaceless platform. In an ASan build
// LeakSanitizer is off for the viewer process, as below.
Environment headlessEnvironment();

// DISPLAY and Mesa's software renderer. In an ASan build LeakSanitizer is off
// for the viewer process: llvmpipe leaks from a module it loads and unloads,
// which LSan cannot name in a suppression (the stacks end in "<unknown module>").
Environment viewerEnvironment(const std::string& display);

// Starts argv with extra environment (an empty value unsets the variable),
// stdout and stderr appended to `log`.
pid_t spawn(const std::vector<std::string>& args, const Environment& env, const std::string& log);

// Waits up to `seconds` for `pid`, then kills it. Returns its exit code, or
// -1 on a timeout or a signal.
int waitBounded(pid_t pid, double seconds);

// spawn, then waitBounded.
int runBounded(const std::vector<std::string>& args, const Environment& env, const std::string& log,
               double seconds);

// Runs xdotool `binary` with `args` on `display`, bounded by timeout(1)
// (10 s); returns what it printed.
std::string xdotool(const std::string& binary, const std::string& display, const std::string& args);

// An Xvfb server (800x600x24) on a free display number, stopped on destruction.
class Xvfb {
 public:
  Xvfb() = default;
  Xvfb(const Xvfb&) = delete;
  Xvfb& operator=(const Xvfb&) = delete;
  ~Xvfb();

  // Tries a few display numbers; each gets at most 10 s to open its socket.
  bool start(const std::string& binary, const std::string& log);
  const std::string& display() const { return display_; }

 private:
  pid_t pid_ = -1;
  std::string display_;
};

}  // namespace tessera::testing
