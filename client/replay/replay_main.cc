// tessera-replay: scripted sessions and load runs against tessera-server
// (issue 6 §3; the script and report formats are in docs/REPLAY.md).
#include <charconv>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "client/replay/load.h"
#include "client/replay/record.h"
#include "client/replay/replay.h"
#include "client/replay/script.h"

namespace {

using namespace tessera;
using namespace tessera::replay;

constexpr const char* kHelp =
    "usage: tessera-replay <command> [options]\n"
    "\n"
    "  generate -o SCRIPT [--document D] [--editors E] [--rate R] [--seconds S] [--seed N]\n"
    "           [--vertex-level L] [--vertex-count N] [--step X] [--no-undo]\n"
    "      write a synthetic script: E editors, R offset edits per second each\n"
    "  check SCRIPT            parse a script; errors are FILE:LINE: reason\n"
    "  replay SCRIPT [--document D] [--speed X]\n"
    "      replay it, one connection per actor, in script order (speed 0: no waiting);\n"
    "      then print the final version and surface hash a fresh subscriber sees\n"
    "  record --document D -o SCRIPT [--seconds S | --until-version V]\n"
    "      record the document's commands live, as a script (any role that may open it);\n"
    "      stops after S seconds, or once version V is recorded (then at most S, default 600)\n"
    "  surface --document D    print the version and surface hash of a document\n"
    "  load --document D [--editors E] [--viewers M] [--rate R] [--seconds S] [--max-edits N]\n"
    "       [--decode-viewers K] [--vertex-level L] [--vertex-count N] [--step X] [--seed N]\n"
    "       [--drain-seconds S] [--pool-threads T] [--display-only] [--server-pid PID] [--report FILE] [--quiet]\n"
    "      a bounded load run; progress on stderr, a summary on stdout, JSON with --report\n"
    "\n"
    "connection: [--host H] [--port N] [--token T | --token-file F] [--viewer-token T]\n"
    "profile (surface, replay, record, load): [--profile BASE,MAX,ANGLE] (default: the script's, or 2,5,10)\n";

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::string> options;
  std::set<std::string> flags;
  const std::string* get(const std::string& k) const {
    auto it = options.find(k);
    return it == options.end() ? nullptr : &it->second;
  }
};

const std::set<std::string> kFlags = {"--no-undo", "--quiet", "--help", "--display-only"};
const std::set<std::string> kOptions = {"--host", "--port", "--token", "--token-file", "--viewer-token", "--document",
                                        "--editors", "--viewers", "--rate", "--seconds", "--seed", "--vertex-level",
                                        "--vertex-count", "--step", "--speed", "--max-edits", "--decode-viewers",
                                        "--drain-seconds", "--pool-threads", "--server-pid", "--report", "--output", "--profile",
                                        "--until-version"};

Expected<Args> parseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    std::string s = argv[i];
    if (s == "-o") s = "--output";
    if (s == "-h") s = "--help";
    if (kFlags.count(s)) {
      a.flags.insert(s);
    } else if (kOptions.count(s)) {
      if (i + 1 >= argc) return invalidArgument(s + " needs a value");
      a.options[s] = argv[++i];
    } else if (s.rfind("--", 0) == 0) {
      return invalidArgument("unknown option " + s);
    } else {
      a.positional.push_back(s);
    }
  }
  return a;
}

template <typename T>
Expected<T> number(const Args& a, const std::string& key, T fallback) {
  const std::string* text = a.get(key);
  if (!text) return fallback;
  T value{};
  auto [end, ec] = std::from_chars(text->data(), text->data() + text->size(), value);
  if (ec != std::errc() || end != text->data() + text->size()) return invalidArgument(key + ": bad number '" + *text + "'");
  return value;
}

int fail(const Status& s) {
  std::fprintf(stderr, "tessera-replay: %s\n", s.message().c_str());
  return 1;
}

int usage(const std::string& message) {
  std::fprintf(stderr, "tessera-replay: %s\n\n%s", message.c_str(), kHelp);
  return 2;
}

