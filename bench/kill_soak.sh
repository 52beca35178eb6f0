#!/usr/bin/env bash
# The kill -9 soak (docs/STORE.md "Kill -9 soak"): the durability
# test (tests/integration/durability_test.cc) with many cycles and editors.
# Each cycle runs a storm of signed moves, creases and undos/redos against the
# real tessera-server on 127.0.0.1, kills it with SIGKILL at a random moment,
# restarts it, and checks that every acknowledged edit is there and that the
# surface equals a replay of the acknowledged history. Not run by CI.
#
#   bash bench/kill_soak.sh [CYCLES]          # default 100
#
# BUILD (default build/release) must hold the built targets tessera-server and
# tessera_integration_tests. EDITORS (default 4), MIX (moves,creases,undos in
# percent, the rest redos; default 60,20,12), STORM_MS (default 400),
# SNAPSHOT_EVERY (default 7) and SEED (default 1) become the test's
# TESSERA_SOAK_* variables. TIME_LIMIT (default 3600 s) bounds the run: the
# test starts no cycle after it (and then fails with the cycles it ran), and
# `timeout` kills the test and its server (one process group) 120 s later.
# Prints the test's "soak:" line (cycles, acknowledged and refused edits,
# losses) and exits with the test's status; its log is removed unless it failed.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${BUILD:-$ROOT/build/release}
CYCLES=${1:-100}
BIN=$BUILD/tests/tessera_integration_tests
if [ ! -x "$BIN" ]; then
  echo "no $BIN: build the targets tessera-server and tessera_integration_tests first" >&2
  exit 2
fi
LOG=$(mktemp /tmp/kill-soak-XXXX.log)
echo "kill -9 soak: $CYCLES cycles, ${EDITORS:-4} editors, mix ${MIX:-60,20,12}, storms up to ${STORM_MS:-400} ms," \
  "snapshot every ${SNAPSHOT_EVERY:-7}, seed ${SEED:-1}; binary $BIN; log $LOG"
START=$(date +%s)
TESSERA_SOAK_CYCLES=$CYCLES TESSERA_SOAK_EDITORS=${EDITORS:-4} TESSERA_SOAK_MIX=${MIX:-60,20,12} \
  TESSERA_SOAK_STORM_MS=${STORM_MS:-400} TESSERA_SOAK_SNAPSHOT_EVERY=${SNAPSHOT_EVERY:-7} TESSERA_SOAK_SEED=${SEED:-1} \
  TESSERA_SOAK_MAX_SECONDS=${TIME_LIMIT:-3600} timeout --signal=KILL $(( ${TIME_LIMIT:-3600} + 120 )) "$BIN" --gtest_filter=ServerDurability.AcknowledgedEditsSurviveKillNine \
  > "$LOG" 2>&1
STATUS=$?
grep '^soak:' "$LOG" || echo "soak: no summary (status $STATUS; killed by timeout?)"
grep -B2 -A6 'Failure' "$LOG" | head -40
echo "status $STATUS after $(( $(date +%s) - START )) s"
# The log is kept, and named, only when the soak failed.
if [ $STATUS -eq 0 ]; then rm -f "$LOG"; else echo "kept the log: $LOG"; fi
exit $STATUS
