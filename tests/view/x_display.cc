#include "view/x_display.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>

namespace tessera::testing {

using Clock = std::chrono::steady_clock;

std::optional<std::string> findProgram(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = dirs.find(':', start);
    const std::string candidate = dirs.substr(start, end - start) + "/" + name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return std::nullopt;
}

Environment headlessEnvironment() {
  Environment env = {{"DISPLAY", ""}, {"WAYLAND_DISPLAY", ""}};
#ifdef __SANITIZE_ADDRESS__
  env.emplace_back("ASAN_OPTIONS", "detect_leaks=0");
#endif
  return env;
}

Environment viewerEnvironment(const std::string& display) {
  Environment env = {{"DISPLAY", display}, {"LIBGL_ALWAYS_SOFTWARE", "1"}};
#ifdef __SANITIZE_ADDRESS__
  env.emplace_back("ASAN_OPTIONS", "detect_leaks=0");
#endif
  return env;
}

pid_t spawn(const std::vector<std::string>& args, const Environment& env, const std::string& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    for (const auto& [k, v] : env) v.empty() ? unsetenv(k.c_str()) : setenv(k.c_str(), v.c_str(), 1);
    FILE* out = std::freopen(log.c_str(), "a", stdout);
    FILE* err = std::freopen(log.c_str(), "a", stderr);
    (void)out, (void)err;
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

int waitBounded(pid_t pid, double seconds) {
  if (pid <= 0) return -1;
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (Clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

int runBounded(const std::vector<std::string>& args, const Environment& env, const std::string& log,
               double seconds) {
  return waitBounded(spawn(args, env, log), seconds);
}

Xvfb::~Xvfb() {
  if (pid_ <= 0) return;
  kill(pid_, SIGTERM);
  int status = 0;
  for (int i = 0; i < 100 && waitpid(pid_, &status, WNOHANG) != pid_; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (waitpid(pid_, &status, WNOHANG) == 0) kill(pid_, SIGKILL), waitpid(pid_, &status, 0);
}

bool Xvfb::start(const std::string& binary, const std::string& log) {
  const int first = 200 + static_cast<int>(getpid() % 500);
  for (int n = first; n < first + 10; ++n) {
    const std::string lock = "/tmp/.X" + std::to_string(n) + "-lock";
    const std::string socket = "/tmp/.X11-unix/X" + std::to_string(n);
    if (std::filesystem::exists(lock) || std::filesystem::exists(socket)) continue;
    const std::string display = ":" + std::to_string(n);
    pid_ = fork();
    if (pid_ == 0) {
      FILE* out = std::freopen(log.c_str(), "a", stdout);
      FILE* err = std::freopen(log.c_str(), "a", stderr);
      (void)out, (void)err;
      execl(binary.c_str(), binary.c_str(), display.c_str(), "-screen", "0", "800x600x24", "-nolisten", "tcp",
            static_cast<char*>(nullptr));
      _exit(127);
    }
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    while (Clock::now() < deadline) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        break;  // lost a race for this display: try the next
      }
      if (std::filesystem::exists(socket)) {
        display_ = display;
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (pid_ > 0) kill(pid_, SIGKILL), waitpid(pid_, nullptr, 0), pid_ = -1;
  }
  return false;
}

std::string xdotool(const std::string& binary, const std::string& display, const std::string& args) {
  const std::string command = "DISPLAY=" + display + " timeout 10 " + binary + " " + args + " 2>&1";
  std::string out;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[256];
    while (fgets(buffer, sizeof buffer, pipe)) out += buffer;
    pclose(pipe);
  }
  return out;
}

}  // namespace tessera::testing
