// tessera-replay: scripted sessions and load runs against tessera-server
// (the script and report formats are in docs/REPLAY.md). The
// command line is CLI11's: subcommands with their own --help, --opt=value,
// errors naming the option, exit 2 on usage errors.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <utility>

#include "client/replay/load_command.h"
#include "client/replay/record.h"
#include "client/replay/replay.h"
#include "client/replay/replay_cli.h"
#include "client/replay/script.h"
#include "tessera/version.h"

namespace {

using namespace tessera;
using namespace tessera::replay;

struct GenerateArgs {
  std::string output, profile;
  uint64_t document = 1, seed = 1, vertexCount = 8;
  int editors = 2, vertexLevel = 0;
  double rate = 10, seconds = 5, step = 0.01;
  bool noUndo = false;
};

struct ReplayArgs {
  ConnectionArgs connection;
  std::string script, profile;
  uint64_t document = 0;  // 0: the script's
  double speed = 1;
};

struct RecordArgs {
  ConnectionArgs connection;
  std::string output, profile;
  uint64_t document = 0, untilVersion = 0;
  double seconds = 0;
};

struct SurfaceArgs {
  ConnectionArgs connection;
  std::string profile;
  uint64_t document = 0;
};

int runGenerate(const GenerateArgs& a) {
  GenerateOptions g;
  g.document = a.document;
  g.editors = a.editors;
  g.rate = a.rate;
  g.seconds = a.seconds;
  g.seed = a.seed;
  g.vertexLevel = a.vertexLevel;
  g.vertexCount = a.vertexCount;
  g.step = a.step;
  g.undo = !a.noUndo;
  Script script = generateScript(g);
  auto header = withProfile(a.profile, script.header);
  if (!header.isOk()) return usage(header.status().message(), "generate");
  std::ofstream f(a.output, std::ios::binary);
  f << headerLine(*header) << "\n";
  for (const ScriptCommand& c : script.commands) f << commandLine(c) << "\n";
  if (!f.flush()) return fail(ioError(a.output + ": cannot write"));
  std::printf("wrote %s: %zu commands by %d editors\n", a.output.c_str(), script.commands.size(), g.editors);
  return 0;
}

int runCheck(const std::string& path) {
  auto script = readScript(path);
  if (!script.isOk()) return fail(script.status());
  std::printf("%s: %zu commands\n", path.c_str(), script->commands.size());
  return 0;
}

void printSurface(const SurfaceState& s) {
  std::printf("version %llu\nsurface_hash %016llx\ntriangles %lld\n",
              static_cast<unsigned long long>(s.version), static_cast<unsigned long long>(s.hash),
              static_cast<long long>(s.triangles));
}

int runReplayCommand(const ReplayArgs& a) {
  auto script = readScript(a.script);
  if (!script.isOk()) return fail(script.status());
  auto session = sessionOptions(a.connection);
  if (!session.isOk()) return usage(session.status().message(), "replay");
  const uint64_t doc = a.document != 0 ? a.document : script->header.document;
  auto header = withProfile(a.profile, script->header);
  if (!header.isOk()) return usage(header.status().message(), "replay");
  // A subscriber with the final profile before the first command too: the
  // server then updates that profile's tessellation edit by edit, as it does
  // for a live session's viewers and recorder, rather than building it at the
  // end (the two can differ in a normal: docs/REPLAY.md §2).
  auto before = readSurface(*session, doc, profileOf(*header));
  if (!before.isOk()) return fail(before.status());
  ReplayOptions options{.session = *session, .document = doc, .speed = a.speed};
  auto result = runReplay(*script, options);
  if (!result.isOk()) return fail(result.status());
  std::printf("commands %d\nacked %d\nrejected %d\n", result->commands, result->acked, result->rejected);
  auto surface = readSurface(*session, doc, profileOf(*header));
  if (!surface.isOk()) return fail(surface.status());
  printSurface(*surface);
  return 0;
}

int runRecordCommand(const RecordArgs& a) {
  auto session = sessionOptions(a.connection);
  if (!session.isOk()) return usage(session.status().message(), "record");
  session->name = "tessera-replay-record";
  if (a.seconds == 0 && a.untilVersion == 0)
    return usage("record needs --seconds S or --until-version V", "record");
  auto header = withProfile(a.profile, ScriptHeader{});
  if (!header.isOk()) return usage(header.status().message(), "record");
  std::ofstream f(a.output, std::ios::binary);
  if (!f) return fail(ioError(a.output + ": cannot write"));
  RecordOptions o;
  o.session = *session;
  o.document = a.document;
  o.header = *header;
  o.seconds = a.seconds == 0 ? 600 : a.seconds;
  o.untilVersion = a.untilVersion;
  o.out = &f;
  o.started = [&](uint64_t from) {
    std::printf("recording document %llu from version %llu\n", static_cast<unsigned long long>(a.document),
                static_cast<unsigned long long>(from));
    std::fflush(stdout);
    if (from != 1) {
      std::fprintf(
          stderr,
          "tessera-replay: the recording starts at version %llu: replay it on a copy of the document "
          "at that version, not on a fresh one\n",
          static_cast<unsigned long long>(from));
    }
  };
  auto result = runRecord(o);
  if (!result.isOk()) return fail(result.status().withContext("record"));
  if (!f.flush()) return fail(ioError(a.output + ": cannot write"));
  std::printf("commands %lld\nactors %zu\nfrom_version %llu\n", static_cast<long long>(result->commands),
              result->actors, static_cast<unsigned long long>(result->fromVersion));
  if (result->surface) {
    printSurface(*result->surface);
  } else {
    std::printf("version %llu\n", static_cast<unsigned long long>(result->lastVersion));
    std::fprintf(
        stderr, "tessera-replay: record: no surface hash: the recorder's view was not at the last version\n");
  }
  std::printf("wrote %s\n", a.output.c_str());
  if (!result->stopped.isOk()) return fail(result->stopped.withContext("record"));
  return 0;
}

int runSurface(const SurfaceArgs& a) {
  auto session = sessionOptions(a.connection);
  if (!session.isOk()) return usage(session.status().message(), "surface");
  auto header = withProfile(a.profile, ScriptHeader{});
  if (!header.isOk()) return usage(header.status().message(), "surface");
  auto surface = readSurface(*session, a.document, profileOf(*header));
  if (!surface.isOk()) return fail(surface.status());
  printSurface(*surface);
  return 0;
}

CLI::App* addGenerate(CLI::App& app, GenerateArgs& a) {
  CLI::App* c =
      app.add_subcommand("generate", "write a synthetic script: E editors, R offset edits per second each");
  c->add_option("-o,--output", a.output, "the script to write")->required();
  c->add_option("--document", a.document, "the document id in the header")->capture_default_str();
  c->add_option("--editors", a.editors, "actors")->check(CLI::Range(1, 1000))->capture_default_str();
  c->add_option("--rate", a.rate, "edits per second per editor, (0, 200]")
      ->check(within(0, 200, true))
      ->capture_default_str();
  c->add_option("--seconds", a.seconds, "script length, (0, 3600]")
      ->check(within(0, 3600, true))
      ->capture_default_str();
  c->add_option("--seed", a.seed, "random seed (the same options give the same file)")->capture_default_str();
  c->add_option("--vertex-level", a.vertexLevel, "moves on v<L>:0..N-1")
      ->check(CLI::Range(0, 12))
      ->capture_default_str();
  c->add_option("--vertex-count", a.vertexCount, "N of --vertex-level")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c->add_option("--step", a.step, "largest offset per axis")->capture_default_str();
  c->add_flag("--no-undo", a.noUndo, "no undo or redo commands");
  addProfileOption(*c, a.profile);
  return c;
}

CLI::App* addReplay(CLI::App& app, ReplayArgs& a) {
  CLI::App* c =
      app.add_subcommand("replay",
                         "replay a script, one connection per actor, in script order; then print the final "
                         "version and surface hash a fresh subscriber sees");
  c->add_option("SCRIPT", a.script, "the script")->required();
  addConnectionOptions(*c, a.connection);
  c->add_option("--document", a.document, "the document (default: the script's)");
  c->add_option("--speed", a.speed, "1 real time, 2 twice as fast, 0 no waiting")
      ->check(within(0, 1e6))
      ->capture_default_str();
  addProfileOption(*c, a.profile);
  return c;
}

CLI::App* addRecord(CLI::App& app, RecordArgs& a) {
  CLI::App* c = app.add_subcommand(
      "record",
      "record the document's commands live, as a script (any role that may open it); stops "
      "after S seconds, or once version V is recorded (then at most S, default 600)");
  addConnectionOptions(*c, a.connection);
  c->add_option("--document", a.document, "the document to record")->required()->check(CLI::PositiveNumber);
  c->add_option("-o,--output", a.output, "the script to write")->required();
  c->add_option("--seconds", a.seconds, "stop after S seconds, [0, 86400]")->check(within(0, 86400));
  c->add_option("--until-version", a.untilVersion, "stop once version V is recorded");
  addProfileOption(*c, a.profile);
  return c;
}

CLI::App* addSurface(CLI::App& app, SurfaceArgs& a) {
  CLI::App* c = app.add_subcommand("surface", "print the version and surface hash of a document");
  addConnectionOptions(*c, a.connection);
  c->add_option("--document", a.document, "the document")->required()->check(CLI::PositiveNumber);
  addProfileOption(*c, a.profile);
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("tessera-replay: scripted sessions and load runs against tessera-server (docs/REPLAY.md)",
               "tessera-replay");
  app.set_version_flag("--version", std::string("tessera-replay ") + tessera::kVersion);
  app.require_subcommand(1);
  // A repeated option keeps its last value, as the hand-written parser did.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.footer(
      "exit codes: 0 success, 1 a failure, 2 a usage error; load also 3 (connection errors, gaps or viewers\n"
      "behind), 4 (a --threshold failed), 5 (stopped: missing document or refused token)");