Expected<client::SessionOptions> sessionOptions(const Args& a) {
  client::SessionOptions o;
  o.name = "tessera-replay";
  o.timeoutSeconds = 30;
  if (const std::string* h = a.get("--host")) o.host = *h;
  TESSERA_ASSIGN_OR_RETURN(unsigned port, number<unsigned>(a, "--port", 7878));
  if (port == 0 || port > 65535) return invalidArgument("--port must be 1..65535");
  o.port = static_cast<uint16_t>(port);
  if (const std::string* t = a.get("--token")) o.token = *t;
  if (const std::string* f = a.get("--token-file")) {
    std::ifstream in(*f);
    std::getline(in, o.token);
    if (o.token.empty()) return invalidArgument(*f + ": no token in the file");
  }
  if (o.token.empty()) return invalidArgument("a token is needed: --token T or --token-file F");
  return o;
}

Expected<ScriptHeader> profileOption(const Args& a, ScriptHeader h) {
  const std::string* p = a.get("--profile");
  if (!p) return h;
  unsigned base = 0, max = 0;
  double angle = 0;
  char extra = 0;
  if (std::sscanf(p->c_str(), "%u,%u,%lf%c", &base, &max, &angle, &extra) != 3) {
    return invalidArgument("--profile expects BASE,MAX,ANGLE, got '" + *p + "'");
  }
  h.baseLevel = base;
  h.maxLevel = max;
  h.angleDegrees = angle;
  return h;
}

int runGenerate(const Args& a) {
  const std::string* out = a.get("--output");
  if (!out) return usage("generate needs -o SCRIPT");
  GenerateOptions g;
  auto doc = number<uint64_t>(a, "--document", 1);
  auto editors = number<int>(a, "--editors", 2);
  auto rate = number<double>(a, "--rate", 10);
  auto seconds = number<double>(a, "--seconds", 5);
  auto seed = number<uint64_t>(a, "--seed", 1);
  auto level = number<int>(a, "--vertex-level", 0);
  auto count = number<uint64_t>(a, "--vertex-count", 8);
  auto step = number<double>(a, "--step", 0.01);
  for (const Status* s : {&doc.status(), &editors.status(), &rate.status(), &seconds.status(), &seed.status(),
                          &level.status(), &count.status(), &step.status()}) {
    if (!s->isOk()) return usage(s->message());
  }
  if (*editors < 1 || *editors > 1000 || !(*rate > 0 && *rate <= 200) || !(*seconds > 0 && *seconds <= 3600) ||
      *level < 0 || *level > 12 || *count == 0) {
    return usage("generate: --editors 1..1000, --rate (0,200], --seconds (0,3600], --vertex-level 0..12, --vertex-count > 0");
  }
  g.document = *doc;
  g.editors = *editors;
  g.rate = *rate;
  g.seconds = *seconds;
  g.seed = *seed;
  g.vertexLevel = *level;
  g.vertexCount = *count;
  g.step = *step;
  g.undo = !a.flags.count("--no-undo");
  Script script = generateScript(g);
  auto header = profileOption(a, script.header);
  if (!header.isOk()) return usage(header.status().message());
  std::ofstream f(*out, std::ios::binary);
  f << headerLine(*header) << "\n";
  for (const ScriptCommand& c : script.commands) f << commandLine(c) << "\n";
  if (!f.flush()) return fail(ioError(*out + ": cannot write"));
  std::printf("wrote %s: %zu commands by %d editors\n", out->c_str(), script.commands.size(), g.editors);
  return 0;
}

void printSurface(const SurfaceState& s) {
  std::printf("version %llu\nsurface_hash %016llx\ntriangles %lld\n", static_cast<unsigned long long>(s.version),
              static_cast<unsigned long long>(s.hash), static_cast<long long>(s.triangles));
}

