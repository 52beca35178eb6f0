#include "client/replay/load.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <semaphore>
#include <random>
#include <set>
#include <sstream>
#include <thread>
#include <unordered_map>

#include "client/lib/document_view.h"
#include "client/replay/load_state.h"
#include "client/replay/replay.h"
#include "client/replay/viewer_pool.h"

namespace tessera::replay {

namespace {

using nlohmann::json;

double msBetween(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

void runEditor(const LoadOptions& o, int index, Clock::time_point hardDeadline, Shared& shared) {
  client::SessionOptions so = o.session;
  so.name = "editor-" + std::to_string(index + 1);
  auto connected = client::Session::connect(so);
  if (!connected.isOk()) return shared.error(so.name + ": " + connected.status().message());
  client::Session& s = **connected;
  // Editors open the document but do not subscribe: the viewers measure.
  if (Status st = openDocument(s, o.document, so.timeoutSeconds); !st.isOk()) return shared.error(so.name + ": " + st.message());
  ++shared.editorsReady;
  while (!shared.startEditing) {
    if (Clock::now() > hardDeadline) return shared.error(so.name + ": the run never started");
    (void)s.receive(0.05);  // presence meanwhile
  }
  const Clock::time_point start{Clock::duration(shared.startNs.load())};
  const auto drainDeadline = start + secondsOf(o.seconds + o.drainSeconds);
  std::mt19937_64 rng(o.seed * 1000003u + static_cast<uint64_t>(index));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<uint64_t> vertex(0, o.vertexCount == 0 ? 0 : o.vertexCount - 1);
  const auto period = secondsOf(1.0 / o.rate);
  auto next = start + period * index / std::max(o.editors, 1);
  std::unordered_map<uint64_t, Clock::time_point> outstanding;
  int64_t sentHere = 0;
  for (;;) {
    auto now = Clock::now();
    const bool editing = !shared.stopEditing && sentHere < o.maxEdits;
    if (editing && now >= next) {
      wire::ClientMessage m;
      auto* move = m.mutable_move_vertex();
      move->set_document_id(o.document);
      move->add_vertex_ids((static_cast<uint64_t>(o.vertexLevel) << 58) | vertex(rng));
      move->mutable_target()->set_x(unit(rng) * o.step);
      move->mutable_target()->set_y(unit(rng) * o.step);
      move->mutable_target()->set_z(unit(rng) * o.step);
      move->set_mode(wire::MOVE_MODE_OFFSET);
      now = Clock::now();
      auto seq = s.send(std::move(m));
      if (!seq.isOk()) return shared.error(so.name + ": " + seq.status().message());
      outstanding[*seq] = now;
      ++sentHere;
      ++shared.sent;
      next += period;
      if (next < now - period) next = now;  // fell behind: do not burst to catch up
    }
    if (!editing && (outstanding.empty() || now > drainDeadline)) break;
    const double wait = editing ? std::clamp(std::chrono::duration<double>(next - now).count(), 0.0005, 0.05) : 0.05;
    auto reply = s.receive(wait);
    if (!reply.isOk()) {
      if (client::isReceiveTimeout(reply.status())) continue;
      return shared.error(so.name + ": " + reply.status().message());
    }
    const auto received = Clock::now();
    const uint64_t seq = client::replyTo(*reply);
    auto it = outstanding.find(seq);
    if (reply->has_ack() && it != outstanding.end()) {
      ++shared.acked;
      const uint64_t version = reply->ack().version();
      uint64_t seen = shared.maxAckedVersion.load();
      while (version > seen && !shared.maxAckedVersion.compare_exchange_weak(seen, version)) {
      }
      std::lock_guard lock(shared.mu);
      shared.sendTimeOfVersion[version] = it->second;
      shared.ackLatencyMs.push_back(msBetween(it->second, received));
      outstanding.erase(it);
    } else if (reply->has_reject() && it != outstanding.end()) {
      ++shared.rejected;
      outstanding.erase(it);
      std::lock_guard lock(shared.mu);
      if (shared.errorMessages.size() < 20) {
        shared.errorMessages.push_back(so.name + ": " + wire::RejectReason_Name(reply->reject().reason()) + ": " +
                                       reply->reject().message());
      }
    } else if (reply->has_error() && reply->error().fatal()) {
      return shared.error(so.name + ": server error: " + reply->error().message());
    }
  }
  if (!outstanding.empty()) shared.error(so.name + ": " + std::to_string(outstanding.size()) + " edits never acknowledged");
  s.close();
}

void runViewer(const LoadOptions& o, int index, bool decode, Clock::time_point hardDeadline, Shared& shared,
               ViewerResult& out) {
  client::SessionOptions so = o.session;
  so.name = "viewer-" + std::to_string(index + 1);
  if (!o.viewerToken.empty()) so.token = o.viewerToken;
  so.timeoutSeconds = std::max(so.timeoutSeconds, o.connectSeconds);
  bool joining = true;
  shared.joining.acquire();
  auto joined = [&] {
    if (joining) shared.joining.release();
    joining = false;
  };
  auto done = [&] {
    joined();
    ++shared.viewersDone;
  };
  auto connected = client::Session::connect(so);
  if (!connected.isOk()) return shared.error(so.name + ": " + connected.status().message()), done();
  client::Session& s = **connected;
  if (Status st = openAndSubscribe(s, o.document, o.profile, nullptr, so.timeoutSeconds); !st.isOk()) {
    return shared.error(so.name + ": " + st.message()), done();
  }
  client::DocumentView view(o.document);
  out.decoded = decode;
  auto lastPing = Clock::now();
  std::optional<Clock::time_point> stopSeen;
  for (;;) {
    const auto now = Clock::now();
    if (now > hardDeadline) break;
    if (shared.stopViewing && !stopSeen) stopSeen = now;
    if (stopSeen && now - *stopSeen > std::chrono::duration<double>(o.drainSeconds)) break;
    if (shared.stopViewing && out.ready && out.version >= shared.maxAckedVersion.load()) break;
    if (now - lastPing > std::chrono::seconds(30)) {
      wire::ClientMessage ping;
      ping.mutable_ping();
      (void)s.send(ping);
      lastPing = now;
    }
    auto m = s.receive(out.ready ? o.viewerPollSeconds : 0.25);
    if (!m.isOk()) {
      if (client::isReceiveTimeout(m.status())) continue;
      shared.error(so.name + ": " + m.status().message());
      break;
    }
    const auto arrival = Clock::now();
    const ViewerEvent event = trackViewerMessage(*m, arrival, o.document, out, shared);
    if (event == ViewerEvent::kReady) joined();
    if (event == ViewerEvent::kGap) (void)s.send(subscribeMessage(o.document, o.profile));
    if (event == ViewerEvent::kFatal) {
      shared.error(so.name + ": server error: " + m->error().message());
      break;
    }
    if (decode) {
      if (Status st = view.apply(*m); !st.isOk() && !m->has_delta()) shared.error(so.name + ": " + st.message());
    }
  }
  if (decode && view.ready()) out.hash = view.surfaceHash();
  s.close();
  done();
}

json percentiles(std::vector<double> v) {
  json j = {{"count", v.size()}};
  if (v.empty()) return j;
  std::sort(v.begin(), v.end());
  auto at = [&](double p) {
    const size_t rank = static_cast<size_t>(std::ceil(p * static_cast<double>(v.size())));
    return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
  };
  auto round3 = [](double x) { return std::round(x * 1000) / 1000; };
  j["p50"] = round3(at(0.50));
  j["p90"] = round3(at(0.90));
  j["p99"] = round3(at(0.99));
  j["max"] = round3(v.back());
  return j;
}

struct ProcSample {
  bool ok = false;
  double cpuSeconds = 0;
  int64_t rssBytes = 0;
};

ProcSample sampleProcess(int pid) {
  ProcSample p;
  if (pid <= 0) return p;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(stat, text)) return p;
  // Fields after the command name (which may hold spaces) start at field 3.
  std::istringstream in(text.substr(text.rfind(')') + 2));
  std::vector<std::string> fields;
  for (std::string f; in >> f;) fields.push_back(f);
  if (fields.size() < 13) return p;
  const double ticks = static_cast<double>(sysconf(_SC_CLK_TCK));
  p.cpuSeconds = (std::stod(fields[11]) + std::stod(fields[12])) / ticks;  // utime, stime (fields 14, 15)
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) p.rssBytes = std::stoll(line.substr(6)) * 1024;
  }
  p.ok = true;
  return p;
}

}  // namespace

