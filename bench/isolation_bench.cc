// Work isolation (docs/PERFORMANCE.md): a bystander's edit-to-delta latency on a
// small document of its own while another client makes the server do bulk
// work on a large one:
//   (a) creating a 2.6-million-triangle mesh (binary PLY, just under the
//       48 MiB mesh limit),
//   (b) subscribing to it with a profile whose first tessellation is large,
//   (c) subscribing with a profile over its triangle budget (refused).
// Prints p50/p99/max per phase, the refusal time, and the server's resident
// memory after each phase. A scenario, not a Google Benchmark: the number is
// a latency distribution under a concurrent load, measured against the real
// server binary (TESSERA_SERVER_BINARY runs another build, for the figures
// before a change). Bounded: every phase ends when its bulk request does or
// after 300 s.
//
//   build/release/bench/tessera_bench_isolation [TRIANGLES]   # default 2,600,000
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <future>
#include <string>
#include <thread>

#include "integration/bystander.h"
#include "integration/messages.h"
#include "integration/server_process.h"

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;

// A bumpy torus as binary little-endian PLY, `triangles` rounded to a grid.
std::string torusPly(int64_t triangles) {
  const int n = static_cast<int>(std::sqrt(static_cast<double>(triangles) / 2.0));
  const int nu = n, nv = n;
  std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(nu * nv) +
                       "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                       std::to_string(2 * nu * nv) + "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string out = header;
  out.reserve(header.size() + static_cast<size_t>(nu) * nv * (12 + 2 * 13));
  auto put = [&](const void* p, size_t n) { out.append(static_cast<const char*>(p), n); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      const double r = 0.3 + 0.01 * std::sin(7 * u) * std::cos(5 * v);
      const float p[3] = {static_cast<float>((1 + r * std::cos(v)) * std::cos(u)),
                          static_cast<float>((1 + r * std::cos(v)) * std::sin(u)),
                          static_cast<float>(r * std::sin(v))};
      put(p, sizeof p);
    }
  }
  auto id = [&](int i, int j) { return static_cast<int32_t>(((i + nu) % nu) * nv + (j + nv) % nv); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const uint8_t three = 3;
      const int32_t a[3] = {id(i, j), id(i + 1, j), id(i + 1, j + 1)};
      const int32_t b[3] = {id(i, j), id(i + 1, j + 1), id(i, j + 1)};
      put(&three, 1), put(a, sizeof a);
      put(&three, 1), put(b, sizeof b);
    }
  }
  return out;
}

double residentMiB(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return 0;
}

// Runs the bystander, one edit every 20 ms, until `bulk` is ready (and at
// least `minimumEdits`), bounded by 300 s.
template <typename T>
testing::Bystander::Latencies during(testing::Bystander& bystander, std::future<T>& bulk, int minimumEdits) {
  const auto deadline = Clock::now() + std::chrono::seconds(300);
  int sent = 0;
  auto l = bystander.runUntil([&] {
    return Clock::now() > deadline ||
           (++sent > minimumEdits && bulk.wait_for(std::chrono::seconds(0)) == std::future_status::ready);
  });
  if (!l.isOk()) {
    std::fprintf(stderr, "bystander failed: %s\n", l.status().message().c_str());
    return {};
  }
  return *l;
}

void report(const char* phase, const testing::Bystander::Latencies& l, double seconds, pid_t server,
            const std::string& outcome) {
  std::printf(
      "%-34s bystander edits %4zu  p50 %7.1f ms  p99 %7.1f ms  max %7.1f ms | bulk %7.3f s, %s | server RSS "
      "%6.0f MiB\n",
      phase, l.ms.size(), l.median(), l.at(0.99), l.max(), seconds, outcome.c_str(), residentMiB(server));
  std::fflush(stdout);
}

