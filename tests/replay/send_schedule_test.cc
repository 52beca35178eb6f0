// The load tester's open model and its HdrHistogram output
// (client/replay/send_schedule.h, hgrm.h): constant sends are due exactly
// where the rate puts them; Poisson arrivals have exponential gaps of the
// rate's mean (their mean, spread and tail), the same for the same seed;
// and the percentile distribution's rows are the samples' nearest ranks.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <vector>

#include "client/replay/hgrm.h"
#include "client/replay/send_schedule.h"

namespace tessera::replay {
namespace {

using Clock = SendSchedule::Clock;

double secondsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

TEST(SendSchedule, ConstantSendsAreDueWhereTheRatePutsThem) {
  const Clock::time_point start = Clock::now();
  SendSchedule s(Arrivals::kConstant, 40, start, 0.25, 1);
  // To the nearest tick of the clock (1 ns).
  for (int k = 0; k < 4000; ++k, s.advance())
    ASSERT_NEAR(secondsBetween(start, s.due()), (k + 0.25) / 40, 1e-9) << k;
}

TEST(SendSchedule, PoissonGapsAreExponentialWithTheRatesMeanAndRepeatForASeed) {
  const Clock::time_point start = Clock::now();
  const double rate = 50;
  SendSchedule a(Arrivals::kPoisson, rate, start, 0, 7), b(Arrivals::kPoisson, rate, start, 0, 7),
      other(Arrivals::kPoisson, rate, start, 0, 8);
  const int n = 20000;
  std::vector<double> gaps;
  Clock::time_point last = start;
  bool differs = false;
  for (int k = 0; k < n; ++k) {
    ASSERT_EQ(a.due(), b.due()) << k;
    differs |= a.due() != other.due();
    gaps.push_back(secondsBetween(last, a.due()));
    last = a.due();
    a.advance(), b.advance(), other.advance();
  }
  EXPECT_TRUE(differs) << "another seed, another schedule";
  double sum = 0, squares = 0;
  int aboveMean = 0;
  for (double g : gaps) sum += g, squares += g * g;
  const double mean = sum / n, sd = std::sqrt(squares / n - mean * mean);
  for (double g : gaps) aboveMean += g > 1 / rate;
  // An exponential gap of rate r: mean 1/r, standard deviation 1/r, and
  // P(gap > 1/r) = 1/e. Over 20,000 gaps the mean's standard error is 0.7 %.
  EXPECT_NEAR(mean * rate, 1, 0.03);
  EXPECT_NEAR(sd / mean, 1, 0.05);
  EXPECT_NEAR(static_cast<double>(aboveMean) / n, std::exp(-1.0), 0.015);
}

TEST(SendSchedule, ArrivalsAreNamed) {
  EXPECT_EQ(*parseArrivals("constant"), Arrivals::kConstant);
  EXPECT_EQ(*parseArrivals("poisson"), Arrivals::kPoisson);
  auto bad = parseArrivals("bursty");
  ASSERT_FALSE(bad.isOk());
  EXPECT_NE(bad.status().message().find("'bursty'"), std::string::npos);
}

struct Row {
  double value, percentile;
  long long count;
};

std::vector<Row> rowsOf(const std::string& text) {
  std::vector<Row> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // the column names
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Row r{};
    fields >> r.value >> r.percentile >> r.count;
    rows.push_back(r);
  }
  return rows;
}

TEST(Hgrm, RowsAreTheSamplesNearestRanksAndTheFooterTheirSummary) {
  std::vector<double> samples;
  for (int i = 1000; i >= 1; --i) samples.push_back(i);  // unsorted on purpose: 1..1000 ms
  const std::string text = percentileDistribution(samples);
  EXPECT_EQ(text.rfind("       Value     Percentile TotalCount 1/(1-Percentile)", 0), 0u) << text;
  const std::vector<Row> rows = rowsOf(text);
  ASSERT_GT(rows.size(), 20u) << text;
  for (size_t i = 0; i < rows.size(); ++i) {
    // The nearest rank of its percentile (at least 1), and that sample.
    const long long rank = std::max(1LL, static_cast<long long>(std::ceil(rows[i].percentile * 1000 - 1e-9)));
    EXPECT_EQ(rows[i].count, std::min(rank, 1000LL)) << i;
    EXPECT_DOUBLE_EQ(rows[i].value, static_cast<double>(rows[i].count)) << i;
    if (i > 0) EXPECT_GE(rows[i].percentile, rows[i - 1].percentile) << i;
  }
  EXPECT_DOUBLE_EQ(rows.front().percentile, 0);
  EXPECT_DOUBLE_EQ(rows.back().percentile, 1);
  EXPECT_DOUBLE_EQ(rows.back().value, 1000);
  bool half = false, ninety = false;
  for (const Row& r : rows) {
    half |= r.percentile == 0.5 && r.value == 500;
    ninety |= std::abs(r.percentile - 0.9) < 1e-12 && r.value == 900;
  }
  EXPECT_TRUE(half && ninety) << text;
  EXPECT_NE(text.find("#[Mean    =      500.500, StdDeviation   =      288.819]"), std::string::npos) << text;
  EXPECT_NE(text.find("#[Max     =     1000.000, Total count    =         1000]"), std::string::npos) << text;
  // No samples: the header and a footer of zeros, nothing to plot.
  EXPECT_TRUE(rowsOf(percentileDistribution({})).empty());
}

}  // namespace
}  // namespace tessera::replay
