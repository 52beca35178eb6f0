#!/usr/bin/env bash
# Runs the whole test suite: installs missing Debian packages, configures,
# builds and runs ctest (which prints its summary), then the libFuzzer
# targets briefly over their seed corpora (the "fuzz" preset, clang-14,
# about a minute; docs/FUZZING.md). Exits non-zero if either fails.
# Usage: bash deploy/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."

bash deploy/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"
# The fuzz run follows even when the main suite fails, so one run reports both.
main=0
ctest --preset release || main=$?

cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --target tessera_fuzzers -j "$(nproc)"
fuzz=0
ctest --preset fuzz || fuzz=$?
if [[ $main -ne 0 ]]; then
  echo "the main suite failed (its ctest summary is above the fuzz run's)" >&2
  exit "$main"
fi
exit "$fuzz"
