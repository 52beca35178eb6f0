#include "client/cli/command_line.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>

namespace tessera::cli {

void onChosen(CLI::App& app, Action& action, Action run) {
  // Runs once parsing is complete; the work itself waits for main().
  app.callback([&action, run = std::move(run)] { action = run; });
}

CLI::Validator wholeNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty() || text.size() > 4 || text.find_first_not_of("0123456789") != std::string::npos ||
            std::stoi(text) > 1000) {
          return "expects a whole number from 0 to 1000, got '" + text + "'";
        }
        return "";
      },
      "");
}

CLI::Validator degrees() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0;
        const char* end = text.data() + text.size();
        auto [ptr, ec] = std::from_chars(text.data(), end, value);
        // from_chars reads "nan" and "inf" too: the range test refuses them.
        if (text.empty() || ec != std::errc() || ptr != end || !(value >= 0 && value <= 180)) {
          return "expects degrees from 0 to 180, got '" + text + "'";
        }
        return "";
      },
      "");
}

CLI::Validator oneOf(const std::vector<std::string>& words) {
  std::string list;
  for (size_t i = 0; i < words.size(); ++i) {
    list += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
  }
  return CLI::Validator(
      [words, list](std::string& text) -> std::string {
        if (std::find(words.begin(), words.end(), text) != words.end()) return "";
        return "expects " + list + ", got '" + text + "'";
      },
      "");
}

int fail(const std::string& command, const Status& status) {
  return fail(command, status.toString());
}

int fail(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "tessera %s: %s\n", command.c_str(), message.c_str());
  return kExitFailure;
}

int usage(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "tessera %s: %s\nRun 'tessera %s --help' for its options.\n", command.c_str(),
               message.c_str(), command.c_str());
  return kExitUsage;
}

Status checkOutputIsNotInput(const std::string& input, const std::string& output) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool same = fs::exists(output, ec)
                        ? fs::equivalent(input, output, ec)
                        : fs::weakly_canonical(input, ec) == fs::weakly_canonical(output, ec);
  if (same && !ec) {
    return invalidArgument("-o " + output + " is the input " + input +
                           "; writing it would destroy the input: choose another output file");
  }
  return Status::ok();
}

}  // namespace tessera::cli
