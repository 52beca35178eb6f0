#!/usr/bin/env bash
# Whole-process speed of `tessera refine` against the small OpenSubdiv tool
# (bench/osd_refine_tool.cc) doing the same file in to file out, per output
# format: median wall time and peak RSS of RUNS runs each, interleaved so that
# both see the same machine load (docs/PERFORMANCE.md "File in to file out").
#   bench/refine_vs_osd.sh BUILD_DIR [MESH.off] [LEVEL] [RUNS]
set -euo pipefail
build=${1:?usage: refine_vs_osd.sh BUILD_DIR [MESH.off] [LEVEL] [RUNS]}
level=${3:-3}
runs=${4:-5}
tessera=$build/client/cli/tessera
osd=$build/bench/tessera_bench_osd_refine
[[ -x $tessera && -x $osd ]] || { echo "build tessera and tessera_bench_osd_refine in $build first" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# The default mesh: camel.off (9,770 vertices, 19,536 triangles) from
# Debian's libcgal-demo data, extracted here.
if [[ -z ${2:-} ]]; then
  tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$out" --strip-components=2 data/meshes/camel.off
fi
mesh=${2:-$out/camel.off}
[[ -f $mesh ]] || { echo "$mesh: not found" >&2; exit 2; }

# "seconds kilobytes" of one run.
measure() { /usr/bin/time -f "%e %M" "$@" 2>&1 >/dev/null | tail -1; }
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

printf '%-5s %10s %10s %7s %10s %10s %7s\n' format tessera_s osd_s ratio tessera_MB osd_MB ratio
for ext in obj ply off stl glb; do
  : >"$out/t" && : >"$out/o"
  for ((i = 0; i < runs; i++)); do
    measure "$tessera" refine "$mesh" --level "$level" -o "$out/t.$ext" >>"$out/t"
    measure "$osd" "$mesh" "$level" "$out/o.$ext" >>"$out/o"
  done
  ts=$(cut -d' ' -f1 "$out/t" | median) tk=$(cut -d' ' -f2 "$out/t" | median)
  os=$(cut -d' ' -f1 "$out/o" | median) ok=$(cut -d' ' -f2 "$out/o" | median)
  awk -v e="$ext" -v ts="$ts" -v os="$os" -v tk="$tk" -v ok="$ok" 'BEGIN {
    printf "%-5s %10.2f %10.2f %7.2f %10.0f %10.0f %7.2f\n", e, ts, os, ts / os, tk / 1024, ok / 1024, tk / ok }'
done
