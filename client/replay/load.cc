#include "client/replay/load.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <semaphore>
#include <thread>
#include <unordered_map>

#include "client/lib/document_view.h"
#include "client/replay/hgrm.h"
#include "client/replay/load_report.h"
#include "client/replay/load_state.h"
#include "client/replay/proc_sample.h"
#include "client/replay/replay.h"
#include "client/replay/send_schedule.h"
#include "client/replay/server_window.h"
#include "client/replay/viewer_pool.h"

namespace tessera::replay {

namespace {

using nlohmann::json;

// How long before a send is due an editor stops reading replies and
// sleeps until it (editorLoop).
constexpr double kPreciseSleepSeconds = 0.002;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

double secondsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// Rejections that no later edit can escape: the token or the document will
// not do, so the run stops rather than collecting the same refusal for its
// whole duration.
bool refusesTheRun(wire::RejectReason reason) {
  return reason == wire::REJECT_REASON_PERMISSION_DENIED || reason == wire::REJECT_REASON_NOT_AUTHENTICATED ||
         reason == wire::REJECT_REASON_NOT_OPEN;
}

void editorLoop(const LoadOptions& o, int index, Clock::time_point hardDeadline, Shared& shared,
                std::vector<int64_t>& sentPerSecond, std::vector<double>& lateness) {
  client::SessionOptions so = o.session;
  so.name = "editor-" + std::to_string(index + 1);
  auto connected = client::Session::connect(so);
  if (!connected.isOk()) return shared.error(so.name + ": " + connected.status().message());
  client::Session& s = **connected;
  // Editors open the document but do not subscribe: the viewers measure.
  if (Status st = openDocument(s, o.document, so.timeoutSeconds); !st.isOk())
    return shared.error(so.name + ": " + st.message());
  ++shared.editorsReady;
  while (!shared.startEditing) {
    if (shared.stopped) return;
    if (Clock::now() > hardDeadline) return shared.error(so.name + ": the run never started");
    (void)s.receive(0.05);  // presence meanwhile
  }
  const Clock::time_point start{Clock::duration(shared.startNs.load())};
  const auto drainDeadline = start + secondsOf(o.seconds + o.drainSeconds);
  std::mt19937_64 rng(o.seed * 1000003u + static_cast<uint64_t>(index));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<uint64_t> vertex(0, o.vertexCount == 0 ? 0 : o.vertexCount - 1);
  // Every send's due time is fixed from the start (send_schedule.h); an
  // edit's latency counts from it, and a send that goes out after it is
  // late by the difference: a tester that falls behind shows as latency.
  SendSchedule schedule(o.arrivals, o.rate, start, static_cast<double>(index) / std::max(o.editors, 1),
                        o.seed * 7919u + static_cast<uint64_t>(index));
  const auto editEnd = start + secondsOf(o.seconds);
  std::unordered_map<uint64_t, Clock::time_point> outstanding;
  int64_t sentHere = 0;
  for (;;) {
    if (shared.stopped) return s.close();  // the outstanding edits no longer matter
    auto now = Clock::now();
    const auto next = schedule.due();
    // The schedule, not the clock of the main thread, ends the editing.
    const bool editing = sentHere < o.maxEdits && next < editEnd;
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
      outstanding[*seq] = next;
      lateness.push_back(msBetween(next, now));
      const auto second =
          static_cast<size_t>(std::max(0.0, std::chrono::duration<double>(next - start).count()));
      if (sentPerSecond.size() <= second) sentPerSecond.resize(second + 1);
      ++sentPerSecond[second];
      ++sentHere;
      ++shared.sent;
      schedule.advance();  // never skipped: a late tester sends its backlog, each send late
    }
    if (!editing && (outstanding.empty() || now > drainDeadline)) break;
    // Replies are read until shortly before the next send is due; the last
    // stretch is slept precisely (a receive's timeout oversleeps by up to a
    // millisecond, which would make every send late).
    const double untilDue = std::chrono::duration<double>(next - now).count();
    if (editing && untilDue > 0 && untilDue <= kPreciseSleepSeconds) {
      std::this_thread::sleep_until(next);
      continue;
    }
    const double wait = editing ? std::clamp(untilDue - kPreciseSleepSeconds, 0.0, 0.05) : 0.05;
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
      shared.ackSamples.push_back({msBetween(start, it->second) / 1000, msBetween(it->second, received)});
      outstanding.erase(it);
    } else if (reply->has_reject() && it != outstanding.end()) {
      ++shared.rejected;
      const std::string why = so.name + ": " + wire::RejectReason_Name(reply->reject().reason()) + ": " +
                              reply->reject().message();
      if (refusesTheRun(reply->reject().reason())) return shared.stop(why);
      std::lock_guard lock(shared.mu);
      shared.rejectedAt.push_back(msBetween(start, it->second) / 1000);
      outstanding.erase(it);
      if (shared.errorMessages.size() < 20) shared.errorMessages.push_back(why);
    } else if (reply->has_error() && reply->error().fatal()) {
      return shared.error(so.name + ": server error: " + reply->error().message());
    }
  }
  // What was due before the end and never went out (the run stopped while
  // the tester was behind) is dropped; --max-edits ends the offer instead.
  if (sentHere < o.maxEdits)
    for (; schedule.due() < editEnd; schedule.advance()) ++shared.dropped;
  if (!outstanding.empty())
    shared.error(so.name + ": " + std::to_string(outstanding.size()) + " edits never acknowledged");
  s.close();
}

