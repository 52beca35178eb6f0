#include "integration/server_process.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

namespace tessera::testing {

Expected<ServerProcess> ServerProcess::start(const std::string& dataDirectory,
                                             const std::vector<std::string>& extraArgs) {
  ServerProcess p;
  const std::string base = std::filesystem::path(dataDirectory).parent_path().string();
  const std::string portFile = dataDirectory + ".port";
  const std::string tokenFile = dataDirectory + ".admin";
  p.adminToken_ = "admin-token-for-tests";
  std::ofstream(tokenFile) << p.adminToken_ << "\n";
  std::filesystem::remove(portFile);
  // TESSERA_SERVER_BINARY runs another build (benchmarks compare before and after).
  const char* binary = std::getenv("TESSERA_SERVER_BINARY");
  std::vector<std::string> args = {binary != nullptr ? binary : TESSERA_SERVER_PATH,
                                   "--data",
                                   dataDirectory,
                                   "--port",
                                   "0",
                                   "--port-file",
                                   portFile,
                                   "--admin-token-file",
                                   tokenFile};
  args.insert(args.end(), extraArgs.begin(), extraArgs.end());
  const std::string log = dataDirectory + ".log";
  p.pid_ = fork();
  if (p.pid_ < 0) return ioError("fork failed");
  if (p.pid_ == 0) {
    // The server's structured log goes to a file next to the data.
    FILE* out = std::freopen(log.c_str(), "a", stderr);
    (void)out;
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline) {
    std::ifstream in(portFile);
    int port = 0;
    if (in >> port && port > 0) {
      p.port_ = static_cast<uint16_t>(port);
      return p;
    }
    int status = 0;
    if (waitpid(p.pid_, &status, WNOHANG) == p.pid_) {
      p.pid_ = -1;
      return ioError("tessera-server exited at start; see " + log);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return ioError("tessera-server did not report its port within 20 s");
}

ServerProcess::ServerProcess(ServerProcess&& other) noexcept
    : pid_(std::exchange(other.pid_, -1)), port_(other.port_), adminToken_(std::move(other.adminToken_)) {}

ServerProcess::~ServerProcess() {
  if (pid_ > 0) kill9();
}

int ServerProcess::stop() {
  if (pid_ <= 0) return -1;
  kill(pid_, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill9();
  return -SIGKILL;
}

void ServerProcess::kill9() {
  if (pid_ <= 0) return;
  kill(pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
}

}  // namespace tessera::testing
