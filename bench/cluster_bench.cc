// The cluster mode's figures (docs/PERFORMANCE.md and
// docs/CLUSTER.md "Figures"), against real nats-server and tessera-server
// processes on loopback, all on this machine's cores:
//
//   latency   one editor at 20 edits/s on a node that does not own the
//             document; edit-to-delta p50/p99 at a viewer on the owner and
//             at a viewer on a third node, and the editor's ack latency
//             (JetStream R3); then the same on one SQLite tessera-server.
//   failover  kill -9 of the owner, KILLS times (default 20): seconds from
//             the kill to the first delta a viewer on a survivor receives
//             (an editor on a survivor edits every 50 ms); the killed node
//             is started again before the next round.
//   fanout    10 editors at 20 edits/s each for 10 s, V viewers spread over
//             1 or 3 nodes; edit-to-delta p99 over every viewer, for V
//             doubling until p99 passes 50 ms.
//
// A scenario, not a Google Benchmark: the figures are latency
// distributions of several processes under load. Every loop is bounded in
// count and time.
//
//   build/release/bench/tessera_bench_cluster latency|failover|fanout [KILLS|MAXVIEWERS]
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cluster/cluster_run.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ClusterRun;
using Clock = std::chrono::steady_clock;

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))];
}

// When each version was sent (by whichever editor), for edit-to-delta.
class SendTimes {
 public:
  void record(uint64_t version, Clock::time_point sent) {
    std::lock_guard<std::mutex> lock(mutex_);
    sent_[version] = sent;
  }
  std::optional<Clock::time_point> of(uint64_t version) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = sent_.find(version);
    if (it == sent_.end()) return std::nullopt;
    return it->second;
  }

 private:
  std::mutex mutex_;
  std::map<uint64_t, Clock::time_point> sent_;
};

// A viewer that records, for every version its deltas cover, when it arrived.
struct TimedViewer {
  std::unique_ptr<Session> session;
  std::vector<std::pair<uint64_t, Clock::time_point>> arrivals;  // version, when; under *mutex
  std::shared_ptr<std::mutex> mutex = std::make_shared<std::mutex>();

  std::vector<std::pair<uint64_t, Clock::time_point>> copy() const {
    std::lock_guard<std::mutex> lock(*mutex);
    return arrivals;
  }
};

std::unique_ptr<Session> connectAndOpen(const client::SessionOptions& options, uint64_t doc, bool subscribe) {
  auto s = Session::connect(options);
  if (!s.isOk()) {
    std::fprintf(stderr, "connect: %s\n", s.status().message().c_str());
    return nullptr;
  }
  auto opened = (*s)->call(testing::openDocument(doc), 30);
  if (!opened.isOk() || !opened->has_ack()) return nullptr;
  if (subscribe) {
    auto sub = (*s)->call(
        testing::subscribe(doc, testing::kClusterBase, testing::kClusterMax, testing::kClusterAngle), 30);
    if (!sub.isOk() || !sub->has_ack()) return nullptr;
  }
  return std::move(*s);
}

void readDeltas(TimedViewer& v, std::atomic<bool>& stop) {
  while (!stop.load()) {
    auto m = v.session->receive(0.2);
    if (!m.isOk()) {
      if (client::isReceiveTimeout(m.status())) continue;
      return;
    }
    if (!m->has_delta()) continue;
    const auto now = Clock::now();
    std::lock_guard<std::mutex> lock(*v.mutex);
    for (uint64_t version = m->delta().from_version() + 1; version <= m->delta().to_version(); ++version) {
      v.arrivals.emplace_back(version, now);
    }
  }
}

// Edits at `rate` per second for `seconds`; the ack latency of each.
std::vector<double> editAtRate(Session& editor, uint64_t doc, double rate, double seconds, SendTimes& times,
                               int seed) {
  std::vector<double> acks;
  std::mt19937 rng(static_cast<uint32_t>(seed));
  const auto start = Clock::now();
  const auto period = std::chrono::duration<double>(1.0 / rate);
  for (int i = 0; Clock::now() - start < std::chrono::duration<double>(seconds); ++i) {
    std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(period * i));
    const auto sent = Clock::now();
    auto reply = editor.call(testing::smallMove(doc, rng, 0.002), 10);
    if (!reply.isOk() || !reply->has_ack()) continue;
    times.record(reply->ack().version(), sent);
    acks.push_back(std::chrono::duration<double, std::milli>(Clock::now() - sent).count());
  }
  return acks;
}

std::vector<double> deltaLatencies(const TimedViewer& v, SendTimes& times) {
  std::vector<double> ms;
  for (const auto& [version, when] : v.copy()) {
    if (auto sent = times.of(version))
      ms.push_back(std::chrono::duration<double, std::milli>(when - *sent).count());
  }
  return ms;
}

