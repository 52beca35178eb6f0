#!/usr/bin/env bash
# The main job: tessera-server on the embedded SQLite store, with a sample
# document, a viewer (a window when a display exists, otherwise a headless
# render to tessera-demo.png under Xvfb), and a short scripted editing
# session streamed through the server.
#
#   bash deploy/run.sh              # serves until Ctrl-C
#   TESSERA_DEMO_ONLY=1 bash deploy/run.sh   # run the session, then stop
#
# The browser viewer is served on TESSERA_WEB_PORT (docs/WEB_VIEWER.md); the
# script prints the address that opens the sample document.
#
# Settings: TESSERA_DATA (default tessera-data), TESSERA_PORT (default 7878),
# TESSERA_WEB_PORT (default 7879), TESSERA_SAMPLE: cube (the default: the
# creased cube of triangles, a Loop document) or quads (the same cube as six
# quads, a Catmull-Clark document).
set -euo pipefail
cd "$(dirname "$0")/.."
data="${TESSERA_DATA:-tessera-data}"
port="${TESSERA_PORT:-7878}"
web_port="${TESSERA_WEB_PORT:-7879}"
sample="${TESSERA_SAMPLE:-cube}"
case "$sample" in
  cube) sample_args=(deploy/samples/cube.obj --scheme loop); session=deploy/samples/session.txt ;;
  quads) sample_args=(deploy/samples/quad_cube.obj --scheme catmull-clark); session=deploy/samples/session_quads.txt ;;
  *) echo "TESSERA_SAMPLE: cube or quads, not '$sample'" >&2; exit 2 ;;
esac

bash deploy/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target tessera tessera-server tessera-view tessera_web

cli=build/release/client/cli/tessera
server=build/release/server/tessera-server
mkdir -p "$data"
token_file="$data/admin.token"
if [ ! -s "$token_file" ]; then
  (umask 077; "$server" token new --role admin --data "$data/store" 2>>"$data/server.log" > "$token_file")
fi
rm -f "$data/port"
"$server" --data "$data/store" --port "$port" --admin-token-file "$token_file" --port-file "$data/port" \
  --ws-port "$web_port" 2>>"$data/server.log" &
server_pid=$!
trap 'kill -TERM $server_pid 2>/dev/null; wait $server_pid 2>/dev/null' EXIT
for _ in $(seq 100); do [ -s "$data/port" ] && break; sleep 0.1; done
[ -s "$data/port" ] || { echo "tessera-server did not start; see $data/server.log" >&2; exit 1; }
remote=("$cli" remote --port "$port" --token-file "$token_file" --name demo)

viewer=build/release/client/view/tessera-view
doc=$("${remote[@]}" list | awk 'NR==1 {print $1}')
fresh=0
if [ -z "$doc" ]; then
  doc=$("${remote[@]}" create "${sample_args[@]}" --tags deploy/samples/cube.tags --max-level 5 --doc-name "sample $sample")
  echo "created document $doc"
  fresh=1
fi
view=("$viewer" --connect "127.0.0.1:$port" --token-file "$token_file" --document "$doc")
if [ -n "${DISPLAY:-}" ] && [ "${TESSERA_DEMO_ONLY:-0}" != 1 ]; then
  "${view[@]}" &  # watch the session's edits stream in
  sleep 2
fi
if [ "$fresh" = 1 ]; then "${remote[@]}" edit "$doc" --script "$session"; fi
if [ -z "${DISPLAY:-}" ] || [ "${TESSERA_DEMO_ONLY:-0}" = 1 ]; then
  # Headless: EGL on Mesa's surfaceless platform, no X server needed.
  "${view[@]}" --screenshot tessera-demo.png --frames 20 && echo "rendered tessera-demo.png"
fi
"${remote[@]}" list
"${remote[@]}" export "$doc" --level 3 --limit -o tessera-demo.glb
"${remote[@]}" stats | head -8
echo "tessera-server: 127.0.0.1:$port, store in $data/store, admin token in $token_file, log in $data/server.log"
# The token rides in the fragment, which the browser never sends to the server.
echo "browser viewer: http://127.0.0.1:$web_port/?doc=$doc#token=$(head -1 "$token_file")  (this address holds the admin token)"
if [ "${TESSERA_DEMO_ONLY:-0}" = 1 ]; then exit 0; fi
echo "serving; Ctrl-C stops it"
wait $server_pid
