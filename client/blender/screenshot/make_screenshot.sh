#!/usr/bin/env bash
# Writes docs/images/blender-live-document.png (docs/BLENDER.md): Debian's
# Blender under Xvfb with the add-on from build/release, a tessera-server
# on a temporary store, the sample quad cube edited by a second session.
# Usage: bash client/blender/screenshot/make_screenshot.sh [BUILD_DIR] [OUT]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../../.." && pwd)
build=$(cd "${1:-$src/build/release}" && pwd)
out=$(realpath -m "${2:-$src/docs/images/blender-live-document.png}")
root=$(mktemp -d -t tessera-blender-shot-XXXXXX)
server_pid=
cleanup() {
  if [[ -n $server_pid ]]; then kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; fi
  rm -rf "$root"
}
trap cleanup EXIT
echo "screenshot-token-0123456789" > "$root/token"
"$build/server/tessera-server" --data "$root/data" --port 0 --port-file "$root/port" \
  --admin-token-file "$root/token" 2> "$root/server.log" &
server_pid=$!
for _ in $(seq 100); do [[ -s $root/port ]] && break; sleep 0.1; done
mkdir -p "$root/scripts/addons"
(cd "$root/scripts/addons" && cmake -E tar xf "$build/client/blender/tessera_blender.zip")
BLENDER_USER_CONFIG="$root/config" blender -b --factory-startup \
  --python-expr "import bpy; bpy.ops.wm.save_as_mainfile(filepath='$root/empty.blend')" > /dev/null
TMPDIR="$root" BLENDER_USER_SCRIPTS="$root/scripts" BLENDER_USER_CONFIG="$root/config" \
  timeout 120 xvfb-run -a -s "-screen 0 1060x780x24" \
  blender --factory-startup --window-geometry 0 0 1060 780 --no-window-focus "$root/empty.blend" \
  --python "$here/live_document_screenshot.py" -- "$(cat "$root/port")" "$root/token" "$src/deploy/samples" "$root/shot.png"
cp "$root/shot.png" "$out"
echo "wrote $out"