void printRow(const char* what, const std::vector<double>& ms) {
  std::printf("  %-44s n=%5zu  p50 %7.2f ms  p99 %7.2f ms  max %7.2f ms\n", what, ms.size(),
              percentile(ms, 0.5), percentile(ms, 0.99),
              ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end()));
}

int latency() {
  std::printf("latency: one editor at 20 edits/s for 20 s on node 1; the document's owner is node 0\n");
  auto run = ClusterRun::start(3);
  if (!run.isOk()) return std::fprintf(stderr, "%s\n", run.status().message().c_str()), 1;
  ClusterRun& c = **run;
  auto doc = c.createCube();
  if (!doc.isOk()) return 1;
  TimedViewer onOwner{connectAndOpen(c.session(0, "viewer", testing::kViewerToken), *doc, true), {}};
  TimedViewer onOther{connectAndOpen(c.session(2, "viewer", testing::kViewerToken), *doc, true), {}};
  auto editor = connectAndOpen(c.session(1, "editor", testing::kEditorToken), *doc, false);
  if (!onOwner.session || !onOther.session || !editor) return 1;
  std::atomic<bool> stop{false};
  std::thread r0(readDeltas, std::ref(onOwner), std::ref(stop)),
      r1(readDeltas, std::ref(onOther), std::ref(stop));
  SendTimes times;
  auto acks = editAtRate(*editor, *doc, 20, 20, times, 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  stop = true;
  r0.join();
  r1.join();
  printRow("cluster: ack (JetStream R3, via node 1)", acks);
  printRow("cluster: edit to delta, viewer on the owner", deltaLatencies(onOwner, times));
  printRow("cluster: edit to delta, viewer on node 2", deltaLatencies(onOther, times));
  run->reset();

  // The same on one tessera-server with its SQLite store.
  const std::string dir = testing::makeTempDir("tessera-bench-sqlite");
  auto server = testing::ServerProcess::start(dir + "/data");
  if (!server.isOk()) return 1;
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                              testing::fileBytes(testing::sourceTestDataPath("cube.tags")),
                              testing::kClusterMaxLevel),
      30);
  const uint64_t single = created->ack().document_id();
  TimedViewer viewer{connectAndOpen(server->session("viewer", server->adminToken()), single, true), {}};
  auto sqliteEditor = connectAndOpen(server->session("editor", server->adminToken()), single, false);
  stop = false;
  std::thread r2(readDeltas, std::ref(viewer), std::ref(stop));
  SendTimes singleTimes;
  auto singleAcks = editAtRate(*sqliteEditor, single, 20, 20, singleTimes, 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  stop = true;
  r2.join();
  printRow("single node: ack (SQLite, synchronous = FULL)", singleAcks);
  printRow("single node: edit to delta", deltaLatencies(viewer, singleTimes));
  std::printf("  ack p50 ratio cluster / SQLite: %.2f\n",
              percentile(acks, 0.5) / std::max(1e-9, percentile(singleAcks, 0.5)));
  return 0;
}

