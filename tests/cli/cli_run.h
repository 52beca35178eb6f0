// Runs the real `tessera` binary as a user would, capturing its exit code,
// stdout and stderr (shared by the CLI suites and the remote CLI tests).
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_meshes.h"

namespace tessera {

struct CliRun {
  int exitCode = -1;
  bool signalled = false;
  std::string out, err;
};

inline std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline CliRun runCli(const std::string& args) {
  static const std::string dir = testing::makeTempDir("tessera-cli");
  const std::string out = dir + "/stdout", err = dir + "/stderr";
  const std::string command = std::string(TESSERA_CLI_PATH) + " " + args + " >" + out + " 2>" + err;
  int status = std::system(command.c_str());
  CliRun run;
  run.signalled = WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) > 128);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = readAll(out);
  run.err = readAll(err);
  return run;
}

}  // namespace tessera
