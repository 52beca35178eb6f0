// tessera-replay load's report against the real server (docs/REPLAY.md §3.1): the
// statistics agree with the report's own histogram and series, thresholds
// set the exit code, the server's stats cover the run's window, and a
// missing document or a refused token stops the run at once.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "replay/replay_support.h"

namespace tessera {
namespace {

using nlohmann::json;
using testing::ReplayServer;
using testing::run;

const std::string kReplay = TESSERA_REPLAY_PATH;

json readReport(const std::string& path) {
  std::ifstream in(path);
  if (!in) return json();
  return json::parse(in, nullptr, false);
}

std::string reportPath(const std::string& name) {
  return testing::makeTempDir("tessera-load-report") + "/" + name;
}

// Where a nearest-rank percentile must fall, from the histogram alone: the
// bucket in which the running count first reaches ceil(p/100 * n).
std::pair<double, double> bucketOfRank(const json& buckets, double percent, int64_t n) {
  const auto rank = static_cast<int64_t>(std::ceil(percent / 100 * static_cast<double>(n) - 1e-9));
  int64_t seen = 0;
  for (const json& b : buckets) {
    seen += b[2].get<int64_t>();
    if (seen >= rank) return {b[0].get<double>(), b[1].get<double>()};
  }
  return {-1, -1};
}

void expectConsistent(const json& latency, const json& buckets, const std::string& which) {
  SCOPED_TRACE(which);
  const int64_t n = latency["count"];
  ASSERT_GT(n, 0);
  int64_t total = 0;
  double lowSum = 0, highSum = 0;
  for (const json& b : buckets) {
    total += b[2].get<int64_t>();
    lowSum += b[0].get<double>() * b[2].get<double>();
    highSum += b[1].get<double>() * b[2].get<double>();
  }
  EXPECT_EQ(total, n);
  // Report values are ms rounded to the microsecond; buckets floor to whole
  // microseconds: a value may sit 1 us outside its bucket's edges.
  const double mean = latency["mean"].get<double>() * 1000;
  EXPECT_GE(mean, lowSum / n - 1);
  EXPECT_LE(mean, highSum / n + 1);
  for (auto [key, p] : {std::pair{"p50", 50.0},
                        {"p90", 90.0},
                        {"p95", 95.0},
                        {"p99", 99.0},
                        {"p99_9", 99.9},
                        {"max", 100.0}}) {
    const auto [low, high] = bucketOfRank(buckets, p, n);
    const double us = latency[key].get<double>() * 1000;
    EXPECT_GE(us, low - 1) << key;
    EXPECT_LE(us, high + 1) << key;
  }
  EXPECT_LE(latency["min"].get<double>(), latency["p50"].get<double>());
  EXPECT_LE(latency["p50"].get<double>(), latency["p90"].get<double>());
  EXPECT_LE(latency["p90"].get<double>(), latency["p95"].get<double>());
  EXPECT_LE(latency["p95"].get<double>(), latency["p99"].get<double>());
  EXPECT_LE(latency["p99"].get<double>(), latency["p99_9"].get<double>());
  EXPECT_LE(latency["p99_9"].get<double>(), latency["max"].get<double>());
  EXPECT_GE(latency["stddev"].get<double>(), 0);
  EXPECT_LE(latency["mean"].get<double>(), latency["max"].get<double>());
}

TEST(LoadReport, StatisticsSeriesAndPassingThresholds) {
  ReplayServer s;
  testing::startServer(s, "tessera-load-stats");
  if (HasFatalFailure()) return;
  const std::string path = reportPath("stats.json");
  auto [out, code] =
      run(kReplay + " load" + s.connection() +
          " --editors 2 --viewers 3 --rate 10 --seconds 2 --drain-seconds 5 --quiet --report " + path +
          " --threshold 'p99<60s' --threshold 'ack.max<=60000ms' --threshold errors=0 --threshold gaps=0");
  EXPECT_EQ(code, 0) << out;
  const json r = readReport(path);
  ASSERT_TRUE(r.is_object()) << out;
  const int64_t sent = r["edits"]["sent"];
  ASSERT_GE(sent, 30) << out;
  // The schedule is fixed before the run: 2 editors x 10/s x 2 s due, and
  // every due send accounted for, sent or dropped.
  EXPECT_EQ(r["edits"]["offered"], 40) << out;
  EXPECT_EQ(r["edits"]["offered"].get<int64_t>(), sent + r["edits"]["dropped"].get<int64_t>());
  EXPECT_EQ(r["edits"]["lateness_ms"]["count"], sent);
  EXPECT_EQ(r["config"]["arrivals"], "constant");
  EXPECT_EQ(r["edits"]["acked"], sent);
  EXPECT_EQ(r["latency_ms"]["edit_to_ack"]["count"], sent);
  EXPECT_EQ(r["latency_ms"]["edit_to_delta"]["count"], 3 * sent);
  expectConsistent(r["latency_ms"]["edit_to_ack"], r["histograms"]["edit_to_ack"], "edit_to_ack");
  expectConsistent(r["latency_ms"]["edit_to_delta"], r["histograms"]["edit_to_delta"], "edit_to_delta");
  EXPECT_EQ(r["histograms"]["unit"], "us");

  // One entry per second of editing; together they hold every edit.
  const json& series = r["series"];
  ASSERT_EQ(series.size(), 2u) << series.dump();
  int64_t seriesSent = 0, seriesAcked = 0, seriesDeltas = 0;
  for (size_t i = 0; i < series.size(); ++i) {
    EXPECT_EQ(series[i]["second"], i);
    seriesSent += series[i]["sent"].get<int64_t>();
    seriesAcked += series[i]["acked"].get<int64_t>();
    seriesDeltas += series[i]["edit_to_delta"]["count"].get<int64_t>();
    EXPECT_GT(series[i]["sent"].get<int64_t>(), 0) << i;
    EXPECT_LE(series[i]["edit_to_ack"]["p99"].get<double>(),
              r["latency_ms"]["edit_to_ack"]["max"].get<double>());
  }
  EXPECT_EQ(seriesSent, sent);
  EXPECT_EQ(seriesAcked, sent);
  EXPECT_EQ(seriesDeltas, 3 * sent);

  ASSERT_EQ(r["thresholds"].size(), 4u);
  for (const json& t : r["thresholds"]) EXPECT_TRUE(t["passed"].get<bool>()) << t.dump();
  EXPECT_EQ(r["thresholds"][1]["measured"], r["latency_ms"]["edit_to_ack"]["max"]);
  EXPECT_NE(out.find("p99.9"), std::string::npos) << out;
  EXPECT_NE(out.find("stddev"), std::string::npos) << out;
  EXPECT_NE(out.find("p99<60s: edit_to_delta p99 "), std::string::npos) << out;
}

// The open model's account (docs/REPLAY.md §3.4): Poisson arrivals, a
// warm-up left out of the latencies and said so, offered against achieved
// rates, the tester's CPU beside the server's, the machine and versions,
// and the latencies in HdrHistogram's format, one row per percentile.
TEST(LoadReport, AnOpenScheduleAccountsForEverySendAndWritesHgrm) {
  ReplayServer s;
  testing::startServer(s, "tessera-load-open");
  if (HasFatalFailure()) return;
  const std::string path = reportPath("open.json");
  const std::string prefix = path.substr(0, path.rfind('/')) + "/open";
  auto [out, code] = run(kReplay + " load" + s.connection() +
                         " --editors 2 --viewers 2 --rate 20 --seconds 3 --arrivals poisson --warmup 1"
                         " --drain-seconds 5 --quiet --report " +
                         path + " --hgrm " + prefix);
  EXPECT_EQ(code, 0) << out;
  const json r = readReport(path);
  ASSERT_TRUE(r.is_object()) << out;
  const json& e = r["edits"];
  const int64_t sent = e["sent"], offered = e["offered"], dropped = e["dropped"];
  EXPECT_EQ(offered, sent + dropped);
  // Poisson: 120 due on average over the run; a 4-sigma band.
  EXPECT_GT(offered, 120 - 4 * 11);
  EXPECT_LT(offered, 120 + 4 * 11);
  EXPECT_NEAR(e["offered_per_second"].get<double>(), offered / 3.0, 1e-9);
  EXPECT_NEAR(e["achieved_per_second"].get<double>(), sent / 3.0, 1e-9);
  EXPECT_EQ(r["config"]["arrivals"], "poisson");
  EXPECT_EQ(r["config"]["warmup_seconds"], 1);
  // Every ack is either in the latencies or in the warm-up, which had some.
  const int64_t warmupAcks = r["warmup_excluded"]["edit_to_ack"];
  EXPECT_GT(warmupAcks, 0);
  EXPECT_EQ(r["latency_ms"]["edit_to_ack"]["count"].get<int64_t>() + warmupAcks, e["acked"].get<int64_t>());
  EXPECT_EQ(r["latency_ms"]["edit_to_delta"]["count"].get<int64_t>() +
                r["warmup_excluded"]["edit_to_delta"].get<int64_t>(),
            2 * e["acked"].get<int64_t>());
  EXPECT_TRUE(r["client"].contains("cpu_percent")) << r["client"].dump();
  // The tester's CPU second by second, beside each second's edits.
  ASSERT_EQ(r["series"].size(), 3u);
  for (const json& second : r["series"]) {
    ASSERT_TRUE(second.contains("tester_cpu_percent")) << second.dump();
    EXPECT_GE(second["tester_cpu_percent"].get<double>(), 0);
  }
  EXPECT_GT(r["machine"]["cpus"].get<int>(), 0);
  EXPECT_TRUE(r["versions"].contains("tessera_replay"));
  EXPECT_NE(out.find("schedule (poisson): offered "), std::string::npos) << out;
  EXPECT_NE(out.find("warm-up: the first 1 s of edits are left out"), std::string::npos) << out;
  // The .hgrm files: the last row counts every sample of the report.
  ASSERT_EQ(r["hgrm_files"].size(), 2u) << r.dump();
  for (const char* which : {"edit_to_ack", "edit_to_delta"}) {
    std::ifstream in(prefix + "-" + which + ".hgrm");
    ASSERT_TRUE(in) << which;
    std::string line, lastRow;
    while (std::getline(in, line))
      if (!line.empty() && line[0] != '#' && line.find("Value") == std::string::npos) lastRow = line;
    std::istringstream fields(lastRow);
    double value = 0, percentile = 0;
    long long count = 0;
    fields >> value >> percentile >> count;
    EXPECT_EQ(percentile, 1.0) << which << ": " << lastRow;
    EXPECT_EQ(count, r["latency_ms"][which]["count"].get<long long>()) << which;
    EXPECT_NEAR(value, r["latency_ms"][which]["max"].get<double>(), 1e-3) << which;
  }
}

TEST(LoadReport, AFailingThresholdExitsWith4AndNamesItsValue) {
  ReplayServer s;
  testing::startServer(s, "tessera-load-threshold");
  if (HasFatalFailure()) return;
  const std::string path = reportPath("failing.json");
  // No loopback round trip takes less than a microsecond.
  auto [out, code] = run(kReplay + " load" + s.connection() +
                             " --editors 1 --viewers 1 --rate 10 --seconds 1 --quiet --report " + path +
                             " --threshold 'ack.max<1us' --threshold errors=0",
                         true);
  EXPECT_EQ(code, 4) << out;
  const json r = readReport(path);
  ASSERT_TRUE(r.is_object()) << out;
  ASSERT_EQ(r["thresholds"].size(), 2u);
  EXPECT_FALSE(r["thresholds"][0]["passed"].get<bool>());
  EXPECT_EQ(r["thresholds"][0]["metric"], "edit_to_ack.max");
  EXPECT_EQ(r["thresholds"][0]["measured"], r["latency_ms"]["edit_to_ack"]["max"]);
  EXPECT_TRUE(r["thresholds"][1]["passed"].get<bool>());
  EXPECT_NE(out.find("tessera-replay: threshold failed: ack.max<1us: edit_to_ack max "), std::string::npos)
      << out;
  EXPECT_EQ(out.find("threshold failed: errors=0"), std::string::npos) << out;
}

TEST(LoadReport, BadThresholdIsAUsageErrorBeforeConnecting) {
  // Nothing listens on port 1: the error must come before any connection.
  auto [out, code] = run(kReplay + " load --port 1 --token t --document 1 --threshold 'p99<50'", true);
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("--threshold 'p99<50': a latency needs a unit: us, ms or s"), std::string::npos) << out;
  std::tie(out, code) = run(kReplay + " load --port 1 --token t --document 1 --threshold 'p98<5ms'", true);
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("--threshold 'p98<5ms': unknown statistic 'p98'"), std::string::npos) << out;
}

