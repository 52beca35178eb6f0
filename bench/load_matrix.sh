#!/usr/bin/env bash
# Runs tessera-replay load rows against fresh release servers (docs/REPLAY.md §5.1):
#   printf "100 10 10\n10 1 50\n" | bash bench/load_matrix.sh
# One row per line "VIEWERS EDITORS RATE [DECODING_VIEWERS]" (default min(VIEWERS, 20)).
# SECONDS_PER_ROW (default 5) sets the editing time; reports go to /tmp/load-report-V-E-R.json,
# and each row's server directory is removed.
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
B=$ROOT/build/release
# An interrupted row removes its server and directory too.
D= S=
trap '[ -n "$S" ] && kill -TERM $S 2>/dev/null; [ -n "$D" ] && rm -rf "$D"' EXIT
while read -r V E R K; do
  DECODE=${K:+--decode-viewers $K}
  D=$(mktemp -d /tmp/load-XXXX)
  echo admin-token-for-load-0123456789 > $D/admin.tok
  $B/server/tessera-server --data $D/data --port 0 --port-file $D/port --admin-token-file $D/admin.tok ${SERVER_OPTIONS:-} 2>$D/server.log &
  S=$!
  for _ in $(seq 100); do [ -s $D/port ] && break; sleep 0.05; done
  P=$(cat $D/port)
  $B/client/cli/tessera remote --port $P --token admin-token-for-load-0123456789 create $ROOT/tests/data/cube.obj --tags $ROOT/tests/data/cube.tags --max-level 5 >/dev/null
  $B/client/cli/tessera remote --port $P --token admin-token-for-load-0123456789 grant 1 editor replay-editor-token-0123456789
  timeout 300 $B/client/replay/tessera-replay load --port $P --token replay-editor-token-0123456789 --document 1 \
    --editors $E --viewers $V --rate $R --seconds ${SECONDS_PER_ROW:-5} $DECODE --profile 2,5,10 --vertex-level 2 --vertex-count 98 \
    ${LOAD_OPTIONS:-} --server-pid $S --report $D/report.json --quiet > $D/summary.txt 2>&1
  echo "=== $V viewers, $E editors, $R/s (loadavg $(cut -d' ' -f1 /proc/loadavg))"
  cat $D/summary.txt | head -20
  kill -TERM $S; wait $S 2>/dev/null
  cp $D/report.json /tmp/load-report-$V-$E-$R.json 2>/dev/null
  rm -rf $D   # the report is kept above; the server's data and logs go
  D= S=
done
