#!/usr/bin/env bash
# Runs every libFuzzer target long, one after another (one core: the
# machine's other core stays free), and prints per target the executions
# reached, exec/s, seconds, corpus size, coverage and the outcome.
#
#   bash tests/fuzz/run_long.sh                    # every target
#   RUNS=10000000 SECONDS_PER_TARGET=600 bash tests/fuzz/run_long.sh frame_decoder tag_file
#   FORK=2 bash tests/fuzz/run_long.sh ...         # libFuzzer -fork=2 (two cores)
#   FUZZ_ARGS=-entropic=0 bash tests/fuzz/run_long.sh document_host   # more libFuzzer flags
#
# A target stops at RUNS executions or SECONDS_PER_TARGET seconds, whichever
# comes first (with FORK, only the time bound holds: -runs is per worker).
# Corpora grow in build/fuzz/long/<target> (seeded from corpus/<target>,
# which is not written to); crashes go to build/fuzz/long/artifacts/. The
# fuzz preset must be built first (BIN and OUT move the binaries and the
# output elsewhere, e.g. to keep a long run going across a rebuild):
#   cmake --preset fuzz && cmake --build --preset fuzz -j2
set -uo pipefail
cd "$(dirname "$0")/../.."

RUNS=${RUNS:-10000000}
SECONDS_PER_TARGET=${SECONDS_PER_TARGET:-600}
FORK=${FORK:-0}
# Per-input limit in seconds; raise it when the machine is shared, where a
# starved process can exceed 30 s of wall time on a 10 ms input.
TIMEOUT=${TIMEOUT:-30}
BIN=${BIN:-build/fuzz/tests/fuzz}
OUT=${OUT:-build/fuzz/long}
ALL="frame_decoder document_host region_decoder region_meshopt document_file journal_entry tag_file edit_script
     import_obj import_off import_ply import_stl import_gltf import_glb"
TARGETS=${*:-$ALL}

mkdir -p "$OUT/artifacts"
SUMMARY=$OUT/summary.tsv
[[ -f $SUMMARY ]] || printf 'target\texecs\texec_per_s\tseconds\tcorpus_files\tcov\tft\tpeak_rss_mb\tresult\n' >"$SUMMARY"

status=0
for t in $TARGETS; do
  exe=$BIN/fuzz_$t
  [[ -x $exe ]] || { echo "missing $exe: build the fuzz preset first" >&2; exit 2; }
  mkdir -p "$OUT/$t"
  log=$OUT/$t.log
  args=(-rss_limit_mb=2048 -timeout="$TIMEOUT" -print_final_stats=1 -max_total_time="$SECONDS_PER_TARGET"
        -artifact_prefix="$OUT/artifacts/$t-")
  # Extra libFuzzer flags, e.g. -entropic=0: the entropic power schedule's
  # bookkeeping is 40 % or more of the time of targets with many features
  # (document_host, edit_script; docs/FUZZING.md).
  # shellcheck disable=SC2206
  [[ -n ${FUZZ_ARGS:-} ]] && args+=($FUZZ_ARGS)
  if [[ $FORK -gt 0 ]]; then
    args+=(-fork="$FORK" -ignore_crashes=0)
  else
    args+=(-runs="$RUNS")
  fi
  start=$(date +%s)
  stamp=$(mktemp)
  "$exe" "${args[@]}" "$OUT/$t" "tests/fuzz/corpus/$t" >"$log" 2>&1
  rc=$?
  secs=$(( $(date +%s) - start ))
  # Single process: final stats; fork mode: the last status line's exec count
  # (the fork-mode parent prints final stats too, but of its own 0 executions).
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  [[ -n $execs && $execs != 0 ]] || execs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
  rate=$(( secs > 0 ? ${execs:-0} / secs : 0 ))
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$log" | tail -1)
  files=$(find "$OUT/$t" -type f | wc -l)
  # Inputs libFuzzer saved this run without failing it (slow-unit-*, with
  # -report_slow_units) are findings too: a slow input is a denial of service.
  saved=$(find "$OUT/artifacts" -name "$t-*" -newer "$stamp" | wc -l)
  rm -f "$stamp"
  if [[ $rc -eq 0 ]] && ! grep -q 'ERROR: \(AddressSanitizer\|UndefinedBehaviorSanitizer\|libFuzzer\)\|runtime error:' "$log"; then
    result=ok
    [[ $saved -eq 0 ]] || result="ok, but $saved input(s) saved in $OUT/artifacts (slow units?)"
  else
    result="FAILED (exit $rc, see $log)"
    status=1
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$t" "${execs:-0}" "$rate" "$secs" "$files" "${cov:-?}" "${ft:-?}" \
    "${rss:-?}" "$result" | tee -a "$SUMMARY"
done
echo "summary: $SUMMARY"
exit $status