  GenerateArgs generate;
  std::string checked;
  ReplayArgs replayArgs;
  RecordArgs record;
  SurfaceArgs surface;
  LoadArgs load;
  CLI::App* generateCommand = addGenerate(app, generate);
  CLI::App* checkCommand = app.add_subcommand("check", "parse a script; errors are FILE:LINE: reason");
  checkCommand->add_option("SCRIPT", checked, "the script")->required();
  CLI::App* replayCommand = addReplay(app, replayArgs);
  CLI::App* recordCommand = addRecord(app, record);
  CLI::App* surfaceCommand = addSurface(app, surface);
  CLI::App* loadCommand = addLoadCommand(app, load);

  // CLI11 would call an unknown command a missing one; name it instead.
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    const std::function<bool(const CLI::App*)> all;  // empty: every subcommand
    for (const CLI::App* c : std::as_const(app).get_subcommands(all))
      known = known || c->get_name() == argv[1];
    if (!known) {
      return usage(std::string("unknown command '") + argv[1] +
                   "' (expected generate, check, replay, record, surface or load)");
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    const auto selected = app.get_subcommands();
    return usage(e.what(), selected.empty() ? "" : selected.front()->get_name());
  }
  if (generateCommand->parsed()) return runGenerate(generate);
  if (checkCommand->parsed()) return runCheck(checked);
  if (replayCommand->parsed()) return runReplayCommand(replayArgs);
  if (recordCommand->parsed()) return runRecordCommand(record);
  if (surfaceCommand->parsed()) return runSurface(surface);
  if (loadCommand->parsed()) return runLoadCommand(load);
  return usage("no command");
}