int runReplayCommand(const Args& a) {
  if (a.positional.size() != 2) return usage("replay expects one SCRIPT");
  auto script = readScript(a.positional[1]);
  if (!script.isOk()) return fail(script.status());
  auto session = sessionOptions(a);
  if (!session.isOk()) return usage(session.status().message());
  auto doc = number<uint64_t>(a, "--document", script->header.document);
  auto speed = number<double>(a, "--speed", 1);
  if (!doc.isOk() || !speed.isOk() || *speed < 0) return usage("replay: bad --document or --speed");
  auto header = profileOption(a, script->header);
  if (!header.isOk()) return usage(header.status().message());
  // A subscriber with the final profile before the first command too: the
  // server then updates that profile's tessellation edit by edit, as it does
  // for a live session's viewers and recorder, rather than building it at the
  // end (the two can differ in a normal: docs/REPLAY.md §2).
  auto before = readSurface(*session, *doc, profileOf(*header));
  if (!before.isOk()) return fail(before.status());
  ReplayOptions options{.session = *session, .document = *doc, .speed = *speed};
  auto result = runReplay(*script, options);
  if (!result.isOk()) return fail(result.status());
  std::printf("commands %d\nacked %d\nrejected %d\n", result->commands, result->acked, result->rejected);
  auto surface = readSurface(*session, *doc, profileOf(*header));
  if (!surface.isOk()) return fail(surface.status());
  printSurface(*surface);
  return 0;
}

int runRecordCommand(const Args& a) {
  const std::string* out = a.get("--output");
  if (!out) return usage("record needs -o SCRIPT");
  auto session = sessionOptions(a);
  if (!session.isOk()) return usage(session.status().message());
  session->name = "tessera-replay-record";
  auto doc = number<uint64_t>(a, "--document", 0);
  auto seconds = number<double>(a, "--seconds", 0);
  auto until = number<uint64_t>(a, "--until-version", 0);
  if (!doc.isOk() || *doc == 0) return usage("record needs --document D");
  if (!seconds.isOk() || !until.isOk()) return usage("record: bad --seconds or --until-version");
  if (!(*seconds >= 0 && *seconds <= 86400)) return usage("record: --seconds must be between 0 and 86400");
  if (*seconds == 0 && *until == 0) return usage("record needs --seconds S or --until-version V");
  auto header = profileOption(a, ScriptHeader{});
  if (!header.isOk()) return usage(header.status().message());
  std::ofstream f(*out, std::ios::binary);
  if (!f) return fail(ioError(*out + ": cannot write"));
  RecordOptions o;
  o.session = *session;
  o.document = *doc;
  o.header = *header;
  o.seconds = *seconds == 0 ? 600 : *seconds;
  o.untilVersion = *until;
  o.out = &f;
  o.started = [&](uint64_t from) {
    std::printf("recording document %llu from version %llu\n", static_cast<unsigned long long>(*doc),
                static_cast<unsigned long long>(from));
    std::fflush(stdout);
    if (from != 1) {
      std::fprintf(stderr, "tessera-replay: the recording starts at version %llu: replay it on a copy of the document "
                   "at that version, not on a fresh one\n", static_cast<unsigned long long>(from));
    }
  };
  auto result = runRecord(o);
  if (!result.isOk()) return fail(result.status().withContext("record"));
  if (!f.flush()) return fail(ioError(*out + ": cannot write"));
  std::printf("commands %lld\nactors %zu\nfrom_version %llu\n", static_cast<long long>(result->commands),
              result->actors, static_cast<unsigned long long>(result->fromVersion));
  if (result->surface) {
    printSurface(*result->surface);
  } else {
    std::printf("version %llu\n", static_cast<unsigned long long>(result->lastVersion));
    std::fprintf(stderr, "tessera-replay: record: no surface hash: the recorder's view was not at the last version\n");
  }
  std::printf("wrote %s\n", out->c_str());
  if (!result->stopped.isOk()) return fail(result->stopped.withContext("record"));
  return 0;
}

int runSurface(const Args& a) {
  auto session = sessionOptions(a);
  if (!session.isOk()) return usage(session.status().message());
  auto doc = number<uint64_t>(a, "--document", 0);
  if (!doc.isOk() || *doc == 0) return usage("surface needs --document D");
  auto header = profileOption(a, ScriptHeader{});
  if (!header.isOk()) return usage(header.status().message());
  auto surface = readSurface(*session, *doc, profileOf(*header));
  if (!surface.isOk()) return fail(surface.status());
  printSurface(*surface);
  return 0;
}

