// tessera-replay (docs/REPLAY.md): the script format's errors, and the real
// binary against the real server -- a short bounded load run, and a script
// replayed on two fresh servers ending at the same surface hash.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "client/replay/script.h"
#include "replay/replay_support.h"

namespace tessera {
namespace {

using replay::parseScript;
using testing::field;
using testing::ReplayServer;
using testing::run;

constexpr const char* kHeader = "{\"format\":\"tessera-replay\",\"version\":1,\"document\":1}\n";

std::string errorOf(const std::string& text) {
  auto parsed = parseScript(text, "s.jsonl");
  return parsed.isOk() ? "parsed" : parsed.status().message();
}

TEST(ReplayScript, ParsesEveryCommandAndRoundTrips) {
  const std::string text =
      std::string(kHeader) +
      "{\"t\":0,\"actor\":\"a\",\"cmd\":\"move\",\"vertex\":\"v2:40\",\"mode\":\"offset\",\"to\":[0,0,0.01]}"
      "\n"
      "\n"
      "{\"t\":5,\"actor\":\"b\",\"cmd\":\"move\",\"vertex\":[\"v1:1\",\"v1:2\"],\"mode\":\"direct\",\"to\":["
      "1,2,3]}\n"
      "{\"t\":5,\"actor\":\"a\",\"cmd\":\"crease\",\"edge\":\"e1:5\",\"sharpness\":\"inf\"}\n"
      "{\"t\":9,\"actor\":\"a\",\"cmd\":\"corner\",\"vertex\":\"v0:3\",\"sharpness\":2.5}\n"
      "{\"t\":10,\"actor\":\"a\",\"cmd\":\"undo\",\"edit\":-1}\n"
      "{\"t\":11,\"actor\":\"a\",\"cmd\":\"redo\",\"edit\":4}\n";
  auto script = parseScript(text, "s.jsonl");
  ASSERT_TRUE(script.isOk()) << script.status().message();
  EXPECT_EQ(script->header.document, 1u);
  ASSERT_EQ(script->commands.size(), 6u);
  EXPECT_EQ(script->commands[1].vertices.size(), 2u);
  EXPECT_FALSE(script->commands[1].offset);
  EXPECT_EQ(script->commands[1].line, 4);
  EXPECT_TRUE(std::isinf(script->commands[2].sharpness));
  EXPECT_EQ(script->commands[4].edit, -1);
  std::string again = replay::headerLine(script->header) + "\n";
  for (const auto& c : script->commands) again += replay::commandLine(c) + "\n";
  auto reparsed = parseScript(again, "again");
  ASSERT_TRUE(reparsed.isOk()) << reparsed.status().message();
  for (size_t i = 0; i < script->commands.size(); ++i) {
    EXPECT_EQ(replay::commandLine(reparsed->commands[i]), replay::commandLine(script->commands[i]));
  }
}

TEST(ReplayScript, BadLinesNameFileLineAndReason) {
  const std::string h = kHeader;
  EXPECT_EQ(errorOf(""), "s.jsonl: empty script (no header line)");
  EXPECT_EQ(errorOf("{\"t\":0}\n"),
            "s.jsonl:1: the first line must be a header {\"format\":\"tessera-replay\",\"version\":1,...}");
  EXPECT_EQ(errorOf("{\"format\":\"tessera-replay\",\"version\":2}\n"),
            "s.jsonl:1: script version 2 is not supported (this build reads version 1)");
  EXPECT_EQ(errorOf(h + "{\"t\":0,\"actor\":\"a\",\"cmd\":\"move\"\n"), "s.jsonl:2: not valid JSON");
  EXPECT_EQ(errorOf(h + "{\"actor\":\"a\",\"cmd\":\"undo\",\"edit\":1}\n"),
            "s.jsonl:2: \"t\" must be a non-negative integer (milliseconds)");
  EXPECT_EQ(errorOf(h + "{\"t\":0,\"actor\":\"\",\"cmd\":\"undo\",\"edit\":1}\n"),
            "s.jsonl:2: \"actor\" must be a non-empty string");
  EXPECT_EQ(errorOf(h + "{\"t\":0,\"actor\":\"a\",\"cmd\":\"jump\"}\n"),
            "s.jsonl:2: unknown cmd \"jump\" (expected move, crease, corner, interpolate, undo, redo)");
  EXPECT_EQ(errorOf(h + "{\"t\":0,\"actor\":\"a\",\"cmd\":\"move\",\"vertex\":\"v2:40\",\"mode\":\"offset\","
                        "\"to\":[0,0]}\n"),
            "s.jsonl:2: \"to\" must be [x, y, z]");
  EXPECT_EQ(errorOf(h + "{\"t\":0,\"actor\":\"a\",\"cmd\":\"move\",\"vertex\":\"v2:40\",\"mode\":\"fly\","
                        "\"to\":[0,0,0]}\n"),
            "s.jsonl:2: \"mode\" must be \"offset\" or \"direct\"");
  EXPECT_EQ(errorOf(h + "{\"t\":0,\"actor\":\"a\",\"cmd\":\"crease\",\"edge\":\"e1:5\",\"sharpness\":-1}\n"),
            "s.jsonl:2: \"sharpness\" must be >= 0");
  EXPECT_EQ(errorOf(h + "{\"t\":0,\"actor\":\"a\",\"cmd\":\"undo\",\"edit\":0}\n"),
            "s.jsonl:2: \"edit\" must be an edit id (> 0) or a step back through the actor's edits (< 0)");
  EXPECT_EQ(errorOf(h + "{\"t\":0,\"actor\":\"a\",\"cmd\":\"undo\",\"edit\":1,\"extra\":true}\n"),
            "s.jsonl:2: unknown key \"extra\"");
  EXPECT_EQ(errorOf(h + "{\"t\":5,\"actor\":\"a\",\"cmd\":\"undo\",\"edit\":1}\n{\"t\":4,\"actor\":\"a\","
                        "\"cmd\":\"undo\",\"edit\":1}\n"),
            "s.jsonl:3: \"t\" 4 is before the previous line's 5");
  // A bad element id: the id parser's reason after FILE:LINE.
  const std::string bad =
      errorOf(h + "{\"t\":0,\"actor\":\"a\",\"cmd\":\"corner\",\"vertex\":\"e1:2\",\"sharpness\":1}\n");
  EXPECT_EQ(bad.rfind("s.jsonl:2: ", 0), 0u) << bad;
}

TEST(ReplayScript, GeneratedScriptsAreDeterministicAndParse) {
  replay::GenerateOptions g{.document = 3, .editors = 3, .rate = 20, .seconds = 2, .seed = 7};
  auto a = replay::generateScript(g), b = replay::generateScript(g);
  ASSERT_EQ(a.commands.size(), 120u);
  std::string text = replay::headerLine(a.header) + "\n";
  for (size_t i = 0; i < a.commands.size(); ++i) {
    EXPECT_EQ(replay::commandLine(a.commands[i]), replay::commandLine(b.commands[i]));
    text += replay::commandLine(a.commands[i]) + "\n";
  }
  auto parsed = parseScript(text, "generated");
  ASSERT_TRUE(parsed.isOk()) << parsed.status().message();
  EXPECT_EQ(parsed->header.document, 3u);
}

TEST(ReplayLoad, ShortBoundedRunAcksEveryEditWithoutGaps) {
  ReplayServer s;
  testing::startServer(s, "tessera-replay-load");
  if (HasFatalFailure()) return;
  const std::string report = testing::makeTempDir("tessera-replay-report") + "/report.json";
  auto [out, code] = run(
      std::string(TESSERA_REPLAY_PATH) + " load" + s.connection() +
      " --editors 2 --viewers 6 --decode-viewers 2 --rate 10 --seconds 2 --profile 2,5,10 --drain-seconds 5"
      " --report " +
      report);
  EXPECT_EQ(code, 0) << out;
  std::ifstream in(report);
  ASSERT_TRUE(in) << out;
  nlohmann::json r = nlohmann::json::parse(in);
  EXPECT_EQ(r["format"], "tessera-replay-report");
  EXPECT_EQ(r["version"], 2);
  const int64_t sent = r["edits"]["sent"];
  EXPECT_GE(sent, 30);  // 2 editors x 10/s x 2 s = 40, paced
  EXPECT_LE(sent, 42);
  EXPECT_EQ(r["edits"]["acked"], sent);
  EXPECT_EQ(r["edits"]["rejected"], 0);
  EXPECT_EQ(r["errors"]["count"], 0) << r["errors"].dump();
  EXPECT_EQ(r["viewers"]["gaps"], 0);
  EXPECT_EQ(r["viewers"]["resyncs"], 0);
  EXPECT_EQ(r["viewers"]["ready_at_end"], 6);
  EXPECT_EQ(r["client"]["pooled_viewers"], 4);  // the counting viewers share the pool's thread
  EXPECT_EQ(r["viewers"]["version_min"], r["final_version"]);
  EXPECT_EQ(r["viewers"]["behind_at_end"], 0);
  EXPECT_EQ(r["final_version"], 1 + sent);
  EXPECT_TRUE(r["viewers"]["decoded_hashes_agree"].get<bool>());
  EXPECT_EQ(r["viewers"]["decoded_at_final_version"], 2);
  EXPECT_GT(r["viewers"]["bytes_per_second_per_viewer"].get<double>(), 0);
  for (const char* which : {"edit_to_ack", "edit_to_delta"}) {
    const auto& p = r["latency_ms"][which];
    EXPECT_EQ(p["count"], std::string(which) == "edit_to_ack" ? sent : 6 * sent) << which;
    EXPECT_GT(p["p50"].get<double>(), 0) << which;
    EXPECT_LE(p["p50"].get<double>(), p["p90"].get<double>()) << which;
    EXPECT_LE(p["p90"].get<double>(), p["p99"].get<double>()) << which;
    EXPECT_LE(p["p99"].get<double>(), p["max"].get<double>()) << which;
  }
  EXPECT_GE(r["server"]["stats"]["edits"].get<double>(), static_cast<double>(sent));
  EXPECT_NE(out.find("edit -> delta"), std::string::npos) << out;
}

// The same on a Catmull-Clark document (the cube as six quads): edits of
// its level-1 vertices (8 corners, 6 face points, 12 edge points), every
// one acknowledged and streamed to every viewer, the decoding viewers'
// surfaces hashing to the server's.
TEST(ReplayLoad, ACatmullClarkDocumentAcksEveryEditWithoutGaps) {
  ReplayServer s;
  testing::startServer(s, "tessera-replay-catmark", "good/cube_quads.obj");
  if (HasFatalFailure()) return;
  const std::string report = testing::makeTempDir("tessera-replay-report") + "/report.json";
  auto [out, code] = run(std::string(TESSERA_REPLAY_PATH) + " load" + s.connection() +
                         " --editors 2 --viewers 4 --decode-viewers 2 --rate 10 --seconds 2 --profile 1,4,10"
                         " --vertex-level 1 --vertex-count 26 --drain-seconds 5 --report " +
                         report);
  EXPECT_EQ(code, 0) << out;
  std::ifstream in(report);
  ASSERT_TRUE(in) << out;
  nlohmann::json r = nlohmann::json::parse(in);
  const int64_t sent = r["edits"]["sent"];
  EXPECT_GE(sent, 30);
  EXPECT_EQ(r["edits"]["acked"], sent);
  EXPECT_EQ(r["edits"]["rejected"], 0);
  EXPECT_EQ(r["errors"]["count"], 0) << r["errors"].dump();
  EXPECT_EQ(r["viewers"]["gaps"], 0);
  EXPECT_EQ(r["viewers"]["behind_at_end"], 0);
  EXPECT_EQ(r["final_version"], 1 + sent);
  EXPECT_TRUE(r["viewers"]["decoded_hashes_agree"].get<bool>());
  EXPECT_EQ(r["viewers"]["decoded_at_final_version"], 2);
}

// View-dependent viewers on camera paths (docs/REPLAY.md §3): every viewer
// follows its own orbit, the decoding ones check their tiles' hash against
// the server's, and the report gives the tile cache's figures.
TEST(ReplayLoad, ViewersOnCameraPathsGetTheirTilesWithoutGaps) {
  ReplayServer s;
  testing::startServer(s, "tessera-replay-cameras");
  if (HasFatalFailure()) return;
  const std::string report = testing::makeTempDir("tessera-replay-report") + "/report.json";
  auto [out, code] = run(std::string(TESSERA_REPLAY_PATH) + " load" + s.connection() +
                         " --editors 1 --viewers 6 --decode-viewers 2 --rate 5 --seconds 2 --drain-seconds 5"
                         " --cameras orbit --camera-target 0.5 0.5 0.5 0.87 --camera-rate 10 --report " +
                         report);
  EXPECT_EQ(code, 0) << out;
  std::ifstream in(report);
  ASSERT_TRUE(in) << out;
  nlohmann::json r = nlohmann::json::parse(in);
  EXPECT_EQ(r["errors"]["count"], 0) << r["errors"].dump();
  EXPECT_EQ(r["viewers"]["gaps"], 0);
  EXPECT_EQ(r["viewers"]["ready_at_end"], 6);
  EXPECT_EQ(r["viewers"]["behind_at_end"], 0);
  EXPECT_EQ(r["config"]["cameras"]["path"], "orbit");
  const auto& w = r["server"]["window"];
  EXPECT_GT(w["views_applied"].get<double>(), 0) << w.dump();
  EXPECT_GT(w["tile_cache_hit_ratio"].get<double>(), 0) << w.dump();
  EXPECT_LE(w["tile_cache_hit_ratio"].get<double>(), 1) << w.dump();
  EXPECT_GT(r["latency_ms"]["edit_to_tiles"]["count"].get<int64_t>(), 0);
  EXPECT_GT(r["viewers"]["delta_regions_per_second_per_viewer"].get<double>(), 0);
  EXPECT_NE(out.find("tiles over the run"), std::string::npos) << out;
  // A camera path needs its sphere.
  auto [bad, badCode] =
      run(std::string(TESSERA_REPLAY_PATH) + " load" + s.connection() + " --cameras orbit", true);
  EXPECT_EQ(badCode, 2) << bad;
  EXPECT_NE(bad.find("--camera-target"), std::string::npos) << bad;
}

// Replays the script that `generateOptions` makes on two fresh servers
// with `mesh` (the default cube when empty): every command accepted, the
// same final version and surface hash on both, and one that differs from
// the unedited document's.
void expectSameSurfaceOnTwoFreshServers(const std::string& generateOptions, const std::string& mesh,
                                        const std::string& commands) {
  const std::string script = testing::makeTempDir("tessera-replay-script") + "/session.jsonl";
  auto [generated, code] =
      run(std::string(TESSERA_REPLAY_PATH) + " generate -o " + script + " " + generateOptions);
  ASSERT_EQ(code, 0) << generated;
  std::string hashes[2], versions[2];
  for (int i = 0; i < 2; ++i) {
    ReplayServer s;
    testing::startServer(s, "tessera-replay-twice", mesh);
    if (::testing::Test::HasFatalFailure()) return;
    auto [before, beforeCode] =
        run(std::string(TESSERA_REPLAY_PATH) + " surface" + s.connection() + " --profile 2,5,10");
    ASSERT_EQ(beforeCode, 0) << before;
    auto [out, replayCode] =
        run(std::string(TESSERA_REPLAY_PATH) + " replay " + script + s.connection() + " --speed 4");
    ASSERT_EQ(replayCode, 0) << out;
    EXPECT_EQ(field(out, "commands"), commands) << out;
    EXPECT_EQ(field(out, "rejected"), "0") << out;
    versions[i] = field(out, "version");
    hashes[i] = field(out, "surface_hash");
    ASSERT_FALSE(hashes[i].empty()) << out;
    EXPECT_NE(hashes[i], field(before, "surface_hash")) << "the edits changed nothing";
  }
  EXPECT_EQ(versions[0], versions[1]);
  EXPECT_EQ(hashes[0], hashes[1]);
}

TEST(ReplayRun, ReplayingOnTwoFreshServersGivesTheSameSurfaceHash) {
  expectSameSurfaceOnTwoFreshServers("--editors 3 --rate 20 --seconds 1 --seed 42 --profile 2,5,10", "",
                                     "60");
}

// The same on a Catmull-Clark document (the cube as six quads; its level 1
// has 8 corners, 6 face points and 12 edge points): offsets, undos and redos
// of a script replay to the same surface on two fresh servers.
TEST(ReplayRun, ACatmullClarkScriptReplaysToTheSameSurfaceOnTwoFreshServers) {
  expectSameSurfaceOnTwoFreshServers(
      "--editors 3 --rate 20 --seconds 1 --seed 7 --profile 2,5,10 --vertex-level 1 --vertex-count 26",
      "good/cube_quads.obj", "60");
}

}  // namespace
}  // namespace tessera