int run(int64_t triangles) {
  const std::string dir = testing::makeTempDir("tessera-bench-isolation");
  auto server = testing::ServerProcess::start(dir + "/data", {"--max-mesh-bytes", "50331648"});
  if (!server.isOk()) return std::fprintf(stderr, "%s\n", server.status().message().c_str()), 1;
  auto admin = client::Session::connect(server->session("admin", server->adminToken()));
  if (!admin.isOk()) return std::fprintf(stderr, "%s\n", admin.status().message().c_str()), 1;
  auto bystander = testing::Bystander::start(*server, **admin);
  if (!bystander.isOk()) return std::fprintf(stderr, "%s\n", bystander.status().message().c_str()), 1;
  const std::string ply = torusPly(triangles);
  std::printf("mesh: %zu bytes of binary PLY, %lld triangles; server RSS at start %.0f MiB\n", ply.size(),
              static_cast<long long>(2 * static_cast<int64_t>(std::sqrt(triangles / 2.0)) *
                                     static_cast<int64_t>(std::sqrt(triangles / 2.0))),
              residentMiB(server->pid()));
  report("(idle) no bulk work", (*bystander)->run(100).value(), 0, server->pid(), "-");

  // (a) create
  auto bulkSession = client::Session::connect(server->session("bulk", server->adminToken()));
  if (!bulkSession.isOk()) return 1;
  client::Session& bulk = **bulkSession;
  wire::ClientMessage create = testing::createDocument("large", ply, "", 3);
  create.mutable_create_document()->set_mesh_format(wire::MESH_FORMAT_PLY);
  auto t0 = Clock::now();
  auto created = std::async(std::launch::async, [&] { return bulk.call(create, 300); });
  auto la = during(**bystander, created, 50);
  auto c = created.get();
  const bool ok = c.isOk() && c->has_ack();
  report("(a) create the large mesh", la, std::chrono::duration<double>(Clock::now() - t0).count(),
         server->pid(), ok ? "created" : (c.isOk() ? c->DebugString() : c.status().message()));
  if (!ok) return 1;
  const uint64_t doc = c->ack().document_id();
  if (!bulk.call(testing::openDocument(doc), 300)->has_ack()) return 1;

  // (b) a large profile's first snapshot: base 0, max 1, within the default
  // budget of 4 million triangles.
  t0 = Clock::now();
  auto subscribed = std::async(std::launch::async, [&] {
    auto ack = bulk.call(testing::subscribe(doc, 0, 1, 30), 300);
    if (!ack.isOk() || !ack->has_ack()) return ack;
    client::DocumentView view(doc);  // until the whole snapshot is here
    while (!view.ready()) {
      auto m = bulk.receive(300);
      if (!m.isOk()) return m;
      if (!view.apply(*m).isOk()) break;
    }
    return ack;
  });
  auto lb = during(**bystander, subscribed, 50);
  auto sb = subscribed.get();
  report("(b) subscribe a large profile", lb, std::chrono::duration<double>(Clock::now() - t0).count(),
         server->pid(),
         sb.isOk() && sb->has_ack() ? "snapshot received"
                                    : (sb.isOk() ? sb->ShortDebugString() : sb.status().message()));
  wire::ClientMessage unsubscribe;  // drops the large view (its last subscriber)
  unsubscribe.mutable_unsubscribe()->set_document_id(doc);
  (void)bulk.call(unsubscribe, 300);

  // (c) over budget: base level 1 alone is four times the mesh.
  double refusal = 0;
  auto refused = std::async(std::launch::async, [&] {
    const auto start = Clock::now();
    auto reply = bulk.call(testing::subscribe(doc, 1, 2, 30), 300);
    refusal = std::chrono::duration<double>(Clock::now() - start).count();
    return reply;
  });
  auto lc = during(**bystander, refused, 50);
  auto rc = refused.get();
  report("(c) subscribe over budget", lc, refusal, server->pid(),
         rc.isOk() && rc->has_reject() ? "refused: " + rc->reject().message().substr(0, 60) : "not refused");
  // Leave everything: memory after the bulk client is gone.
  bulk.close();
  // The document closes with its last client; its memory goes back to the
  // system once the bulk work it had queued is done.
  const auto closed = Clock::now();
  while (residentMiB(server->pid()) > 200 && Clock::now() - closed < std::chrono::seconds(120)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  std::printf("resident memory below 200 MiB %.1f s after the bulk client left (or gave up after 120 s)\n",
              std::chrono::duration<double>(Clock::now() - closed).count());
  report("(after) bulk client gone", (*bystander)->run(20).value(), 0, server->pid(), "-");
  if (Status acked = (*bystander)->awaitAcks(); !acked.isOk())
    std::fprintf(stderr, "bystander: %s\n", acked.message().c_str());
  server->stop();
  return 0;
}

}  // namespace
}  // namespace tessera

int main(int argc, char** argv) {
  const int64_t triangles = argc > 1 ? std::atoll(argv[1]) : 2'600'000;
  return tessera::run(triangles);
}
