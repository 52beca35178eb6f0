#include "server/base/log.h"

#include <fcntl.h>
#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <mutex>

#include <nlohmann/json.hpp>

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
    case LogLevel::kDebug:
      return "debug";
    case LogLevel::kInfo:
      return "info";
    case LogLevel::kWarn:
      return "warn";
    case LogLevel::kError:
      return "error";
  }
  return "info";
}

}  // namespace

void setLogLevel(LogLevel level) {
  minimumLevel = static_cast<int>(level);
}

Status setLogFile(const std::string& path) {
  TESSERA_ASSIGN_OR_RETURN(std::FILE * file, openAppending(path));
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
  const auto millis =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char ts[64];  // room for any int fields, so the compiler can prove no truncation
  std::snprintf(ts, sizeof ts, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900, utc.tm_mon + 1,
                utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, static_cast<int>(millis));
  // Keys in the order written: ts, level, event, then the fields.
  nlohmann::ordered_json object;
  object["ts"] = ts;
  object["level"] = levelName(level);
  object["event"] = event;
  for (const LogField& field : fields) {
    nlohmann::ordered_json& slot = object[std::string(field.first)];
    std::visit([&slot](const auto& v) { slot = v; }, field.second);
  }
  // Bytes that are not UTF-8 (a client's text quoted in an event) become
  // U+FFFD rather than an exception or an invalid line; JSON has no inf or
  // NaN, which are written as null.
  std::string line = object.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  line += '\n';
  std::lock_guard lock(outputMutex);
  std::FILE* target = output != nullptr ? output : stderr;
  std::fwrite(line.data(), 1, line.size(), target);
  std::fflush(target);
}

}  // namespace tessera::server