void runEditor(const LoadOptions& o, int index, Clock::time_point hardDeadline, Shared& shared) {
  std::vector<int64_t> sentPerSecond;
  std::vector<double> lateness;
  editorLoop(o, index, hardDeadline, shared, sentPerSecond, lateness);
  std::lock_guard lock(shared.mu);
  shared.lateness.insert(shared.lateness.end(), lateness.begin(), lateness.end());
  if (shared.sentPerSecond.size() < sentPerSecond.size()) shared.sentPerSecond.resize(sentPerSecond.size());
  for (size_t i = 0; i < sentPerSecond.size(); ++i) shared.sentPerSecond[i] += sentPerSecond[i];
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
  if (Status st = openDocument(s, o.document, so.timeoutSeconds); !st.isOk()) {
    return shared.error(so.name + ": " + st.message()), done();
  }
  if (auto subscribed = s.call(subscribeMessage(o, index, shared), so.timeoutSeconds);
      !subscribed.isOk() || !subscribed->has_ack()) {
    return shared.error(so.name + ": subscribe: " +
                        (subscribed.isOk() ? subscribed->ShortDebugString() : subscribed.status().message())),
           done();
  }
  Clock::time_point lastView = Clock::now();
  client::DocumentView view(o.document);
  out.decoded = decode;
  auto lastPing = Clock::now();
  std::optional<Clock::time_point> stopSeen;
  for (;;) {
    const auto now = Clock::now();
    if (now > hardDeadline || shared.stopped) break;
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
    if (event == ViewerEvent::kGap) (void)s.send(subscribeMessage(o, index, shared));
    if (!shared.stopViewing && out.ready) {
      if (auto view = viewIfDue(o, index, shared, lastView)) (void)s.send(std::move(*view));
    }
    if (event == ViewerEvent::kFatal) {
      shared.error(so.name + ": server error: " + m->error().message());
      break;
    }
    if (decode) {
      if (Status st = view.apply(*m); !st.isOk() && !m->has_delta())
        shared.error(so.name + ": " + st.message());
    }
  }
  if (decode && view.ready()) {
    if (!o.cameras) {
      out.hash = view.surfaceHash();  // every viewer of one profile holds the same surface
    } else if (Status same = view.verifySurface(); !same.isOk()) {
      shared.error(so.name + ": " + same.message());  // each camera's tiles: their own hash
    }
  }
  s.close();
  done();
}

// Before any load: the editors' token (and the viewers', if another) must
// be accepted and open the document, so that a wrong token or a missing
// document stops the run in seconds with the server's reason, instead of
// every connection failing alike for the whole run.
Status checkAccess(const LoadOptions& o) {
  auto check = [&](const std::string& token, const char* whose) -> Status {
    client::SessionOptions so = o.session;
    so.name = "tessera-replay-check";
    so.token = token;
    auto session = client::Session::connect(so);
    if (!session.isOk()) return session.status().withContext(std::string("the ") + whose + " token");
    Status opened = openDocument(**session, o.document, so.timeoutSeconds);
    (*session)->close();
    return opened.isOk() ? opened : opened.withContext(std::string("the ") + whose + " token");
  };
  TESSERA_RETURN_IF_ERROR(
      check(o.session.token, o.viewerToken.empty() ? "editors' and viewers'" : "editors'"));
  if (!o.viewerToken.empty() && o.viewers > 0) TESSERA_RETURN_IF_ERROR(check(o.viewerToken, "viewers'"));
  return Status::ok();
}

