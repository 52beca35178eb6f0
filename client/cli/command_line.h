// What every `tessera` subcommand shares on the command line (CLI11): how a
// chosen subcommand is run after parsing, the exit codes, the validators
// whose messages name the option, and the checks on input and output files.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "core/util/status.h"

namespace tessera::cli {

inline constexpr int kExitFailure = 1;  // the command ran and failed
inline constexpr int kExitUsage = 2;    // the command line is wrong

// A subcommand's work, chosen while parsing and run after the whole command
// line parsed (so a usage error never leaves half a command done).
using Action = std::function<int()>;

// Sets `action` to `run` when `app` is the subcommand chosen.
void onChosen(CLI::App& app, Action& action, Action run);

// A whole number 0..1000 ("--level: expects a whole number from 0 to 1000, got 'two'").
CLI::Validator wholeNumber();

// An angle in degrees, 0 to 180 ("--crease-angle: expects degrees from 0 to 180, got '200'").
CLI::Validator degrees();

// Accepts exactly these words: "expects uniform or chaikin, got 'x'".
CLI::Validator oneOf(const std::vector<std::string>& words);

// "tessera <command>: <message>" on stderr; returns kExitFailure.
int fail(const std::string& command, const Status& status);
int fail(const std::string& command, const std::string& message);
// "tessera <command>: <message>" and where help is, on stderr; kExitUsage.
int usage(const std::string& command, const std::string& message);

// Refuses an output that is the input itself (the same file by any path, or
// the same path when the output does not exist yet): writing it would
// destroy the input before or while it is read.
Status checkOutputIsNotInput(const std::string& input, const std::string& output);

}  // namespace tessera::cli
