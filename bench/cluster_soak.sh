#!/usr/bin/env bash
# A fault-injection soak of the cluster mode, in Jepsen's manner
# (docs/CLUSTER.md "Fault-injection soak"). CI runs the bounded form
# (EVERY_KIND=2, tests/CMakeLists.txt: cluster_soak_every_fault_twice).
#
#   bash bench/cluster_soak.sh                          # 200 faults over 1800 s
#   FAULTS=12 DURATION=120 bash bench/cluster_soak.sh   # a short try
#   SEED=7 bash bench/cluster_soak.sh                   # the same schedule again
#   EVERY_KIND=1 DURATION=80 bash bench/cluster_soak.sh # each kind of fault once
#   EVERY_KIND=2 DURATION=120 bash bench/cluster_soak.sh # each kind twice (CI)
#
# Environment: FAULTS (200), DURATION (seconds, 1800), SEED (default: from
# the clock, printed), BASE_PORT (25100: it uses BASE_PORT+1 .. +39 on
# 127.0.0.1), LEASE_MS (2000), EDIT_RATE (commands per second per editor, 4),
# TESSERA_BIN (the directory holding tessera-server, tessera, tessera-replay;
# default: copies of TESSERA_BUILD_DIR's, itself build/release by default),
# EVERY_KIND=N (each kind of fault N times, in an order drawn from SEED;
# FAULTS is then N times the number of kinds; a run whose schedule was cut
# short fails), SOAK_DIR (the run directory; default a new one
# under $TMPDIR or /tmp), KINDS (a comma-separated subset of the fault kinds, e.g.
# KINDS=kill-all-nats,partition-node), KEEP=1 (keep the run directory even when the check passes).
#
# Exit status: 0 the checker found nothing, 1 it found something (the run
# directory is kept and named), 2 the run could not be set up.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
faults="${FAULTS:-200}"
duration="${DURATION:-1800}"
seed="${SEED:-$(( $(date +%s) % 1000000 ))}"
base="${BASE_PORT:-25100}"
bin="${TESSERA_BIN:-}"
if [ -z "$bin" ]; then
  bin="$(mktemp -d "${TMPDIR:-/tmp}/tessera-soak-bin-XXXXXX")"
  # A copy, so that a rebuild during the run cannot relink them under it.
  build="${TESSERA_BUILD_DIR:-$repo/build/release}"
  cp "$build/server/tessera-server" "$build/client/cli/tessera" "$build/client/replay/tessera-replay" "$bin/"
  own_bin=1
fi
dir="${SOAK_DIR:-$(mktemp -d "${TMPDIR:-/tmp}/tessera-soak-XXXXXX")}"
echo "cluster soak: seed $seed, ${EVERY_KIND:+each kind of fault $EVERY_KIND times, not }$faults faults, over $duration s, run directory $dir"

status=0
node "$repo/bench/cluster_soak/driver.mjs" --dir "$dir" --bin "$bin" --repo "$repo" --faults "$faults" \
  --duration "$duration" --seed "$seed" --base-port "$base" --lease-ms "${LEASE_MS:-2000}" \
  --edit-rate "${EDIT_RATE:-4}" ${KINDS:+--kinds "$KINDS"} ${EVERY_KIND:+--every-kind "$EVERY_KIND"} || status=$?
if [ "$status" -ne 0 ]; then
  echo "the driver failed (exit $status); its files are in $dir" >&2
  [ -n "${own_bin:-}" ] && rm -rf "$bin"
  exit 2
fi
# The journal replayed offline by a single-node server (offline.json); a
# failure there is a finding of the checker's.
python3 "$repo/bench/cluster_soak/offline_replay.py" "$dir" "$bin" "$repo" || true
node "$repo/bench/cluster_soak/check.mjs" "$dir" || status=$?
[ -n "${own_bin:-}" ] && rm -rf "$bin"
if [ "$status" -ne 0 ]; then
  echo "the checker found something: the run's files are kept in $dir (seed $seed)" >&2
  exit 1
fi
if [ -n "${KEEP:-}" ]; then echo "kept: $dir"; else rm -rf "$dir"; fi