// Sleeps until `until` in short steps, returning early once the run stops.
void sleepUnlessStopped(Clock::time_point until, const Shared& shared) {
  for (auto now = Clock::now(); now < until && !shared.stopped; now = Clock::now()) {
    std::this_thread::sleep_for(std::min<Clock::duration>(until - now, std::chrono::milliseconds(20)));
  }
}

void printProgress(int second, int viewers, const Shared& shared, int64_t& lastAcked, const ProcSample& now) {
  const int64_t acked = shared.acked;
  std::fprintf(
      stderr,
      "[%3ds] edits sent %lld acked %lld (+%lld) rejected %lld | viewers ready %lld/%d deltas %lld gaps %lld "
      "resyncs %lld | errors %lld%s\n",
      second, static_cast<long long>(shared.sent.load()), static_cast<long long>(acked),
      static_cast<long long>(acked - lastAcked), static_cast<long long>(shared.rejected.load()),
      static_cast<long long>(shared.viewersReady.load()), viewers,
      static_cast<long long>(shared.deltas.load()), static_cast<long long>(shared.gaps.load()),
      static_cast<long long>(shared.resyncs.load()), static_cast<long long>(shared.errors.load()),
      now.ok ? (" | server rss " + std::to_string(now.rssBytes >> 20) + " MiB").c_str() : "");
  lastAcked = acked;
}

// Connects everyone, edits for the run's time, drains; fills `run`.
void runConnections(const LoadOptions& o, Shared& shared, LoadRunData& run) {
  const auto begin = run.begin;
  const auto hardDeadline = begin + secondsOf(o.connectSeconds + o.seconds + o.drainSeconds + 5);
  // Decoding viewers (and every viewer over TLS) get a thread each; the
  // counting ones share the pool's threads.
  const int decode = run.decodingViewers;
  const int threaded = run.threadedViewers = o.session.tls || o.poolThreads <= 0 ? o.viewers : decode;
  std::vector<std::thread> viewerThreads;
  for (int i = 0; i < threaded; ++i) {
    viewerThreads.emplace_back(runViewer, std::cref(o), i, i < decode, hardDeadline, std::ref(shared),
                               std::ref(run.viewers[static_cast<size_t>(i)]));
  }
  const ViewerPoolOptions poolOptions{.firstIndex = threaded, .threads = std::max(o.poolThreads, 1)};
  run.poolThreads = poolOptions.threads;
  viewerThreads.emplace_back(runViewerPool, std::cref(o), std::cref(poolOptions), hardDeadline,
                             std::ref(shared),
                             std::span<ViewerResult>(run.viewers).subspan(static_cast<size_t>(threaded)));
  std::vector<std::thread> editorThreads;
  for (int i = 0; i < o.editors; ++i)
    editorThreads.emplace_back(runEditor, std::cref(o), i, hardDeadline, std::ref(shared));
  // Every viewer subscribed and every editor in (or failed) before the first
  // edit, then until no Presence came for 500 ms (the joins' fan-out).
  const auto connectDeadline = begin + secondsOf(o.connectSeconds);
  while ((shared.viewersReady + shared.viewersDone < o.viewers ||
          shared.editorsReady + shared.errors < o.editors) &&
         Clock::now() < connectDeadline && !shared.stopped) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  run.connectMs = msBetween(begin, Clock::now());
  while (Clock::now() < connectDeadline && !shared.stopped &&
         Clock::now() - Clock::time_point(Clock::duration(shared.lastPresenceNs.load())) <
             std::chrono::milliseconds(500)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  run.settleMs = msBetween(begin, Clock::now()) - run.connectMs;
  if (!shared.stopped) {
    // The server's counters at the start of the window (server_window.h).
    auto stats = fetchServerStats(o.session);
    if (stats.isOk()) {
      run.statsStart = std::move(*stats);
    } else {
      run.statsError = stats.status().message();
    }
    // The schedule starts a little ahead, so that editors waiting for the
    // start (in 50 ms receives) are ready before their first send is due.
    run.start = Clock::now() + std::chrono::milliseconds(100);
    run.started = true;
    const auto editEnd = run.start + secondsOf(o.seconds);
    shared.startNs = run.start.time_since_epoch().count();
    shared.startEditing = true;
    int64_t lastAcked = 0;
    sleepUnlessStopped(run.start, shared);
    // CPU from the start: over the window (edit_seconds) and each second,
    // the tester's and the server's.
    run.cpuBefore = sampleProcess(o.serverPid);
    run.rssPeak = run.cpuBefore.rssBytes;
    run.testerCpuBefore = processCpuSeconds();
    auto lastAt = Clock::now();
    double lastTester = run.testerCpuBefore;
    ProcSample lastServer = run.cpuBefore;
    for (int second = 1; Clock::now() < editEnd && !shared.stopped; ++second) {
      sleepUnlessStopped(std::min(editEnd, run.start + std::chrono::seconds(second)), shared);
      if (shared.stopped) break;
      const ProcSample now = sampleProcess(o.serverPid);
      const auto at = Clock::now();
      const double tester = processCpuSeconds(), elapsed = std::max(1e-3, secondsBetween(lastAt, at));
      std::optional<double> server;
      if (now.ok && lastServer.ok) server = 100 * (now.cpuSeconds - lastServer.cpuSeconds) / elapsed;
      run.cpuPerSecond.push_back({100 * (tester - lastTester) / elapsed, server});
      lastAt = at, lastTester = tester, lastServer = now;
      run.rssPeak = std::max(run.rssPeak, now.rssBytes);
      if (o.progress) printProgress(second, o.viewers, shared, lastAcked, now);
    }
  }
  for (auto& t : editorThreads) t.join();
  run.editsDone = Clock::now();
  run.testerCpuAfter = processCpuSeconds();
  run.cpuAfter = sampleProcess(o.serverPid);
  run.rssPeak = std::max(run.rssPeak, run.cpuAfter.rssBytes);
  shared.stopViewing = true;
  for (auto& t : viewerThreads) t.join();
  if (run.started && !shared.stopped) {
    auto stats = fetchServerStats(o.session);
    if (stats.isOk()) {
      run.statsEnd = std::move(*stats);
    } else {
      run.statsError = stats.status().message();
    }
  }
}

}  // namespace

