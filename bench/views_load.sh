#!/usr/bin/env bash
# One hundred view-dependent viewers on distinct orbits around CGAL's
# armadillo (held to level 4) with ten editors at 2 edits a second each
# (docs/PERFORMANCE.md "Views"), against the same load with the viewers on
# one whole-document profile. Fresh release server per row; prints the
# load tester's summary; reports go to /tmp/views-load-{views,profile}.json.
#   bash bench/views_load.sh
# MODES=views (or profile) runs one row; SERVER_BIN=path runs another
# build's server (to alternate two builds); PERF=path records the server
# with perf into path.views / path.profile.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
B=$ROOT/build/release
VIEWERS=${VIEWERS:-100}
SECONDS_PER_ROW=${SECONDS_PER_ROW:-20}
M=$(mktemp -d /tmp/views-mesh-XXXX)
# An interrupted run removes its server and directories too.
D= S=
trap '[ -n "$S" ] && kill -TERM $S 2>/dev/null; rm -rf "$M" ${D:+"$D"}' EXIT
tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C $M data/meshes/armadillo.off
# The armadillo's bounding sphere (bounding box centre, half its diagonal).
read -r CX CY CZ R < <(awk 'NR==2 {n=$1} NR>2 && NR<=2+n {
  for (i = 1; i <= 3; i++) { if (NR==3 || $i<lo[i]) lo[i]=$i; if (NR==3 || $i>hi[i]) hi[i]=$i } }
  END { print (lo[1]+hi[1])/2, (lo[2]+hi[2])/2, (lo[3]+hi[3])/2,
        sqrt((hi[1]-lo[1])^2+(hi[2]-lo[2])^2+(hi[3]-lo[3])^2)/2 }' $M/data/meshes/armadillo.off)
for MODE in ${MODES:-views profile}; do
  D=$(mktemp -d /tmp/views-load-XXXX)
  echo admin-token-for-views-0123456789 > $D/admin.tok
  ${SERVER_BIN:-$B/server/tessera-server} --data $D/data --port 0 --port-file $D/port --admin-token-file $D/admin.tok \
    --max-level 4 ${SERVER_OPTIONS:-} 2>$D/server.log &
  S=$!
  for _ in $(seq 100); do [ -s $D/port ] && break; sleep 0.05; done
  P=$(cat $D/port)
  $B/client/cli/tessera remote --port $P --token admin-token-for-views-0123456789 create \
    $M/data/meshes/armadillo.off --max-level 4 >/dev/null
  $B/client/cli/tessera remote --port $P --token admin-token-for-views-0123456789 grant 1 editor \
    replay-editor-token-0123456789 >/dev/null
  if [ $MODE = views ]; then
    WHAT="--cameras orbit --camera-target $CX $CY $CZ $R --camera-size 390x844 --camera-tolerance 1 --camera-rate 5"
  else
    WHAT="--profile 1,1,10"  # level 1 everywhere: the finest a whole-model phone view shows
  fi
  [ -n "${PERF:-}" ] && { perf record -F 149 --call-graph dwarf,16384 -p $S -o "$PERF.$MODE" >/dev/null 2>&1 & PP=$!; }
  timeout 600 $B/client/replay/tessera-replay load --port $P --token replay-editor-token-0123456789 --document 1 \
    --editors 10 --viewers $VIEWERS --rate 2 --seconds $SECONDS_PER_ROW --vertex-level 0 --vertex-count 2000 \
    --step 0.2 $WHAT --server-pid $S --report /tmp/views-load-$MODE.json --quiet 2>&1 | head -20
  [ -n "${PERF:-}" ] && { kill -INT $PP; wait $PP; }
  echo "  (server RSS at the end: $(( $(awk '/VmRSS/ {print $2}' /proc/$S/status) / 1024 )) MiB)"
  kill -TERM $S; wait $S 2>/dev/null
  rm -rf $D
  D= S=
done
