#include "cluster/nats_cluster.h"

#include <nats/nats.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "server/cluster/nats_server_info.h"

namespace tessera::testing {

namespace {

// Whether this nats-server (2.10 and later) can sync each write: then the
// test clusters run with sync_interval: always, as docs/CLUSTER.md tells
// operators to ("What an acknowledged edit survives"). Debian 12's 2.9.10
// refuses the option.
bool natsSyncsEachWrite() {
  static const bool syncs = [] {
    FILE* pipe = ::popen("nats-server --version 2>&1", "r");
    if (!pipe) return false;
    char text[128] = {};
    const size_t n = std::fread(text, 1, sizeof text - 1, pipe);
    ::pclose(pipe);
    const std::string out(text, n);
    const size_t v = out.find('v');
    return v != std::string::npos && cluster::supportsPerWriteSync(out.substr(v + 1));
  }();
  return syncs;
}

// Ports the kernel has just handed out and taken back: free, with a small
// race that a test run on loopback rarely meets. All are held until the
// last is picked: a port closed at once can be handed out again, and one
// run (ClusterFailover under ThreadSanitizer, session 17) got the same port
// as one server's route port and another's client port, so that server
// could not listen and the cluster had two of its three servers.
std::vector<int> freePorts(int count) {
  std::vector<int> held, ports;
  for (int i = 0; i < count; ++i) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    int port = 0;
    if (fd >= 0 && ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
      port = ntohs(address.sin_port);
    }
    if (fd >= 0) held.push_back(fd);
    ports.push_back(port);
  }
  for (int fd : held) ::close(fd);
  return ports;
}

// Each server's server_name, which is also how JetStream names a leader.
std::string serverName(int server) {
  return "n" + std::to_string(server + 1);
}

}  // namespace