TEST(LoadReport, ServerStatsCoverTheRunsWindow) {
  ReplayServer s;
  testing::startServer(s, "tessera-load-window");
  if (HasFatalFailure()) return;
  const std::string busy = reportPath("busy.json"), idle = reportPath("idle.json");
  auto [busyOut, busyCode] = run(kReplay + " load" + s.connection() +
                                 " --editors 2 --viewers 2 --rate 20 --seconds 1 --quiet --report " + busy);
  ASSERT_EQ(busyCode, 0) << busyOut;
  const json b = readReport(busy);
  const double acked = b["edits"]["acked"].get<double>();
  ASSERT_GT(acked, 0);
  const json& bw = b["server"]["window"];
  EXPECT_EQ(bw["edits"].get<double>(), acked) << bw.dump();
  EXPECT_GT(bw["edits_per_second"].get<double>(), 0);
  EXPECT_GT(bw["bytes_sent"].get<double>(), 0);
  EXPECT_GT(bw["seconds"].get<double>(), 0.9);
  EXPECT_TRUE(bw.contains("tessellate_ms_per_edit"));
  EXPECT_NE(busyOut.find("server over the run"), std::string::npos) << busyOut;

  // An idle run after it: the window is near zero, the server's whole-uptime
  // figures are not.
  auto [idleOut, idleCode] = run(kReplay + " load" + s.connection() +
                                 " --editors 0 --viewers 1 --seconds 1 --quiet --report " + idle);
  ASSERT_EQ(idleCode, 0) << idleOut;
  const json i = readReport(idle);
  const json& iw = i["server"]["window"];
  EXPECT_EQ(iw["edits"].get<double>(), 0) << iw.dump();
  EXPECT_EQ(iw["edits_per_second"].get<double>(), 0);
  EXPECT_EQ(iw["rejects"].get<double>(), 0);
  EXPECT_EQ(iw["resyncs"].get<double>(), 0);
  EXPECT_EQ(iw["deltas"].get<double>(), 0);
  EXPECT_LT(iw["bytes_sent"].get<double>(), 4096);  // the stats replies and a hello
  EXPECT_FALSE(iw.contains("tessellate_ms_per_edit"));
  EXPECT_EQ(i["server"]["stats"]["edits"].get<double>(), acked);
  EXPECT_GT(i["server"]["stats"]["edits_per_second"].get<double>(), 0);
}

