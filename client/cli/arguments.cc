#include "client/cli/arguments.h"

#include <cerrno>
#include <cstdlib>

namespace tessera::cli {

Expected<Arguments> parseArguments(const std::vector<std::string>& args, const ArgumentSpec& spec) {
  Arguments parsed;
  for (size_t i = 0; i < args.size(); ++i) {
    std::string arg = args[i];
    if (arg == "-o") arg = "--output";
    if (arg == "-h") arg = "--help";
    if (arg == "--help" || spec.flags.count(arg)) {
      parsed.flags.insert(arg);
    } else if (spec.options.count(arg)) {
      if (i + 1 >= args.size()) return invalidArgument(arg + " needs a value");
      if (parsed.options.count(arg)) return invalidArgument(arg + " given twice");
      parsed.options[arg] = args[++i];
    } else if (arg.size() > 1 && arg[0] == '-') {
      return invalidArgument("unknown option " + arg);
    } else {
      parsed.positional.push_back(arg);
    }
  }
  return parsed;
}

Expected<int> parseLevel(const std::string& option, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end == nullptr || *end != '\0' || errno != 0 || value < 0 || value > 1000) {
    return invalidArgument(option + " expects a whole number >= 0, got '" + text + "'");
  }
  return static_cast<int>(value);
}

}  // namespace tessera::cli
