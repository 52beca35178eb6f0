#include "client/replay/load_command.h"

#include <cstdio>
#include <fstream>

#include "client/replay/load.h"
#include "client/replay/replay.h"
#include "client/replay/thresholds.h"

namespace tessera::replay {

CLI::App* addLoadCommand(CLI::App& app, LoadArgs& a) {
  CLI::App* load = app.add_subcommand(
      "load", "a bounded load run: progress on stderr, a summary on stdout, JSON with --report");
  addConnectionOptions(*load, a.connection);
  load->add_option("--viewer-token", a.viewerToken, "the viewers' token (default: --token)");
  load->add_option("--document", a.document, "the document to edit and watch")
      ->required()
      ->check(CLI::PositiveNumber);
  load->add_option("--editors", a.editors, "editor connections")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  load->add_option("--viewers", a.viewers, "viewer connections")
      ->check(CLI::Range(0, 2000))
      ->capture_default_str();
  load->add_option("--rate", a.rate, "edits per second per editor, (0, 200]")
      ->check(within(0, 200, true))
      ->capture_default_str();
  load->add_option("--seconds", a.seconds, "editing time, (0, 3600]")
      ->check(within(0, 3600, true))
      ->capture_default_str();
  load->add_option("--arrivals", a.arrivals,
                   "when editors send: constant or poisson, on a schedule fixed before the run; latency "
                   "counts from each send's due time")
      ->capture_default_str();
  load->add_option("--warmup", a.warmupSeconds,
                   "seconds of editing at the start whose edits are left out of the latencies")
      ->check(within(0, 3600))
      ->capture_default_str();
  load->add_option("--hgrm", a.hgrmPrefix,
                   "also write the latencies as PREFIX-edit_to_ack.hgrm, PREFIX-edit_to_delta.hgrm "
                   "(HdrHistogram's percentile format)")
      ->type_name("PREFIX");
  load->add_option("--max-edits", a.maxEdits, "edits per editor at most")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  load->add_option("--decode-viewers", a.decodeViewers,
                   "viewers that decode every region (default: min(viewers, 20))");
  load->add_option("--vertex-level", a.vertexLevel, "edits move v<L>:0..N-1")
      ->check(CLI::Range(0, 12))
      ->capture_default_str();
  load->add_option("--vertex-count", a.vertexCount, "N of --vertex-level")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  load->add_option("--step", a.step, "largest offset per axis")->capture_default_str();
  load->add_option("--seed", a.seed, "random seed")->capture_default_str();
  load->add_option("--drain-seconds", a.drainSeconds, "after editing: waiting for the last acks and deltas")
      ->check(within(0, 600))
      ->capture_default_str();
  load->add_option("--pool-threads", a.poolThreads,
                   "threads of the counting viewers' pool; 0: a thread per viewer")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  load->add_flag("--display-only", a.displayOnly, "viewers subscribe without vertex ids");
  load->add_option("--codec", a.codec, "the viewers' region codec (docs/REGION_ENCODING.md)")
      ->check(CLI::IsMember({"draco", "meshopt"}))
      ->capture_default_str();
  load->add_option("--server-pid", a.serverPid, "sample this server process's CPU and RSS from /proc");
  load->add_option("--report", a.report, "write the JSON report to FILE");
  load->add_flag("--quiet", a.quiet, "no progress lines");
  load->add_option("--cameras", a.cameras,
                   "viewers subscribe with views that follow camera paths: orbit, zoom, fly or random (each "
                   "viewer its own seed)");
  load->add_option("--camera-target", a.cameraTarget, "the sphere the cameras look at: X Y Z RADIUS")
      ->expected(4);
  load->add_option("--camera-size", a.cameraSize, "the cameras' viewport, WIDTHxHEIGHT")
      ->capture_default_str();
  load->add_option("--camera-tolerance", a.cameraTolerance, "screen-space error in pixels")
      ->capture_default_str();
  load->add_option("--camera-rate", a.cameraRate, "SetViews per second per viewer")->capture_default_str();
  load->add_option("--threshold", a.thresholds,
                   "pass/fail rule, repeatable: 'p99<50ms', 'ack.p95<=10ms', 'mean<5ms', 'errors=0' (exit 4 "
                   "if one fails)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  addProfileOption(*load, a.profile);
  return load;
}

int runLoadCommand(const LoadArgs& a) {
  std::vector<Threshold> thresholds;
  for (const std::string& text : a.thresholds) {
    auto t = parseThreshold(text);
    if (!t.isOk()) return usage(t.status().message(), "load");
    thresholds.push_back(*t);
  }
  auto session = sessionOptions(a.connection);
  if (!session.isOk()) return usage(session.status().message(), "load");
  auto header = withProfile(a.profile, ScriptHeader{});
  if (!header.isOk()) return usage(header.status().message(), "load");
  LoadOptions o;
  o.session = *session;
  o.viewerToken = a.viewerToken;
  o.document = a.document;
  o.editors = a.editors;
  o.viewers = a.viewers;
  o.rate = a.rate;
  o.seconds = a.seconds;
  auto arrivals = parseArrivals(a.arrivals);
  if (!arrivals.isOk()) return usage(arrivals.status().message(), "load");
  o.arrivals = *arrivals;
  if (!(a.warmupSeconds < a.seconds))
    return usage("--warmup must be shorter than --seconds (" + std::to_string(a.seconds) + ")", "load");
  o.warmupSeconds = a.warmupSeconds;
  o.hgrmPrefix = a.hgrmPrefix;
  o.maxEdits = a.maxEdits;
  o.decodeViewers = a.decodeViewers;
  o.vertexLevel = a.vertexLevel;
  o.vertexCount = a.vertexCount;
  o.step = a.step;
  o.seed = a.seed;
  o.drainSeconds = a.drainSeconds;
  o.serverPid = a.serverPid;
  o.poolThreads = a.poolThreads;
  o.profile = profileOf(*header);
  // Viewers that only watch: regions without vertex ids (docs/PROTOCOL.md).
  o.profile.set_omit_vertex_ids(a.displayOnly);
  o.codec = a.codec == "meshopt" ? wire::REGION_CODEC_MESHOPT : wire::REGION_CODEC_DRACO;
  o.progress = !a.quiet;
  if (!a.cameras.empty()) {
    auto kind = cameraPathKind(a.cameras);
    if (!kind.isOk()) return usage(kind.status().message(), "load");
    if (a.cameraTarget.size() != 4 || !(a.cameraTarget[3] > 0))
      return usage("--cameras needs --camera-target X Y Z RADIUS (a positive radius)", "load");
    CameraPaths paths;
    paths.kind = *kind;
    paths.centre = Vec3(a.cameraTarget[0], a.cameraTarget[1], a.cameraTarget[2]);
    paths.radius = a.cameraTarget[3];
    char x = 0;
    if (std::sscanf(a.cameraSize.c_str(), "%d%c%d", &paths.width, &x, &paths.height) != 3 || x != 'x')
      return usage("--camera-size: expects WIDTHxHEIGHT, got '" + a.cameraSize + "'", "load");
    paths.tolerancePixels = a.cameraTolerance;
    paths.viewsPerSecond = a.cameraRate;
    paths.seed = a.seed;
    if (Status valid = cameraAt(paths, 0, 0).check(); !valid.isOk()) return usage(valid.message(), "load");
    o.cameras = paths;
  }
  auto ran = runLoad(o);
  if (!ran.isOk()) return fail(ran.status());
  nlohmann::json& report = *ran;
  const std::vector<ThresholdResult> results = checkThresholds(thresholds, report);
  int failed = 0;
  if (!results.empty()) {
    nlohmann::json checked = nlohmann::json::array();
    for (const ThresholdResult& r : results) {
      checked.push_back({{"threshold", r.threshold.text},
                         {"metric", r.threshold.metric.empty() ? r.threshold.stat
                                                               : r.threshold.metric + "." + r.threshold.stat},
                         {"limit", r.threshold.limit},
                         {"measured", r.measured ? nlohmann::json(r.value) : nlohmann::json(nullptr)},
                         {"passed", r.passed}});
      failed += r.passed ? 0 : 1;
    }
    report["thresholds"] = checked;
  }
  if (!a.report.empty()) {
    std::ofstream f(a.report, std::ios::binary);
    f << report.dump(2) << "\n";
    if (!f.flush()) return fail(ioError(a.report + ": cannot write"));
  }
  std::fputs(summarize(report).c_str(), stdout);
  if (!results.empty()) {
    std::printf("  thresholds:\n");
    for (const ThresholdResult& r : results) std::printf("    %s\n", r.describe().c_str());
  }
  std::fflush(stdout);
  if (report.contains("stopped")) {
    std::fprintf(stderr, "tessera-replay: load stopped after %.1f s: %s\n",
                 report["stopped"]["after_seconds"].get<double>(),
                 report["stopped"]["reason"].get<std::string>().c_str());
    return kExitStopped;
  }
  if (failed > 0) {
    for (const ThresholdResult& r : results) {
      if (!r.passed) std::fprintf(stderr, "tessera-replay: threshold failed: %s\n", r.describe().c_str());
    }
    return kExitThresholdFailed;
  }
  // A run whose connections failed, whose viewers saw gaps or did not catch
  // up by the end of the drain time is a failed run.
  const bool clean = report["errors"]["count"].get<int64_t>() == 0 &&
                     report["viewers"]["gaps"].get<int64_t>() == 0 &&
                     report["viewers"]["behind_at_end"].get<int64_t>() == 0;
  return clean ? 0 : kExitUncleanRun;
}

}  // namespace tessera::replay