// The run of `args` against `s` with 60 s of editing asked for: it must stop
// long before, with exit 5 and `reason` in its report and on stderr.
void expectStopped(const ReplayServer& s, const std::string& args, const std::string& reason) {
  const std::string path = reportPath("stopped.json");
  auto [out, code] = run(kReplay + " load --port " + std::to_string(s.process->port()) + args +
                             " --editors 1 --viewers 2 --seconds 60 --quiet --report " + path,
                         true);
  EXPECT_EQ(code, 5) << out;
  const json r = readReport(path);
  ASSERT_TRUE(r.is_object()) << out;
  ASSERT_TRUE(r.contains("stopped")) << r.dump();
  EXPECT_NE(r["stopped"]["reason"].get<std::string>().find(reason), std::string::npos) << r["stopped"].dump();
  EXPECT_LT(r["stopped"]["after_seconds"].get<double>(), 15) << r["stopped"].dump();
  EXPECT_NE(out.find("tessera-replay: load stopped after "), std::string::npos) << out;
  EXPECT_NE(out.find(reason), std::string::npos) << out;
}

TEST(LoadStop, NoServerIsAFailureNotAStop) {
  // Port 1: nothing listens there.
  auto [out, code] = run(kReplay + " load --port 1 --token t --document 1 --seconds 60 --quiet", true);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("tessera-replay: load: the editors' and viewers' token: cannot connect to 127.0.0.1:1"),
            std::string::npos)
      << out;
}

