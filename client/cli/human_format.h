// Numbers as people read them: whole counts with thousands separators
// ("5,042,010", never "5.04201e+06"), bytes in binary units ("4.8 MiB"),
// durations and rates with a few decimals, and sharpness with "inf".
#pragma once

#include <cstdint>
#include <string>

namespace tessera::cli {

std::string formatCount(uint64_t value);                // 5042010 -> "5,042,010"
std::string formatBytes(double bytes);                  // 5042010 -> "4.81 MiB"; below 1 KiB: "512 B"
std::string formatDecimal(double value, int decimals);  // thousands separators too: "12,345.68"
std::string formatSharpness(double sharpness);          // "inf" for an infinite one, else "%g"
std::string formatDuration(double seconds);             // "3 h 12 min", "4 min 05 s", "12.3 s"

// One of the server's stats (docs/PROTOCOL.md), formatted by what its name
// says it holds: *_bytes* in binary units, *_ms* and *_per_second* with
// decimals, uptime as a duration, counts as whole numbers.
std::string formatStat(const std::string& name, double value);

}  // namespace tessera::cli