int runLoadCommand(const Args& a) {
  auto session = sessionOptions(a);
  if (!session.isOk()) return usage(session.status().message());
  LoadOptions o;
  o.session = *session;
  if (const std::string* t = a.get("--viewer-token")) o.viewerToken = *t;
  auto doc = number<uint64_t>(a, "--document", 0);
  auto editors = number<int>(a, "--editors", 1);
  auto viewers = number<int>(a, "--viewers", 10);
  auto rate = number<double>(a, "--rate", 10);
  auto seconds = number<double>(a, "--seconds", 5);
  auto maxEdits = number<int64_t>(a, "--max-edits", 100000);
  auto decode = number<int>(a, "--decode-viewers", -1);
  auto level = number<int>(a, "--vertex-level", 0);
  auto count = number<uint64_t>(a, "--vertex-count", 8);
  auto step = number<double>(a, "--step", 0.01);
  auto seed = number<uint64_t>(a, "--seed", 1);
  auto drain = number<double>(a, "--drain-seconds", 10);
  auto pid = number<int>(a, "--server-pid", 0);
  auto poolThreads = number<int>(a, "--pool-threads", 2);
  for (const Status* s : {&doc.status(), &editors.status(), &viewers.status(), &rate.status(), &seconds.status(),
                          &maxEdits.status(), &decode.status(), &level.status(), &count.status(), &step.status(),
                          &seed.status(), &drain.status(), &pid.status(), &poolThreads.status()}) {
    if (!s->isOk()) return usage(s->message());
  }
  if (*level < 0 || *level > 12 || *count == 0 || *maxEdits < 1 || !(*drain >= 0 && *drain <= 600) || *poolThreads < 0 ||
      *poolThreads > 16) {
    return usage("load: --vertex-level 0..12, --vertex-count > 0, --max-edits >= 1, --drain-seconds 0..600, "
                 "--pool-threads 0..16");
  }
  auto header = profileOption(a, ScriptHeader{});
  if (!header.isOk()) return usage(header.status().message());
  o.document = *doc;
  o.editors = *editors;
  o.viewers = *viewers;
  o.rate = *rate;
  o.seconds = *seconds;
  o.maxEdits = *maxEdits;
  o.decodeViewers = *decode;
  o.vertexLevel = *level;
  o.vertexCount = *count;
  o.step = *step;
  o.seed = *seed;
  o.drainSeconds = *drain;
  o.serverPid = *pid;
  o.poolThreads = *poolThreads;
  o.profile = profileOf(*header);
  // Viewers that only watch: regions without vertex ids (docs/PROTOCOL.md).
  o.profile.set_omit_vertex_ids(a.flags.count("--display-only") > 0);
  o.progress = !a.flags.count("--quiet");
  auto report = runLoad(o);
  if (!report.isOk()) return fail(report.status());
  if (const std::string* path = a.get("--report")) {
    std::ofstream f(*path, std::ios::binary);
    f << report->dump(2) << "\n";
    if (!f.flush()) return fail(ioError(*path + ": cannot write"));
  }
  std::fputs(summarize(*report).c_str(), stdout);
  // A run whose connections failed, whose viewers saw gaps or did not catch
  // up by the end of the drain time is a failed run.
  const nlohmann::json& r = *report;
  const bool clean = r["errors"]["count"].get<int64_t>() == 0 && r["viewers"]["gaps"].get<int64_t>() == 0 &&
                     r["viewers"]["behind_at_end"].get<int64_t>() == 0;
  return clean ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  auto args = parseArgs(argc, argv);
  if (!args.isOk()) return usage(args.status().message());
  if (args->flags.count("--help")) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  if (args->positional.empty()) return usage("no command");
  const std::string& command = args->positional[0];
  if (command == "generate") return runGenerate(*args);
  if (command == "check") {
    if (args->positional.size() != 2) return usage("check expects one SCRIPT");
    auto script = readScript(args->positional[1]);
    if (!script.isOk()) return fail(script.status());
    std::printf("%s: %zu commands\n", args->positional[1].c_str(), script->commands.size());
    return 0;
  }
  if (command == "replay") return runReplayCommand(*args);
  if (command == "surface") return runSurface(*args);
  if (command == "record") return runRecordCommand(*args);
  if (command == "load") return runLoadCommand(*args);
  return usage("unknown command '" + command + "'");
}