Expected<json> runLoad(const LoadOptions& o) {
  if (o.document == 0) return invalidArgument("--document is required");
  if (o.editors < 0 || o.editors > 100) return invalidArgument("--editors must be 0..100");
  if (o.viewers < 0 || o.viewers > 2000) return invalidArgument("--viewers must be 0..2000");
  if (!(o.rate > 0 && o.rate <= 200)) return invalidArgument("--rate must be in (0, 200] edits per second");
  if (!(o.seconds > 0 && o.seconds <= 3600)) return invalidArgument("--seconds must be in (0, 3600]");
  Shared shared;
  LoadRunData run;
  run.begin = Clock::now();
  run.decodingViewers = o.decodeViewers < 0 ? std::min(o.viewers, 20) : std::min(o.decodeViewers, o.viewers);
  run.viewers.resize(static_cast<size_t>(o.viewers));
  if (Status access = checkAccess(o); !access.isOk()) {
    // No server to reach (or no answer in time) is a plain failure; a
    // server's refusal stops the run with its reason.
    if (isTransient(access)) return access.withContext("load");
    shared.stop(access.message());
  } else {
    runConnections(o, shared, run);
  }
  LoadLatencies latencies;
  json report = buildLoadReport(o, shared, run, &latencies);
  if (!o.hgrmPrefix.empty()) {
    // The latency samples for HdrHistogram's tools (hgrm.h).
    json files = json::array();
    auto write = [&](const char* name, const std::vector<double>& samples) -> Status {
      const std::string path = o.hgrmPrefix + "-" + name + ".hgrm";
      std::ofstream out(path);
      out << percentileDistribution(samples);
      if (!out.flush()) return ioError(path + ": cannot write");
      files.push_back(path);
      return Status::ok();
    };
    TESSERA_RETURN_IF_ERROR(write("edit_to_ack", latencies.toAck));
    TESSERA_RETURN_IF_ERROR(write("edit_to_delta", latencies.toDelta));
    if (o.cameras) TESSERA_RETURN_IF_ERROR(write("edit_to_tiles", latencies.toTiles));
    report["hgrm_files"] = files;
  }
  return report;
}

}  // namespace tessera::replay