Expected<NatsCluster> NatsCluster::start(int servers, const std::string& maxPayload) {
  NatsCluster cluster;
  // In $TMPDIR, where the suite's other temporary files go (deploy/test.sh
  // checks that the suite leaves nothing there).
  std::string pattern = (std::filesystem::temp_directory_path() / "tessera-nats-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) return ioError("mkdtemp failed for " + pattern);
  cluster.directory_ = pattern;
  cluster.servers_.resize(static_cast<size_t>(servers));
  const std::vector<int> ports = freePorts(2 * servers);
  for (size_t i = 0; i < cluster.servers_.size(); ++i) {
    cluster.servers_[i].clientPort = ports[2 * i];
    cluster.servers_[i].routePort = ports[2 * i + 1];
  }
  for (int i = 0; i < servers; ++i) {
    Server& s = cluster.servers_[static_cast<size_t>(i)];
    const std::string name = serverName(i);
    s.config = cluster.directory_ + "/" + name + ".conf";
    std::ofstream conf(s.config);
    conf << "server_name: " << name << "\n"
         << "listen: 127.0.0.1:" << s.clientPort << "\n"
         << "max_payload: " << maxPayload << "\n"
         << "jetstream { " << (natsSyncsEachWrite() ? "sync_interval: always, " : "") << "store_dir: \""
         << cluster.directory_ << "/" << name << "\", max_mem: 64MB, max_file: 2GB }\n";
    if (servers > 1) {
      conf << "cluster { name: tessera-test, listen: 127.0.0.1:" << s.routePort << ", routes: [";
      const char* separator = "";
      for (int j = 0; j < servers; ++j) {
        if (j == i) continue;
        conf << separator << "nats://127.0.0.1:" << cluster.servers_[static_cast<size_t>(j)].routePort;
        separator = ", ";
      }
      conf << "] }\n";
    }
  }
  for (int i = 0; i < servers; ++i) TESSERA_RETURN_IF_ERROR(cluster.launch(i));
  for (int i = 0; i < servers; ++i) TESSERA_RETURN_IF_ERROR(cluster.waitForJetStream(i));
  return cluster;
}

Status NatsCluster::launch(int server) {
  Server& s = servers_[static_cast<size_t>(server)];
  const std::string log = s.config + ".log";
  s.pid = ::fork();
  if (s.pid < 0) return ioError("fork failed");
  if (s.pid == 0) {
    FILE* out = std::freopen(log.c_str(), "a", stderr);
    (void)out;
    ::execlp("nats-server", "nats-server", "-c", s.config.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return Status::ok();
}

Status NatsCluster::waitForJetStream(int server, std::chrono::seconds limit) const {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  std::string last = "not tried";
  while (std::chrono::steady_clock::now() < deadline) {
    natsConnection* nc = nullptr;
    const std::string u = url(server);
    if (natsConnection_ConnectTo(&nc, u.c_str()) == NATS_OK) {
      jsCtx* js = nullptr;
      jsAccountInfo* info = nullptr;
      jsErrCode code = static_cast<jsErrCode>(0);
      natsStatus s = natsConnection_JetStream(&js, nc, nullptr);
      if (s == NATS_OK) s = js_GetAccountInfo(&info, js, nullptr, &code);
      if (info != nullptr) jsAccountInfo_Destroy(info);
      jsCtx_Destroy(js);
      natsConnection_Destroy(nc);
      if (s == NATS_OK) return Status::ok();
      last = natsStatus_GetText(s);
    } else {
      last = "cannot connect";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return ioError("nats-server " + std::to_string(server + 1) + " (" + url(server) +
                 "): JetStream not ready within the limit: " + last + "; see " +
                 servers_[static_cast<size_t>(server)].config + ".log");
}

NatsCluster::NatsCluster(NatsCluster&& other) noexcept
    : directory_(std::move(other.directory_)), servers_(std::move(other.servers_)) {
  other.servers_.clear();
  other.directory_.clear();
}

NatsCluster::~NatsCluster() {
  for (int i = 0; i < size(); ++i) kill9(i);
  if (!directory_.empty() && std::getenv("TESSERA_KEEP_NATS") == nullptr) {
    std::error_code ignored;
    std::filesystem::remove_all(directory_, ignored);
  }
}

Expected<std::unique_ptr<cluster::NatsLink>> NatsCluster::connect() const {
  cluster::NatsLinkOptions options;
  TESSERA_ASSIGN_OR_RETURN(options.urls, cluster::parseNatsUrls(urls()));
  return cluster::NatsLink::connect(options);
}

Expected<int> NatsCluster::leaderOf(const std::string& stream) const {
  TESSERA_ASSIGN_OR_RETURN(std::unique_ptr<cluster::NatsLink> link, connect());
  jsStreamInfo* info = nullptr;
  jsErrCode code = static_cast<jsErrCode>(0);
  const natsStatus s = js_GetStreamInfo(&info, link->jetStream(), stream.c_str(), nullptr, &code);
  if (s != NATS_OK) return link->error(s, "stream info of " + stream, code);
  const std::string leader =
      info->Cluster != nullptr && info->Cluster->Leader != nullptr ? info->Cluster->Leader : "";
  jsStreamInfo_Destroy(info);
  for (int i = 0; i < size(); ++i) {
    if (leader == serverName(i)) return i;
  }
  return ioError("stream " + stream + " has no leader among the test's servers ('" + leader + "')");
}

std::string NatsCluster::url(int server) const {
  return "nats://127.0.0.1:" + std::to_string(servers_[static_cast<size_t>(server)].clientPort);
}

std::string NatsCluster::urls() const {
  std::string all;
  for (int i = 0; i < size(); ++i) all += (i ? "," : "") + url(i);
  return all;
}

void NatsCluster::kill9(int server) {
  Server& s = servers_[static_cast<size_t>(server)];
  if (s.pid <= 0) return;
  ::kill(s.pid, SIGKILL);
  int status = 0;
  ::waitpid(s.pid, &status, 0);
  s.pid = -1;
}

Status NatsCluster::restart(int server) {
  kill9(server);
  return launch(server);
}

void NatsCluster::pause(int server) {
  if (servers_[static_cast<size_t>(server)].pid > 0)
    ::kill(servers_[static_cast<size_t>(server)].pid, SIGSTOP);
}

void NatsCluster::resume(int server) {
  if (servers_[static_cast<size_t>(server)].pid > 0)
    ::kill(servers_[static_cast<size_t>(server)].pid, SIGCONT);
}

}  // namespace tessera::testing