TEST(LoadStop, MissingDocumentStopsAtOnceWithTheReason) {
  ReplayServer s;
  testing::startServer(s, "tessera-load-missing");
  if (HasFatalFailure()) return;
  // With a token for every document (the admin's), the server says the
  // document is not there; a token granted on one document only is told it
  // has no access to any other, existing or not (PERMISSION_DENIED).
  expectStopped(s, " --token " + s.process->adminToken() + " --document 999",
                "document 999: open: REJECT_REASON_NOT_FOUND");
  expectStopped(s, std::string(" --token ") + testing::kEditorToken + " --document 999",
                "document 999: open: REJECT_REASON_PERMISSION_DENIED");
}

TEST(LoadStop, UnknownTokenStopsAtOnceWithTheReason) {
  ReplayServer s;
  testing::startServer(s, "tessera-load-token");
  if (HasFatalFailure()) return;
  expectStopped(s, " --token wrong-token-0123456789abcdef --document " + std::to_string(s.doc),
                "the access token is not known to this server");
}

TEST(LoadStop, TokenWithoutEditRightsStopsAtTheFirstEdit) {
  ReplayServer s;
  testing::startServer(s, "tessera-load-viewer-token");
  if (HasFatalFailure()) return;
  // A viewer's token opens the document; its first edit is refused.
  expectStopped(s, std::string(" --token ") + testing::kViewerToken + " --document " + std::to_string(s.doc),
                "REJECT_REASON_PERMISSION_DENIED");
}

}  // namespace
}  // namespace tessera
