#include "client/cli/human_format.h"

#include <cmath>
#include <cstdio>

#include "core/mesh/sharpness.h"

namespace tessera::cli {

namespace {

bool contains(const std::string& text, const char* part) {
  return text.find(part) != std::string::npos;
}

bool endsWith(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

// Inserts a comma every three digits of the integer part of `digits`.
std::string grouped(const std::string& digits) {
  const size_t start = digits[0] == '-' ? 1 : 0;
  size_t end = digits.find('.');
  if (end == std::string::npos) end = digits.size();
  std::string out = digits;
  for (size_t i = end; i > start + 3; i -= 3) out.insert(i - 3, ",");
  return out;
}

}  // namespace

std::string formatCount(uint64_t value) {
  return grouped(std::to_string(value));
}

std::string formatDecimal(double value, int decimals) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return grouped(buffer);
}

std::string formatBytes(double bytes) {
  if (!std::isfinite(bytes) || bytes < 0) return formatDecimal(bytes, 0) + " B";
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int unit = 0;
  while (bytes >= 1024 && unit < 4) bytes /= 1024, ++unit;
  if (unit == 0) return formatDecimal(bytes, 0) + " B";
  return formatDecimal(bytes, bytes < 10 ? 2 : 1) + " " + units[unit];
}

std::string formatSharpness(double sharpness) {
  // Infinite sharpness is stored as the finite sentinel 10 (every value from
  // 10 up acts alike, core/mesh/sharpness.h): print what it means.
  if (std::isinf(sharpness) || isInfinite(static_cast<float>(sharpness))) return "inf";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", sharpness);
  return buffer;
}

std::string formatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return formatDecimal(seconds, 1) + " s";
  char buffer[64];
  if (seconds < 60) {
    std::snprintf(buffer, sizeof buffer, "%.1f s", seconds);
  } else if (seconds < 3600) {
    std::snprintf(buffer, sizeof buffer, "%d min %02d s", static_cast<int>(seconds / 60),
                  static_cast<int>(seconds) % 60);
  } else if (seconds < 86400) {
    std::snprintf(buffer, sizeof buffer, "%d h %02d min", static_cast<int>(seconds / 3600),
                  static_cast<int>(seconds / 60) % 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%d d %02d h", static_cast<int>(seconds / 86400),
                  static_cast<int>(seconds / 3600) % 24);
  }
  return buffer;
}

std::string formatStat(const std::string& name, double value) {
  if (name == "uptime_seconds" || endsWith(name, "_seconds")) return formatDuration(value);
  if (contains(name, "bytes")) {
    return formatBytes(value) + (contains(name, "per_second") ? "/s" : "");
  }
  if (contains(name, "_ms")) return formatDecimal(value, 3) + " ms";
  if (contains(name, "per_second")) return formatDecimal(value, 2) + "/s";
  if (contains(name, "average") || contains(name, "_per_")) return formatDecimal(value, 2);
  if (value == std::floor(value) && std::fabs(value) < 9.0e15) {
    return value < 0 ? "-" + formatCount(static_cast<uint64_t>(-value))
                     : formatCount(static_cast<uint64_t>(value));
  }
  return formatDecimal(value, 2);
}

}  // namespace tessera::cli
