#include "server/log.h"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <mutex>
#include <unistd.h>

namespace tessera::server {

namespace {

std::atomic<int> minimumLevel{static_cast<int>(LogLevel::kInfo)};
std::mutex outputMutex;
std::FILE* output = nullptr;  // guarded by outputMutex; null: stderr
std::string outputPath;       // guarded by outputMutex

Expected<std::FILE*> openAppending(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0640);
  if (fd < 0) return ioError(path + ": cannot open the log file: " + std::strerror(errno));
  std::FILE* file = ::fdopen(fd, "a");
  if (file == nullptr) {
    ::close(fd);
    return ioError(path + ": cannot open the log file: " + std::strerror(errno));
  }
  return file;
}

const char* levelName(LogLevel level) {
  switch (level) {
    case LogLevel::kDebug: return "debug";
    case LogLevel::kInfo: return "info";
    case LogLevel::kWarn: return "warn";
    case LogLevel::kError: return "error";
  }
  return "info";
}

void appendEscaped(std::string& out, std::string_view text) {
  for (char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
}

}  // namespace

void setLogLevel(LogLevel level) { minimumLevel = static_cast<int>(level); }

Status setLogFile(const std::string& path) {
  TESSERA_ASSIGN_OR_RETURN(std::FILE* file, openAppending(path));
  std::lock_guard lock(outputMutex);
  if (output != nullptr) std::fclose(output);
  output = file;
  outputPath = path;
  return Status::ok();
}

Status reopenLogFile() {
  std::string path;
  {
    std::lock_guard lock(outputMutex);
    if (output == nullptr) return Status::ok();  // stderr: nothing to reopen
    path = outputPath;
  }
  // On failure the old file stays in use, so no line is lost.
  return setLogFile(path);
}

void logEvent(LogLevel level, std::string_view event, std::initializer_list<LogField> fields) {
  if (static_cast<int>(level) < minimumLevel) return;
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char ts[64];  // room for any int fields, so the compiler can prove no truncation
  std::snprintf(ts, sizeof ts, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday,
                utc.tm_hour, utc.tm_min, utc.tm_sec, static_cast<int>(millis));
  std::string line = "{\"ts\":\"";
  line += ts;
  line += "\",\"level\":\"";
  line += levelName(level);
  line += "\",\"event\":\"";
  appendEscaped(line, event);
  line += '"';
  for (const auto& [key, value] : fields) {
    line += ",\"";
    appendEscaped(line, key);
    line += "\":";
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::string_view>) {
            line += '"';
            appendEscaped(line, v);
            line += '"';
          } else if constexpr (std::is_same_v<T, bool>) {
            line += v ? "true" : "false";
          } else if constexpr (std::is_same_v<T, double>) {
            if (!std::isfinite(v)) {  // JSON has no inf or NaN
              line += "null";
              return;
            }
            char buf[32];
            std::snprintf(buf, sizeof buf, "%.6g", v);
            line += buf;
          } else {
            line += std::to_string(v);
          }
        },
        value);
  }
  line += "}\n";
  std::lock_guard lock(outputMutex);
  std::FILE* target = output != nullptr ? output : stderr;
  std::fwrite(line.data(), 1, line.size(), target);
  std::fflush(target);
}

}  // namespace tessera::server
