// The load report's pieces on known inputs (docs/REPLAY.md §3.1): summary
// statistics checked against values worked out by hand, the histogram's
// fixed bucket layout, the per-second series, thresholds, and the server
// stats window.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "client/replay/latency_histogram.h"
#include "client/replay/latency_stats.h"
#include "client/replay/load_series.h"
#include "client/replay/server_window.h"
#include "client/replay/thresholds.h"

namespace tessera::replay {
namespace {

TEST(LatencyStats, TenSamplesByHand) {
  // 1..10: mean 5.5; squared deviations sum to 82.5, so the sample standard
  // deviation is sqrt(82.5 / 9). Nearest rank: p50 is the 5th, p90 the 9th,
  // p95 the ceil(9.5) = 10th.
  const LatencySummary s = summarizeLatencies({7, 3, 10, 1, 5, 9, 2, 8, 4, 6});
  EXPECT_EQ(s.count, 10u);
  EXPECT_DOUBLE_EQ(s.mean, 5.5);
  EXPECT_NEAR(s.stddev, 3.0276503540974917, 1e-12);
  EXPECT_EQ(s.min, 1);
  EXPECT_EQ(s.p50, 5);
  EXPECT_EQ(s.p90, 9);
  EXPECT_EQ(s.p95, 10);
  EXPECT_EQ(s.p99, 10);
  EXPECT_EQ(s.p999, 10);
  EXPECT_EQ(s.max, 10);
}

TEST(LatencyStats, TextbookStandardDeviation) {
  // {2,4,4,4,5,5,7,9}: mean 5, squared deviations 32; sample sd sqrt(32/7).
  const LatencySummary s = summarizeLatencies({2, 4, 4, 4, 5, 5, 7, 9});
  EXPECT_DOUBLE_EQ(s.mean, 5);
  EXPECT_NEAR(s.stddev, std::sqrt(32.0 / 7.0), 1e-12);
  EXPECT_EQ(s.p50, 4);  // 4th of 8
  EXPECT_EQ(s.p90, 9);  // ceil(7.2) = 8th
}

TEST(LatencyStats, AThousandSamplesHitExactRanks) {
  // 1..1000 shuffled: p99.9 is the 999th sample, not the maximum; the sample
  // variance of 1..n is n(n+1)/12.
  std::vector<double> v(1000);
  std::iota(v.begin(), v.end(), 1.0);
  std::shuffle(v.begin(), v.end(), std::mt19937(5));
  const LatencySummary s = summarizeLatencies(v);
  EXPECT_DOUBLE_EQ(s.mean, 500.5);
  EXPECT_NEAR(s.stddev, std::sqrt(1000.0 * 1001.0 / 12.0), 1e-9);
  EXPECT_EQ(s.p50, 500);
  EXPECT_EQ(s.p90, 900);
  EXPECT_EQ(s.p95, 950);
  EXPECT_EQ(s.p99, 990);
  EXPECT_EQ(s.p999, 999);
  EXPECT_EQ(s.max, 1000);
}

TEST(LatencyStats, OneSampleAndNone) {
  const LatencySummary one = summarizeLatencies({3.25});
  EXPECT_EQ(one.count, 1u);
  EXPECT_EQ(one.stddev, 0);
  EXPECT_EQ(one.p50, 3.25);
  EXPECT_EQ(one.p999, 3.25);
  const LatencySummary none = summarizeLatencies({});
  EXPECT_EQ(none.count, 0u);
  EXPECT_EQ(nearestRank({}, 50), 0);
}

TEST(LatencyHistogram, FixedLayout) {
  auto range = [](uint64_t v) {
    HistogramBucket b = bucketOf(v);
    return std::pair{b.lowerMicros, b.upperMicros};
  };
  EXPECT_EQ(range(0), (std::pair<uint64_t, uint64_t>{0, 1}));
  EXPECT_EQ(range(7), (std::pair<uint64_t, uint64_t>{7, 8}));
  EXPECT_EQ(range(8), (std::pair<uint64_t, uint64_t>{8, 9}));
  EXPECT_EQ(range(15), (std::pair<uint64_t, uint64_t>{15, 16}));
  EXPECT_EQ(range(16), (std::pair<uint64_t, uint64_t>{16, 18}));
  EXPECT_EQ(range(17), (std::pair<uint64_t, uint64_t>{16, 18}));
  // 512 <= 1000 < 1024: buckets of 64, the 8th (s = 15 - 8 = 7) is [960, 1024).
  EXPECT_EQ(range(1000), (std::pair<uint64_t, uint64_t>{960, 1024}));
  EXPECT_EQ(range(1024), (std::pair<uint64_t, uint64_t>{1024, 1152}));
  // Contiguous, holding their value, at most 1/8 of the lower bound wide.
  for (uint64_t v = 0; v < 200000; ++v) {
    const HistogramBucket b = bucketOf(v);
    ASSERT_LE(b.lowerMicros, v);
    ASSERT_LT(v, b.upperMicros);
    ASSERT_EQ(bucketOf(b.upperMicros).lowerMicros, b.upperMicros);
    if (b.lowerMicros >= 8) ASSERT_LE((b.upperMicros - b.lowerMicros) * 8, b.lowerMicros);
  }
}

TEST(LatencyHistogram, CountsMillisecondSamples) {
  LatencyHistogram h;
  for (double ms : {0.0005, 0.0015, 1.0, 1.01, 1.5, -2.0}) h.addMilliseconds(ms);
  // 0.5 us and -2 ms -> 0; 1.5 us -> 1; 1000 and 1010 us -> [960, 1024); 1500 us -> [1408, 1536).
  const auto b = h.buckets();
  ASSERT_EQ(b.size(), 4u);
  EXPECT_EQ(b[0].lowerMicros, 0u);
  EXPECT_EQ(b[0].count, 2u);
  EXPECT_EQ(b[1].lowerMicros, 1u);
  EXPECT_EQ(b[1].count, 1u);
  EXPECT_EQ(b[2].lowerMicros, 960u);
  EXPECT_EQ(b[2].count, 2u);
  EXPECT_EQ(b[3].lowerMicros, 1408u);
  EXPECT_EQ(b[3].upperMicros, 1536u);
  EXPECT_EQ(h.total(), 6u);
}

TEST(LoadSeries, PlacesEventsBySendSecond) {
  LoadSeries s(3);
  s.sent(0, 4);
  s.sent(2, 1);
  s.sent(7, 2);  // past the end: the last second
  for (double ms : {1.0, 2.0, 3.0, 10.0}) s.acked(0.5, ms);
  s.acked(2.99, 7.0);
  s.delta(0.1, 4.0);
  s.delta(1.0, 6.0);  // exactly 1.0 s is in second 1
  s.rejected(1.7);
  s.error(-3);  // while connecting: the first second
  s.error(42);  // during the drain: the last
  const nlohmann::json j = s.toJson();
  ASSERT_EQ(j.size(), 3u);
  EXPECT_EQ(j[0]["second"], 0);
  EXPECT_EQ(j[0]["sent"], 4);
  EXPECT_EQ(j[0]["acked"], 4);
  EXPECT_EQ(j[0]["errors"], 1);
  EXPECT_DOUBLE_EQ(j[0]["edit_to_ack"]["mean"].get<double>(), 4.0);  // (1+2+3+10)/4
  EXPECT_EQ(j[0]["edit_to_ack"]["p50"], 2.0);                        // 2nd of 4
  EXPECT_EQ(j[0]["edit_to_ack"]["p99"], 10.0);
  EXPECT_EQ(j[0]["edit_to_delta"]["count"], 1);
  EXPECT_EQ(j[1]["sent"], 0);
  EXPECT_EQ(j[1]["rejected"], 1);
  EXPECT_EQ(j[1]["edit_to_delta"]["max"], 6.0);
  EXPECT_EQ(j[1]["edit_to_ack"]["count"], 0);
  EXPECT_FALSE(j[1]["edit_to_ack"].contains("p50"));
  EXPECT_EQ(j[2]["sent"], 3);
  EXPECT_EQ(j[2]["acked"], 1);
  EXPECT_EQ(j[2]["errors"], 1);
  EXPECT_TRUE(LoadSeries(0).toJson().empty());
}

Threshold parsed(const std::string& text) {
  auto t = parseThreshold(text);
  EXPECT_TRUE(t.isOk()) << text << ": " << t.status().message();
  return t.isOk() ? *t : Threshold{};
}

std::string parseError(const std::string& text) {
  auto t = parseThreshold(text);
  return t.isOk() ? "parsed" : t.status().message();
}

TEST(Thresholds, ParseEveryForm) {
  Threshold t = parsed("p99<50ms");
  EXPECT_EQ(t.metric, "edit_to_delta");
  EXPECT_EQ(t.stat, "p99");
  EXPECT_EQ(t.op, Comparison::kLess);
  EXPECT_EQ(t.limit, 50);
  t = parsed("ack.p95 <= 1500us");
  EXPECT_EQ(t.metric, "edit_to_ack");
  EXPECT_EQ(t.stat, "p95");
  EXPECT_EQ(t.op, Comparison::kLessEqual);
  EXPECT_DOUBLE_EQ(t.limit, 1.5);
  t = parsed("edit_to_delta.p99.9<0.2s");
  EXPECT_EQ(t.stat, "p99_9");
  EXPECT_DOUBLE_EQ(t.limit, 200);
  t = parsed("p99.9<1s");
  EXPECT_EQ(t.metric, "edit_to_delta");
  EXPECT_EQ(t.stat, "p99_9");
  t = parsed("mean>=0.5ms");
  EXPECT_EQ(t.op, Comparison::kGreaterEqual);
  t = parsed("delta.stddev>2ms");
  EXPECT_EQ(t.op, Comparison::kGreater);
  t = parsed("errors=0");
  EXPECT_EQ(t.metric, "");
  EXPECT_EQ(t.stat, "errors");
  EXPECT_EQ(t.op, Comparison::kEqual);
  t = parsed("gaps==0");
  EXPECT_EQ(t.op, Comparison::kEqual);
  t = parsed("throughput>=19.5/s");
  EXPECT_DOUBLE_EQ(t.limit, 19.5);
}

TEST(Thresholds, BadOnesNameTheThresholdAndTheFault) {
  EXPECT_EQ(parseError("p99"),
            "--threshold 'p99': no comparison (expected <, <=, >, >= or =), e.g. 'p99<50ms'");
  EXPECT_EQ(parseError("p99<50"), "--threshold 'p99<50': a latency needs a unit: us, ms or s");
  EXPECT_EQ(parseError("p99<50min"), "--threshold 'p99<50min': unknown unit 'min' (expected us, ms or s)");
  EXPECT_EQ(parseError("p98<5ms").rfind("--threshold 'p98<5ms': unknown statistic 'p98' (expected ", 0), 0u);
  EXPECT_EQ(parseError("ping.p99<5ms").rfind("--threshold 'ping.p99<5ms': unknown latency 'ping'", 0), 0u);
  EXPECT_EQ(parseError("errors=0ms"), "--threshold 'errors=0ms': errors is a count and takes no unit");
  EXPECT_EQ(parseError("errors=none"), "--threshold 'errors=none': 'none' is not a number");
  EXPECT_EQ(parseError("<5ms"), "--threshold '<5ms': nothing to compare before '<'");
}

TEST(Thresholds, CheckedAgainstTheReportsValues) {
  const nlohmann::json report = {
      {"latency_ms",
       {{"edit_to_ack", {{"count", 10}, {"p99", 4.0}, {"mean", 2.0}}}, {"edit_to_delta", {{"count", 0}}}}},
      {"errors", {{"count", 2}}},
      {"edits", {{"rejected", 0}, {"throughput_per_second", 19.9}}},
      {"viewers", {{"gaps", 0}}}};
  auto results =
      checkThresholds({parsed("ack.p99<4ms"), parsed("ack.p99<=4ms"), parsed("ack.mean>1999us"),
                       parsed("errors=0"), parsed("rejected=0"), parsed("p99<1s"), parsed("throughput>=20")},
                      report);
  ASSERT_EQ(results.size(), 7u);
  EXPECT_FALSE(results[0].passed);  // 4 < 4
  EXPECT_TRUE(results[1].passed);
  EXPECT_TRUE(results[2].passed);
  EXPECT_FALSE(results[3].passed);
  EXPECT_EQ(results[3].value, 2);
  EXPECT_TRUE(results[4].passed);
  EXPECT_FALSE(results[5].passed);  // no delta samples: nothing passes
  EXPECT_FALSE(results[5].measured);
  EXPECT_FALSE(results[6].passed);
  EXPECT_EQ(results[0].describe(), "ack.p99<4ms: edit_to_ack p99 4 ms (FAILED)");
  EXPECT_EQ(results[3].describe(), "errors=0: errors 2 (FAILED)");
  EXPECT_EQ(results[5].describe(), "p99<1s: edit_to_delta p99 n/a (no samples) (FAILED)");
  EXPECT_EQ(results[6].describe(), "throughput>=20: throughput 19.9 (FAILED)");
}

TEST(ServerWindow, DifferencesRatesAndWindowAverages) {
  const ServerStatsSample start = {
      {"uptime_seconds", 100}, {"edits", 40},        {"bytes_sent", 1000},
      {"deltas", 10},          {"rejects", 1},       {"tessellate_ms_per_edit", 0.5},
      {"connections", 3},      {"store_batches", 4}, {"store_average_batch", 10}};
  const ServerStatsSample end = {
      {"uptime_seconds", 110}, {"edits", 60},        {"bytes_sent", 6000},
      {"deltas", 15},          {"rejects", 1},       {"tessellate_ms_per_edit", 0.6},
      {"connections", 5},      {"store_batches", 8}, {"store_average_batch", 7.5}};
  auto w = statsWindow(start, end);
  ASSERT_TRUE(w.isOk()) << w.status().message();
  EXPECT_DOUBLE_EQ((*w)["seconds"].get<double>(), 10);
  EXPECT_DOUBLE_EQ((*w)["edits"].get<double>(), 20);
  EXPECT_DOUBLE_EQ((*w)["edits_per_second"].get<double>(), 2);
  EXPECT_DOUBLE_EQ((*w)["bytes_sent_per_second"].get<double>(), 500);
  EXPECT_DOUBLE_EQ((*w)["rejects"].get<double>(), 0);
  // (0.6 * 60 - 0.5 * 40) / 20 = 0.8 ms per edit of the window alone.
  EXPECT_DOUBLE_EQ((*w)["tessellate_ms_per_edit"].get<double>(), 0.8);
  // (7.5 * 8 - 10 * 4) / 4 = 5 per batch.
  EXPECT_DOUBLE_EQ((*w)["store_average_batch"].get<double>(), 5);
  EXPECT_DOUBLE_EQ((*w)["edits_per_delta"].get<double>(), 4);
  EXPECT_DOUBLE_EQ((*w)["connections"].get<double>(), 5);
  EXPECT_FALSE(w->contains("frames_sent"));  // in neither sample

  // An idle window: no per-edit averages to give.
  auto idle = statsWindow(end, {{"uptime_seconds", 111}, {"edits", 60}, {"tessellate_ms_per_edit", 0.6}});
  ASSERT_TRUE(idle.isOk());
  EXPECT_DOUBLE_EQ((*idle)["edits"].get<double>(), 0);
  EXPECT_DOUBLE_EQ((*idle)["edits_per_second"].get<double>(), 0);
  EXPECT_FALSE(idle->contains("tessellate_ms_per_edit"));

  auto restarted = statsWindow(end, {{"uptime_seconds", 2}});
  EXPECT_FALSE(restarted.isOk());
}

}  // namespace
}  // namespace tessera::replay
