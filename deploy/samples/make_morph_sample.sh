#!/usr/bin/env bash
# Makes the image-morph sample (docs/INTERPOLATION.md; deploy/samples/morph/) and the
# frame strip in the README (docs/images/morph_strip.png):
#   a.png, b.png        a striped ring (a shape with a hole) on two backgrounds,
#                       the second moved, turned and stretched, a green dot on
#                       each at the same mesh vertex
#   mesh_a.obj, mesh_b.obj  the annulus mesh over each image (pixel coordinates)
#   morph.tags          three interpolating vertices (the dot marks one)
# then runs `tessera morph` over them. Needs a release build:
#   cmake --preset release && cmake --build --preset release -j2
#   bash deploy/samples/make_morph_sample.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build/release}
OUT=deploy/samples/morph
"$BUILD/tests/write_morph_sample" "$OUT"
"$BUILD/client/cli/tessera" morph --from "$OUT/a.png" --to "$OUT/b.png" \
  --mesh-from "$OUT/mesh_a.obj" --mesh-to "$OUT/mesh_b.obj" --tags "$OUT/morph.tags" \
  --level 3 --frames 7 -o "${TMPDIR:-/tmp}/tessera-morph-sample" --strip docs/images/morph_strip.png