Expected<json> runLoad(const LoadOptions& o) {
  if (o.document == 0) return invalidArgument("--document is required");
  if (o.editors < 0 || o.editors > 100) return invalidArgument("--editors must be 0..100");
  if (o.viewers < 0 || o.viewers > 2000) return invalidArgument("--viewers must be 0..2000");
  if (!(o.rate > 0 && o.rate <= 200)) return invalidArgument("--rate must be in (0, 200] edits per second");
  if (!(o.seconds > 0 && o.seconds <= 3600)) return invalidArgument("--seconds must be in (0, 3600]");
  const int decode = o.decodeViewers < 0 ? std::min(o.viewers, 20) : std::min(o.decodeViewers, o.viewers);
  Shared shared;
  std::vector<ViewerResult> viewerResults(static_cast<size_t>(o.viewers));
  const auto begin = Clock::now();
  const auto hardDeadline = begin + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(o.connectSeconds + o.seconds + o.drainSeconds + 5));
  // Decoding viewers (and every viewer over TLS) get a thread each; the
  // counting ones share the pool's threads.
  const int threaded = o.session.tls || o.poolThreads <= 0 ? o.viewers : decode;
  std::vector<std::thread> viewerThreads;
  for (int i = 0; i < threaded; ++i) {
    viewerThreads.emplace_back(runViewer, std::cref(o), i, i < decode, hardDeadline, std::ref(shared),
                               std::ref(viewerResults[static_cast<size_t>(i)]));
  }
  const ViewerPoolOptions poolOptions{.firstIndex = threaded, .threads = std::max(o.poolThreads, 1)};
  viewerThreads.emplace_back(runViewerPool, std::cref(o), std::cref(poolOptions), hardDeadline, std::ref(shared),
                             std::span<ViewerResult>(viewerResults).subspan(static_cast<size_t>(threaded)));
  std::vector<std::thread> editorThreads;
  for (int i = 0; i < o.editors; ++i) editorThreads.emplace_back(runEditor, std::cref(o), i, hardDeadline, std::ref(shared));
  // Every viewer subscribed and every editor in (or failed) before the first
  // edit, then until no Presence came for 500 ms (the joins' fan-out).
  const auto connectDeadline = begin + secondsOf(o.connectSeconds);
  while ((shared.viewersReady + shared.viewersDone < o.viewers || shared.editorsReady + shared.errors < o.editors) &&
         Clock::now() < connectDeadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double connectMs = msBetween(begin, Clock::now());
  while (Clock::now() < connectDeadline &&
         Clock::now() - Clock::time_point(Clock::duration(shared.lastPresenceNs.load())) < std::chrono::milliseconds(500)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double settleMs = msBetween(begin, Clock::now()) - connectMs;
  const ProcSample cpuBefore = sampleProcess(o.serverPid);
  int64_t rssPeak = cpuBefore.rssBytes;
  const auto start = Clock::now();
  const auto editEnd = start + secondsOf(o.seconds);
  shared.startNs = start.time_since_epoch().count();
  shared.startEditing = true;
  int64_t lastAcked = 0;
  for (int second = 1; Clock::now() < editEnd; ++second) {
    std::this_thread::sleep_until(std::min(editEnd, start + std::chrono::seconds(second)));
    const ProcSample now = sampleProcess(o.serverPid);
    rssPeak = std::max(rssPeak, now.rssBytes);
    if (o.progress) {
      const int64_t acked = shared.acked;
      std::fprintf(stderr,
                   "[%3ds] edits sent %lld acked %lld (+%lld) rejected %lld | viewers ready %lld/%d deltas %lld gaps %lld "
                   "resyncs %lld | errors %lld%s\n",
                   second, static_cast<long long>(shared.sent.load()), static_cast<long long>(acked),
                   static_cast<long long>(acked - lastAcked), static_cast<long long>(shared.rejected.load()),
                   static_cast<long long>(shared.viewersReady.load()), o.viewers, static_cast<long long>(shared.deltas.load()),
                   static_cast<long long>(shared.gaps.load()), static_cast<long long>(shared.resyncs.load()),
                   static_cast<long long>(shared.errors.load()),
                   now.ok ? (" | server rss " + std::to_string(now.rssBytes >> 20) + " MiB").c_str() : "");
      lastAcked = acked;
    }
  }
  shared.stopEditing = true;
  for (auto& t : editorThreads) t.join();
  const auto editsDone = Clock::now();
  const ProcSample cpuAfter = sampleProcess(o.serverPid);
  rssPeak = std::max(rssPeak, cpuAfter.rssBytes);
  shared.stopViewing = true;
  for (auto& t : viewerThreads) t.join();
  const double editSeconds = std::chrono::duration<double>(editsDone - start).count();

  // Edit to delta: the send time of the edit whose Ack carried version V
  // against the arrival of the delta that brought the viewer to V (a delta
  // spans several versions when the server or a full queue batched edits).
  std::vector<double> toDelta;
  int64_t deltaBytes = 0, snapshotBytes = 0, readyViewers = 0, presenceBytes = 0, presenceMessages = 0;
  uint64_t minVersion = UINT64_MAX, maxVersion = 0;
  std::set<uint64_t> hashes;
  int decodedReady = 0;
  int64_t behind = 0;
  for (const ViewerResult& v : viewerResults) {
    if (v.version < shared.maxAckedVersion) ++behind;
    deltaBytes += v.deltaBytes;
    presenceBytes += v.presenceBytes;
    presenceMessages += v.presenceMessages;
    snapshotBytes += v.snapshotBytes;
    if (v.ready) ++readyViewers;
    minVersion = std::min(minVersion, v.version);
    maxVersion = std::max(maxVersion, v.version);
    if (v.decoded && v.hash != 0 && v.version == shared.maxAckedVersion) hashes.insert(v.hash), ++decodedReady;
    for (const auto& d : v.deltaTimes) {
      for (uint64_t version = d.fromVersion + 1; version <= d.toVersion; ++version) {
        auto it = shared.sendTimeOfVersion.find(version);
        if (it != shared.sendTimeOfVersion.end()) toDelta.push_back(msBetween(it->second, d.arrival));
      }
    }
  }
  if (o.viewers == 0) minVersion = 0;

  json report;
  report["format"] = "tessera-replay-report";
  report["version"] = 1;
  report["config"] = {{"document", o.document},
                      {"editors", o.editors},
                      {"viewers", o.viewers},
                      {"rate_per_editor", o.rate},
                      {"seconds", o.seconds},
                      {"max_edits_per_editor", o.maxEdits},
                      {"profile", {o.profile.base_level(), o.profile.max_level(), o.profile.angle_threshold_degrees()}},
                      {"display_only", o.profile.omit_vertex_ids()},
                      {"decoding_viewers", decode},
                      {"vertices", "v" + std::to_string(o.vertexLevel) + ":0.." + std::to_string(o.vertexCount - 1)}};
  report["connect_ms"] = std::round(connectMs);
  report["settle_ms"] = std::round(settleMs);
  report["edit_seconds"] = editSeconds;
  report["edits"] = {{"sent", shared.sent.load()},
                     {"acked", shared.acked.load()},
                     {"rejected", shared.rejected.load()},
                     {"throughput_per_second", editSeconds > 0 ? shared.acked / editSeconds : 0.0}};
  report["latency_ms"] = {{"edit_to_ack", percentiles(shared.ackLatencyMs)}, {"edit_to_delta", percentiles(toDelta)}};
  report["final_version"] = shared.maxAckedVersion.load();
  report["viewers"] = {{"ready_at_end", readyViewers},
                       {"gaps", shared.gaps.load()},
                       {"resyncs", shared.resyncs.load()},
                       {"deltas", shared.deltas.load()},
                       {"snapshot_bytes_per_viewer", o.viewers ? snapshotBytes / o.viewers : 0},
                       {"delta_bytes_per_viewer", o.viewers ? deltaBytes / o.viewers : 0},
                       {"bytes_per_second_per_viewer", o.viewers && editSeconds > 0 ? deltaBytes / o.viewers / editSeconds : 0.0},
                       {"version_min", minVersion},
                       {"version_max", maxVersion},
                       {"behind_at_end", behind},
                       {"presence_messages_per_viewer", o.viewers ? presenceMessages / o.viewers : 0},
                       {"presence_bytes_per_viewer", o.viewers ? presenceBytes / o.viewers : 0},
                       {"decoded_at_final_version", decodedReady},
                       {"decoded_hashes_agree", hashes.size() <= 1}};
  report["errors"] = {{"count", shared.errors.load()}, {"messages", shared.errorMessages}};
  json server = json::object();
  if (cpuBefore.ok && cpuAfter.ok) {
    server["pid"] = o.serverPid;
    server["cpu_percent"] = std::round(1000 * (cpuAfter.cpuSeconds - cpuBefore.cpuSeconds) / std::max(editSeconds, 1e-3)) / 10;
    server["rss_bytes"] = cpuAfter.rssBytes;
    server["rss_peak_bytes"] = rssPeak;
  }
  client::SessionOptions so = o.session;
  so.name = "tessera-replay-stats";
  if (auto s = client::Session::connect(so); s.isOk()) {
    wire::ClientMessage m;
    m.mutable_stats();
    auto reply = (*s)->call(m, 10);
    if (reply.isOk() && reply->has_stats_reply()) {
      json stats = json::object();
      for (const auto& stat : reply->stats_reply().stats()) stats[stat.name()] = stat.value();
      server["stats"] = stats;
    }
    (*s)->close();
  }
  report["server"] = server;
  rusage self{};
  getrusage(RUSAGE_SELF, &self);
  const double cpu = static_cast<double>(self.ru_utime.tv_sec + self.ru_stime.tv_sec) +
                     static_cast<double>(self.ru_utime.tv_usec + self.ru_stime.tv_usec) / 1e6;
  report["client"] = {{"cpu_seconds", std::round(cpu * 100) / 100},
                      {"threads", o.editors + threaded + (o.viewers > threaded ? poolOptions.threads : 0)},
                      {"pooled_viewers", o.viewers - threaded}};
  return report;
}

std::string summarize(const json& r) {
  auto lat = [](const json& p) {
    if (p.value("count", 0) == 0) return std::string("n/a");
    char buf[160];
    std::snprintf(buf, sizeof buf, "p50 %.2f  p90 %.2f  p99 %.2f  max %.2f ms (n=%lld)", p["p50"].get<double>(),
                  p["p90"].get<double>(), p["p99"].get<double>(), p["max"].get<double>(), p["count"].get<long long>());
    return std::string(buf);
  };
  std::ostringstream out;
  const json& c = r["config"];
  out << "tessera-replay load: " << c["editors"] << " editors x " << c["rate_per_editor"] << "/s, " << c["viewers"]
      << " viewers, " << r["edit_seconds"].get<double>() << " s\n";
  out << "  edits: " << r["edits"]["acked"] << " acked of " << r["edits"]["sent"] << " sent, " << r["edits"]["rejected"]
      << " rejected, " << r["edits"]["throughput_per_second"].get<double>() << " acked/s\n";
  out << "  edit -> ack:   " << lat(r["latency_ms"]["edit_to_ack"]) << "\n";
  out << "  edit -> delta: " << lat(r["latency_ms"]["edit_to_delta"]) << "\n";
  out << "  viewers: " << r["viewers"]["ready_at_end"] << " ready, " << r["viewers"]["behind_at_end"]
      << " behind the last acked version at the end, gaps " << r["viewers"]["gaps"] << ", resyncs "
      << r["viewers"]["resyncs"] << ", " << r["viewers"]["bytes_per_second_per_viewer"].get<double>() / 1024
      << " KiB/s each (snapshot " << r["viewers"]["snapshot_bytes_per_viewer"] << " B)\n";
  out << "  errors: " << r["errors"]["count"] << "\n";
  const json& s = r["server"];
  if (s.contains("cpu_percent")) {
    out << "  server: cpu " << s["cpu_percent"] << " %, rss " << (s["rss_bytes"].get<int64_t>() >> 20) << " MiB (peak "
        << (s["rss_peak_bytes"].get<int64_t>() >> 20) << " MiB)\n";
  }
  return out.str();
}

}  // namespace tessera::replay
