#!/usr/bin/env bash
# Runs the whole test suite: installs missing Debian packages, configures,
# builds and runs ctest (which prints its summary). Usage: bash deploy/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."

bash deploy/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"
ctest --preset release
