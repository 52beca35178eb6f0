// Structured logs: one JSON object per line, on stderr or in a log file, e.g.
//   {"ts":"2026-11-22T01:40:00.123Z","level":"info","event":"edit","doc":3,"version":17,"ms":1.2}
// Values are escaped; tokens are never passed here (the connection logs
// only whether a session authenticated and with which role).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include "core/util/status.h"

namespace tessera::server {

enum class LogLevel { kDebug, kInfo, kWarn, kError };

using LogValue = std::variant<int64_t, uint64_t, double, bool, std::string_view>;
using LogField = std::pair<std::string_view, LogValue>;

void setLogLevel(LogLevel level);

// Sends log lines to `path` (appending, created 0640) from now on. SIGHUP
// handling calls reopenLogFile() so that logrotate can move the file away:
// the next line goes to a new file under the same name.
Status setLogFile(const std::string& path);
Status reopenLogFile();
void logEvent(LogLevel level, std::string_view event, std::initializer_list<LogField> fields = {});

}  // namespace tessera::server
