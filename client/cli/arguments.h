// A small command-line parser for the `tessera` subcommands: positional
// arguments, --flags and --options with values. Unknown options and missing
// values are errors naming the option.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/util/status.h"

namespace tessera::cli {

struct ArgumentSpec {
  std::set<std::string> flags;    // e.g. "--limit"
  std::set<std::string> options;  // take a value, e.g. "--level"
};

struct Arguments {
  std::vector<std::string> positional;
  std::set<std::string> flags;
  std::map<std::string, std::string> options;

  bool has(const std::string& flag) const { return flags.count(flag) > 0; }
  const std::string* option(const std::string& name) const {
    auto it = options.find(name);
    return it == options.end() ? nullptr : &it->second;
  }
};

// `-o` is accepted as a short alias of `--output`; `--help`/`-h` is always a flag.
Expected<Arguments> parseArguments(const std::vector<std::string>& args, const ArgumentSpec& spec);

// Parses a whole non-negative integer, naming the option on failure.
Expected<int> parseLevel(const std::string& option, const std::string& text);

}  // namespace tessera::cli
