#!/usr/bin/env bash
# Runs the whole test suite: installs missing Debian packages, configures,
# builds and runs ctest (which prints its summary), then the libFuzzer
# targets briefly over their seed corpora (the "fuzz" preset, clang-14,
# about a minute; docs/FUZZING.md). Exits non-zero if either fails or
# leaves files in its temporary directory.
# Usage: bash deploy/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."

bash deploy/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"
# Runs ctest with a temporary directory of its own ($TMPDIR), which must be
# empty afterwards: a test removes what it made, and keeps it only when it
# fails (tests/support/test_meshes.h makeTempDir). What is left is listed
# and kept, and the run fails. /tmp itself is compared before and after too,
# for anything that ignored $TMPDIR (the X servers' socket directories,
# /tmp/.X11-unix and the like, are the system's and not counted).
tmp_entries() {
  find /tmp -mindepth 1 -maxdepth 1 -printf '%f\n' 2>/dev/null | grep -Ev '^\.[A-Za-z0-9]+-unix$' | sort
}
run_suite() {
  local tmp status=0 before left
  tmp=$(mktemp -d "${TMPDIR:-/tmp}/tessera-suite-XXXXXX")
  before=$(tmp_entries)
  TMPDIR=$tmp ctest --preset "$1" || status=$?
  if ! rmdir "$tmp" 2>/dev/null; then
    echo "the $1 suite left files in its temporary directory $tmp:" >&2
    find "$tmp" -mindepth 1 -maxdepth 2 >&2
    [[ $status -ne 0 ]] || status=1
  fi
  left=$(comm -13 <(echo "$before") <(tmp_entries))
  if [[ -n $left ]]; then
    echo "the $1 suite left these in /tmp, outside its temporary directory:" >&2
    echo "$left" | sed 's|^|  /tmp/|' >&2
    [[ $status -ne 0 ]] || status=1
  fi
  return "$status"
}

# The fuzz run follows even when the main suite fails, so one run reports both.
main=0
run_suite release || main=$?

cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --target tessera_fuzzers -j "$(nproc)"
fuzz=0
run_suite fuzz || fuzz=$?
if [[ $main -ne 0 ]]; then
  echo "the main suite failed (its ctest summary is above the fuzz run's)" >&2
  exit "$main"
fi
exit "$fuzz"
