#include "client/replay/replay_cli.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace tessera::replay {

CLI::Validator within(double lo, double hi, bool openBelow) {
  char interval[96];
  std::snprintf(interval, sizeof interval, "%s%g, %g]", openBelow ? "(" : "[", lo, hi);
  const std::string text = interval;
  return CLI::Validator(
      [=](std::string& input) -> std::string {
        double v = 0;
        try {
          size_t used = 0;
          v = std::stod(input, &used);
          if (used != input.size()) return "'" + input + "' is not a number";
        } catch (const std::exception&) {
          return "'" + input + "' is not a number";
        }
        if (!(openBelow ? v > lo : v >= lo) || !(v <= hi)) return input + " is not in " + text;
        return std::string();
      },
      text);
}

void addConnectionOptions(CLI::App& app, ConnectionArgs& args) {
  app.add_option("--host", args.host, "server address")->capture_default_str();
  app.add_option("--port", args.port, "server port")->check(CLI::Range(1u, 65535u))->capture_default_str();
  auto* token = app.add_option("--token", args.token, "access token");
  app.add_option("--token-file", args.tokenFile, "read the token from the first line of FILE")
      ->excludes(token);
}

void addProfileOption(CLI::App& app, std::string& text) {
  app.add_option("--profile", text, "LOD profile BASE,MAX,ANGLE (default: the script's, or 2,5,10)");
}

Expected<client::SessionOptions> sessionOptions(const ConnectionArgs& args) {
  client::SessionOptions o;
  o.name = "tessera-replay";
  o.timeoutSeconds = 30;
  o.host = args.host;
  o.port = static_cast<uint16_t>(args.port);
  o.token = args.token;
  if (!args.tokenFile.empty()) {
    std::ifstream in(args.tokenFile);
    if (!in) return invalidArgument("--token-file " + args.tokenFile + ": cannot read the file");
    std::getline(in, o.token);
    if (o.token.empty()) return invalidArgument("--token-file " + args.tokenFile + ": no token in the file");
  }
  if (o.token.empty()) return invalidArgument("a token is needed: --token T or --token-file F");
  return o;
}

Expected<ScriptHeader> withProfile(const std::string& text, ScriptHeader h) {
  if (text.empty()) return h;
  unsigned base = 0, max = 0;
  double angle = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%u,%u,%lf%c", &base, &max, &angle, &extra) != 3) {
    return invalidArgument("--profile expects BASE,MAX,ANGLE, got '" + text + "'");
  }
  h.baseLevel = base;
  h.maxLevel = max;
  h.angleDegrees = angle;
  return h;
}

int fail(const Status& s) {
  std::fprintf(stderr, "tessera-replay: %s\n", s.message().c_str());
  return kExitFailure;
}

int usage(const std::string& message, const std::string& command) {
  const std::string help =
      command.empty() ? "tessera-replay --help" : "tessera-replay " + command + " --help";
  std::fprintf(stderr, "tessera-replay: %s\n(%s lists the options)\n", message.c_str(), help.c_str());
  return kExitUsage;
}

}  // namespace tessera::replay
