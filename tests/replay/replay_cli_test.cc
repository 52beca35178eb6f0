// tessera-replay's command line: --version, per-subcommand
// help, --opt=value, and usage errors that name the option (exit 2).
#include <gtest/gtest.h>

#include "replay/replay_support.h"
#include "tessera/version.h"

namespace tessera {
namespace {

using testing::run;

const std::string kReplay = TESSERA_REPLAY_PATH;

TEST(ReplayCli, VersionAndPerCommandHelp) {
  auto [version, code] = run(kReplay + " --version");
  EXPECT_EQ(code, 0);
  EXPECT_EQ(version, std::string("tessera-replay ") + kVersion + "\n");
  auto [help, helpCode] = run(kReplay + " load --help");
  EXPECT_EQ(helpCode, 0);
  EXPECT_NE(help.find("tessera-replay load"), std::string::npos) << help;
  EXPECT_NE(help.find("--threshold"), std::string::npos) << help;
  EXPECT_EQ(help.find("--speed"), std::string::npos) << help;          // replay's
  EXPECT_EQ(help.find("--until-version"), std::string::npos) << help;  // record's
  auto [all, allCode] = run(kReplay + " --help");
  EXPECT_EQ(allCode, 0);
  for (const char* command : {"generate", "check", "replay", "record", "surface", "load"}) {
    EXPECT_NE(all.find(command), std::string::npos) << command;
  }
}

TEST(ReplayCli, OptionEqualsValue) {
  const std::string dir = testing::makeTempDir("tessera-replay-cli");
  auto [out, code] =
      run(kReplay + " generate -o " + dir + "/a.jsonl --editors=2 --rate=20 --seconds=0.5 --seed=3");
  EXPECT_EQ(code, 0) << out;
  EXPECT_EQ(out, "wrote " + dir + "/a.jsonl: 20 commands by 2 editors\n");
  auto [checked, checkCode] = run(kReplay + " check " + dir + "/a.jsonl");
  EXPECT_EQ(checkCode, 0);
  EXPECT_EQ(checked, dir + "/a.jsonl: 20 commands\n");
}

TEST(ReplayCli, UsageErrorsNameTheOption) {
  struct Case {
    const char* args;
    const char* named;
  };
  for (const Case& c :
       {Case{" load --port 1 --token t --document 1 --rate=abc", "--rate"},
        Case{" load --port 1 --token t --document 1 --rate 0", "--rate: 0 is not in (0, 200]"},
        Case{" load --port 1 --token t --document 1 --bogus", "--bogus"},
        Case{" load --port 1 --token t", "--document"},
        Case{" surface --port 70000 --token t --document 1", "--port"},
        Case{" load --port 1 --document 1", "a token is needed: --token T or --token-file F"},
        Case{" generate", "--output"}, Case{"", "subcommand"}, Case{" fly", "fly"}}) {
    auto [out, code] = run(kReplay + c.args, true);
    EXPECT_EQ(code, 2) << c.args << "\n" << out;
    EXPECT_NE(out.find(c.named), std::string::npos) << c.args << "\n" << out;
  }
}

}  // namespace
}  // namespace tessera
