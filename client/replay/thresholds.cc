#include "client/replay/thresholds.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

namespace tessera::replay {

namespace {

const std::map<std::string, std::string> kLatencies = {{"ack", "edit_to_ack"},
                                                       {"edit_to_ack", "edit_to_ack"},
                                                       {"delta", "edit_to_delta"},
                                                       {"edit_to_delta", "edit_to_delta"}};
const std::map<std::string, std::string> kStats = {
    {"mean", "mean"}, {"stddev", "stddev"}, {"min", "min"}, {"max", "max"},    {"p50", "p50"},
    {"p90", "p90"},   {"p95", "p95"},       {"p99", "p99"}, {"p99.9", "p99_9"}};
// Where each count is in the report.
const std::map<std::string, std::pair<const char*, const char*>> kCounts = {
    {"errors", {"errors", "count"}},
    {"rejected", {"edits", "rejected"}},
    {"gaps", {"viewers", "gaps"}},
    {"resyncs", {"viewers", "resyncs"}},
    {"behind", {"viewers", "behind_at_end"}},
    {"sent", {"edits", "sent"}},
    {"acked", {"edits", "acked"}},
    {"throughput", {"edits", "throughput_per_second"}}};

const char* opText(Comparison op) {
  switch (op) {
    case Comparison::kLess:
      return "<";
    case Comparison::kLessEqual:
      return "<=";
    case Comparison::kGreater:
      return ">";
    case Comparison::kGreaterEqual:
      return ">=";
    case Comparison::kEqual:
      return "=";
  }
  return "?";
}

bool compare(double value, Comparison op, double limit) {
  switch (op) {
    case Comparison::kLess:
      return value < limit;
    case Comparison::kLessEqual:
      return value <= limit;
    case Comparison::kGreater:
      return value > limit;
    case Comparison::kGreaterEqual:
      return value >= limit;
    case Comparison::kEqual:
      return value == limit;
  }
  return false;
}

std::string joinKeys(const std::map<std::string, std::string>& m) {
  std::string out;
  for (const auto& [k, v] : m) out += (out.empty() ? "" : ", ") + k;
  return out;
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  std::string s = buf;
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s;
}

}  // namespace

Expected<Threshold> parseThreshold(const std::string& given) {
  Threshold t;
  t.text = given;
  std::string s;
  for (char c : given) {
    if (!std::isspace(static_cast<unsigned char>(c))) s += c;
  }
  auto bad = [&](const std::string& why) { return invalidArgument("--threshold '" + given + "': " + why); };
  const size_t opAt = s.find_first_of("<>=");
  if (opAt == std::string::npos) return bad("no comparison (expected <, <=, >, >= or =), e.g. 'p99<50ms'");
  std::string name = s.substr(0, opAt);
  size_t valueAt = opAt + 1;
  const char first = s[opAt];
  const char second = valueAt < s.size() ? s[valueAt] : '\0';
  if (second == '=') ++valueAt;
  if (first == '<') t.op = second == '=' ? Comparison::kLessEqual : Comparison::kLess;
  if (first == '>') t.op = second == '=' ? Comparison::kGreaterEqual : Comparison::kGreater;
  if (first == '=') t.op = Comparison::kEqual;  // "=" or "=="
  if (name.empty()) return bad("nothing to compare before '" + std::string(opText(t.op)) + "'");
  std::string value = s.substr(valueAt);

  // The number, then its unit.
  double limit = 0;
  auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), limit);
  if (ec != std::errc() || end == value.data() || !std::isfinite(limit)) {
    return bad("'" + value + "' is not a number");
  }
  const std::string unit(end, static_cast<const char*>(value.data() + value.size()));

  if (auto count = kCounts.find(name); count != kCounts.end()) {
    t.stat = name;
    if (!unit.empty() && !(name == "throughput" && unit == "/s"))
      return bad(name + " is a count and takes no unit");
    t.limit = limit;
    return t;
  }
  std::string stat = name;
  t.metric = "edit_to_delta";
  if (size_t dot = name.find('.'); dot != std::string::npos && kStats.find(name) == kStats.end()) {
    auto latency = kLatencies.find(name.substr(0, dot));
    if (latency == kLatencies.end()) {
      return bad("unknown latency '" + name.substr(0, dot) + "' (expected " + joinKeys(kLatencies) + ")");
    }
    t.metric = latency->second;
    stat = name.substr(dot + 1);
  }
  auto known = kStats.find(stat);
  if (known == kStats.end()) {
    return bad("unknown statistic '" + stat + "' (expected " + joinKeys(kStats) +
               ", or a count: errors, rejected, gaps, resyncs, behind, sent, acked, throughput)");
  }
  t.stat = known->second;
  if (unit == "us") {
    t.limit = limit / 1000;
  } else if (unit == "ms") {
    t.limit = limit;
  } else if (unit == "s") {
    t.limit = limit * 1000;
  } else {
    return bad(unit.empty() ? "a latency needs a unit: us, ms or s"
                            : "unknown unit '" + unit + "' (expected us, ms or s)");
  }
  return t;
}

std::string ThresholdResult::describe() const {
  const Threshold& t = threshold;
  std::string what;
  if (t.metric.empty()) {
    what = t.stat + " " + (measured ? number(value) : "n/a");
  } else {
    what = t.metric + " " + (t.stat == "p99_9" ? "p99.9" : t.stat) + " " +
           (measured ? number(value) + " ms" : "n/a (no samples)");
  }
  return t.text + ": " + what + (passed ? " (ok)" : " (FAILED)");
}

std::vector<ThresholdResult> checkThresholds(const std::vector<Threshold>& thresholds,
                                             const nlohmann::json& report) {
  std::vector<ThresholdResult> out;
  for (const Threshold& t : thresholds) {
    ThresholdResult r{.threshold = t};
    const nlohmann::json* source = nullptr;
    std::string key;
    if (t.metric.empty()) {
      const auto& [section, field] = kCounts.at(t.stat);
      if (report.contains(section)) source = &report[section], key = field;
    } else if (report.contains("latency_ms") && report["latency_ms"].contains(t.metric)) {
      source = &report["latency_ms"][t.metric];
      key = t.stat;
    }
    if (source && source->contains(key) && (*source)[key].is_number()) {
      r.measured = true;
      r.value = (*source)[key].get<double>();
      r.passed = compare(r.value, t.op, t.limit);
    }
    out.push_back(r);
  }
  return out;
}

}  // namespace tessera::replay
