#!/usr/bin/env bash
# The main job. For now, a demo: refine a sample mesh with creases and a corner
# to level 3 on its limit surface, and write a Draco-compressed GLB.
# Usage: bash deploy/run.sh [OUTPUT.glb]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-tessera-demo.glb}"

bash deploy/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target tessera

cli=build/release/client/cli/tessera
"$cli" info deploy/samples/cube.obj --tags deploy/samples/cube.tags
"$cli" refine deploy/samples/cube.obj --tags deploy/samples/cube.tags \
  --level 3 --limit --draco -o "$out"
echo "wrote $out"
