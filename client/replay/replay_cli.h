// What tessera-replay's subcommands share on the command line (CLI11):
// the connection options, the profile option, and the exit conventions of
// docs/REPLAY.md (1 a failure, 2 a usage error).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "client/lib/session.h"
#include "client/replay/script.h"
#include "core/util/status.h"

namespace tessera::replay {

inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

struct ConnectionArgs {
  std::string host = "127.0.0.1";
  unsigned port = 7878;
  std::string token;
  std::string tokenFile;
};

// A number in [lo, hi], or (lo, hi] with `openBelow`; the error names the
// interval as it is written in the help ("(0, 200]").
CLI::Validator within(double lo, double hi, bool openBelow = false);

// --host, --port, --token, --token-file on `app`.
void addConnectionOptions(CLI::App& app, ConnectionArgs& args);
// --profile BASE,MAX,ANGLE on `app`, into `text`.
void addProfileOption(CLI::App& app, std::string& text);

// The session options of `args`; a missing token or an unreadable token
// file is an error naming the option (a usage error).
Expected<client::SessionOptions> sessionOptions(const ConnectionArgs& args);
// `header` with the profile of --profile, if given ("" keeps it).
Expected<ScriptHeader> withProfile(const std::string& text, ScriptHeader header);

// "tessera-replay: MESSAGE" on stderr; the exit code.
int fail(const Status& status);
// A usage error of `command` ("" for none): the message and where help is.
int usage(const std::string& message, const std::string& command = "");

}  // namespace tessera::replay