int failover(int kills) {
  std::printf(
      "failover: %d kill -9 of the owner; seconds from the kill to the first delta at a survivor's viewer\n",
      kills);
  auto run = ClusterRun::start(3);
  if (!run.isOk()) return std::fprintf(stderr, "%s\n", run.status().message().c_str()), 1;
  ClusterRun& c = **run;
  auto doc = c.createCube();
  if (!doc.isOk()) return 1;
  std::vector<double> seconds;
  int owner = 0;
  // The owner is whoever opens first: node 0's viewer, then whoever took over.
  auto ownerViewer = connectAndOpen(c.session(0, "viewer", testing::kViewerToken), *doc, true);
  for (int round = 0; round < kills; ++round) {
    const int survivor = (owner + 1) % 3;
    TimedViewer watcher{connectAndOpen(c.session(survivor, "viewer", testing::kViewerToken), *doc, true), {}};
    auto editor = connectAndOpen(c.session(survivor, "editor", testing::kEditorToken), *doc, false);
    if (!watcher.session || !editor) return 1;
    std::atomic<bool> stop{false};
    std::thread reader(readDeltas, std::ref(watcher), std::ref(stop));
    std::atomic<bool> editing{true};
    std::thread edits([&] {
      std::mt19937 rng(static_cast<uint32_t>(round));
      while (editing.load()) {
        (void)editor->send(testing::smallMove(*doc, rng, 0.002));
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    c.nodes[static_cast<size_t>(owner)]->kill9();
    const auto killed = Clock::now();
    const size_t before = watcher.copy().size();
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    double took = -1;
    // Reads happen on `reader`; poll its arrivals (appended only) for 30 s.
    for (int i = 0; i < 3000 && took < 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      // Deltas that arrived after the kill, from a version the old owner never sent.
      const auto snapshot = watcher.copy();
      for (size_t k = before; k < snapshot.size(); ++k) {
        if (snapshot[k].second > killed + std::chrono::milliseconds(100)) {
          took = std::chrono::duration<double>(snapshot[k].second - killed).count();
          break;
        }
      }
    }
    editing = false;
    edits.join();
    stop = true;
    reader.join();
    if (took < 0) {
      std::printf("  round %d: no delta within 30 s\n", round + 1);
    } else {
      seconds.push_back(took);
      std::printf("  round %d: owner node%d killed, first delta after %.2f s\n", round + 1, owner, took);
    }
    auto restarted = c.startNode(owner);
    if (!restarted.isOk()) return std::fprintf(stderr, "%s\n", restarted.message().c_str()), 1;
    owner = survivor;  // its editor's node took over (or the third node did: the next kill finds out)
    auto who = Session::connect(c.session(owner, "admin", c.nodes[static_cast<size_t>(owner)]->adminToken()));
    wire::ClientMessage stats;
    stats.mutable_stats();
    bool owns = false;
    if (who.isOk()) {
      auto reply = (*who)->call(stats, 10);
      if (reply.isOk()) {
        for (const auto& s : reply->stats_reply().stats())
          owns |= s.name() == "documents_owned" && s.value() > 0;
      }
    }
    if (!owns) owner = (owner + 1) % 3;
    ownerViewer = connectAndOpen(c.session(owner, "viewer", testing::kViewerToken), *doc, true);
  }
  std::vector<double> ms;
  for (double s : seconds) ms.push_back(s * 1000);
  printRow("kill -9 to first delta at a survivor", ms);
  return 0;
}

// V viewers over `nodes` nodes, 10 editors at 20 edits/s for 10 s: p99 of
// edit to delta over all viewers.
double fanoutRound(int nodes, int viewers, double* p50) {
  auto run = ClusterRun::start(nodes, 3000, {"--connections-per-address", "100000"});
  if (!run.isOk()) return -1;
  ClusterRun& c = **run;
  auto doc = c.createCube();
  if (!doc.isOk()) return -1;
  std::vector<TimedViewer> vs(static_cast<size_t>(viewers));
  for (int i = 0; i < viewers; ++i) {
    vs[static_cast<size_t>(i)].session =
        connectAndOpen(c.session(i % nodes, "viewer", testing::kViewerToken), *doc, true);
    if (!vs[static_cast<size_t>(i)].session) return -1;
  }
  std::atomic<bool> stop{false};
  std::vector<std::thread> readers;
  for (auto& v : vs) readers.emplace_back(readDeltas, std::ref(v), std::ref(stop));
  SendTimes times;
  std::vector<std::thread> editors;
  for (int e = 0; e < 10; ++e) {
    editors.emplace_back([&, e] {
      auto editor = connectAndOpen(c.session(e % nodes, "editor", testing::kEditorToken), *doc, false);
      if (editor) editAtRate(*editor, *doc, 20, 10, times, e);
    });
  }
  for (auto& t : editors) t.join();
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  stop = true;
  for (auto& t : readers) t.join();
  std::vector<double> all;
  for (const auto& v : vs) {
    auto ms = deltaLatencies(v, times);
    all.insert(all.end(), ms.begin(), ms.end());
  }
  *p50 = percentile(all, 0.5);
  return percentile(all, 0.99);
}

int fanout(int maxViewers) {
  std::printf(
      "fanout: 10 editors x 20 edits/s for 10 s; edit-to-delta over every viewer (all processes share this "
      "machine's cores)\n");
  for (int nodes : {1, 3}) {
    for (int viewers = 25; viewers <= maxViewers; viewers *= 2) {
      double p50 = 0;
      const double p99 = fanoutRound(nodes, viewers, &p50);
      std::printf("  %d node(s), %4d viewers: p50 %7.2f ms  p99 %7.2f ms%s\n", nodes, viewers, p50, p99,
                  p99 > 50 ? "  (over 50 ms)" : "");
      if (p99 < 0 || p99 > 50) break;
    }
  }
  return 0;
}

}  // namespace
}  // namespace tessera

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "latency";
  if (mode == "latency") return tessera::latency();
  if (mode == "failover") return tessera::failover(argc > 2 ? std::atoi(argv[2]) : 20);
  if (mode == "fanout") return tessera::fanout(argc > 2 ? std::atoi(argv[2]) : 800);
  std::fprintf(stderr, "usage: tessera_bench_cluster latency|failover [KILLS]|fanout [MAXVIEWERS]\n");
  return 2;
}
