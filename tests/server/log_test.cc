// The server's log lines (server/base/log.h): one JSON object per line,
// read back here with a JSON parser, keys in the order written.
#include "server/base/log.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/test_meshes.h"

namespace tessera::server {
namespace {

std::vector<std::string> linesOf(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(Log, EveryLineIsOneJsonObjectWhateverTheTextHolds) {
  const std::string dir = testing::makeTempDir("tessera-log");
  const std::string path = dir + "/server.log";
  ASSERT_TRUE(setLogFile(path).isOk());
  const std::string quoted = "a \"quoted\" name\\ with\na newline and a tab\t";
  const std::string notUtf8 = std::string("cube") + static_cast<char>(0xff) + ".obj";
  logEvent(LogLevel::kWarn, "odd_text",
           {{"doc", uint64_t{3}},
            {"text", std::string_view(quoted)},
            {"file", std::string_view(notUtf8)},
            {"ms", 1.25},
            {"none", std::nan("")},
            {"ok", true},
            {"delta", int64_t{-7}}});
  logEvent(LogLevel::kDebug, "below_the_level");  // the default level is info: not written
  logEvent(LogLevel::kInfo, "plain");
  ASSERT_TRUE(setLogFile(dir + "/other.log").isOk());  // closes server.log; later tests log elsewhere

  const auto lines = linesOf(path);
  ASSERT_EQ(lines.size(), 2u);
  const auto first = nlohmann::ordered_json::parse(lines[0]);  // throws on a line that is not JSON
  std::vector<std::string> keys;
  for (const auto& [key, value] : first.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"ts", "level", "event", "doc", "text", "file", "ms", "none", "ok",
                                            "delta"}));
  EXPECT_EQ(first["level"], "warn");
  EXPECT_EQ(first["event"], "odd_text");
  EXPECT_EQ(first["doc"], 3);
  EXPECT_EQ(first["text"], quoted);
  EXPECT_EQ(first["file"], "cube\xEF\xBF\xBD.obj");  // U+FFFD for the byte that is not UTF-8
  EXPECT_EQ(first["ms"], 1.25);
  EXPECT_TRUE(first["none"].is_null());  // JSON has no NaN
  EXPECT_EQ(first["ok"], true);
  EXPECT_EQ(first["delta"], -7);
  EXPECT_EQ(first["ts"].get<std::string>().size(), std::string("2026-11-22T01:40:00.123Z").size());
  EXPECT_EQ(nlohmann::json::parse(lines[1])["event"], "plain");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera::server
