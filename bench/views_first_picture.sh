#!/usr/bin/env bash
# View-dependent streaming against whole-document profiles (docs/PERFORMANCE.md
# "Views"): CGAL's armadillo held to level 4 on a fresh release server, then
# tessera-view headless (software GL) at phone and desktop sizes, each with
# --views (tolerance 1 px) and with the uniform profile whose level is the
# finest the view shows there (the same on-screen error), one fresh viewer per
# row. Prints the viewer's first and whole picture times (from its start,
# connecting included), the region bytes it received, its triangles, and the
# server's resident memory after the row.
#   bash bench/views_first_picture.sh
set -u
ROOT=$(cd "$(dirname "$0")/.." && pwd)
B=$ROOT/build/release
D=$(mktemp -d /tmp/views-bench-XXXX)
trap 'kill -TERM $S 2>/dev/null; wait $S 2>/dev/null; rm -rf $D' EXIT
tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C $D data/meshes/armadillo.off
echo admin-token-for-views-0123456789 > $D/admin.tok
$B/server/tessera-server --data $D/data --port 0 --port-file $D/port --admin-token-file $D/admin.tok \
  --max-level 4 ${SERVER_OPTIONS:-} 2>$D/server.log &
S=$!
for _ in $(seq 100); do [ -s $D/port ] && break; sleep 0.05; done
P=$(cat $D/port)
$B/client/cli/tessera remote --port $P --token admin-token-for-views-0123456789 create \
  $D/data/meshes/armadillo.off --max-level 4 >/dev/null
row() {  # NAME SIZE OPTIONS...
  local name=$1 size=$2; shift 2
  local out
  out=$(DISPLAY= WAYLAND_DISPLAY= timeout 600 $B/client/view/tessera-view --connect 127.0.0.1:$P \
    --token admin-token-for-views-0123456789 --document 1 --no-hud --no-gizmo --frames 2 --timeout 300 \
    --size $size --screenshot $D/$name.png "$@" 2>&1)
  local rss
  rss=$(awk '/VmRSS/ {print $2}' /proc/$S/status)
  echo "$name: $(echo "$out" | grep -o '[0-9]* triangles)' | tr -d ')'), $(echo "$out" | grep '^first picture'), server RSS $((rss / 1024)) MiB"
}
row phone-views 390x844 --views --tolerance 1
row phone-level1 390x844 --base-level 1 --max-level 1
row desktop-views 1920x1080 --views --tolerance 1
row desktop-level2 1920x1080 --base-level 2 --max-level 2
