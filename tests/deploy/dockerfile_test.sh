#!/usr/bin/env bash
# Checks deploy/Dockerfile without a Docker engine (Debian 12 packages no
# Dockerfile linter: hadolint is not in Debian), rule by rule:
#   - multi-stage, every stage FROM Debian 12;
#   - packages only from Debian: no curl, wget, pip, npm or remote ADD;
#     apt-get install with --no-install-recommends, lists removed after;
#   - the runtime stage runs as a non-root USER, has a VOLUME that is the
#     server's --data, a HEALTHCHECK through `tessera-server health`, EXPOSEs
#     the protocol and HTTP ports the CMD sets;
#   - its package list covers every shared library of tessera-server and
#     tessera (ldd, dpkg -S) beyond the debian:12-slim base;
#   - .dockerignore keeps build trees out of the context.
# Usage: dockerfile_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1
build=$2
file=$src/deploy/Dockerfile
fail() { echo "FAIL: deploy/Dockerfile: $*" >&2; exit 1; }
# Continuation lines joined, comments dropped.
text=$(sed -e 's/#.*$//' "$file" | sed -e ':a' -e '/\\$/N; s/\\\n/ /; ta')

froms=$(grep -cE '^FROM ' <<<"$text")
((froms >= 2)) || fail "not a multi-stage build ($froms FROM lines)"
while read -r _ image _; do
  [[ $image =~ ^debian:(12|bookworm)(-slim)?$ ]] || fail "stage FROM $image is not Debian 12"
done < <(grep -E '^FROM ' <<<"$text")
if grep -qiE '(curl|wget|pip3? install|npm (install|ci)|^ADD +https?:)' <<<"$text"; then
  fail "downloads from outside Debian: $(grep -iE 'curl|wget|pip|npm|^ADD' <<<"$text" | head -1)"
fi
while read -r line; do
  [[ $line == *--no-install-recommends* ]] || fail "apt-get install without --no-install-recommends: $line"
  [[ $line == *"rm -rf /var/lib/apt/lists"* ]] || fail "apt lists left in the layer: $line"
done < <(grep -E 'apt-get install' <<<"$text")
grep -q 'install-deps.sh --build' <<<"$text" || fail "the build stage does not use deploy/install-deps.sh --build"

runtime=$(awk '/^FROM /{n++} n==2' <<<"$text")
[[ -n $runtime ]] || fail "no runtime stage"
user=$(grep -E '^USER ' <<<"$runtime" | tail -1 | awk '{print $2}')
[[ -n $user && $user != root && $user != 0 && $user != 0:* ]] || fail "the runtime stage runs as '${user:-root}'"
volume=$(grep -E '^VOLUME ' <<<"$runtime" | grep -oE '/[a-z/]+' | head -1)
[[ -n $volume ]] || fail "no VOLUME for the data directory"
grep -qE "\"--data\", \"$volume\"" <<<"$runtime" || fail "the server's --data is not the volume $volume"
grep -qE '^HEALTHCHECK .*CMD \["tessera-server", "health"' <<<"$runtime" || fail "no HEALTHCHECK through tessera-server health"
http=$(grep -oE '"--http-port", "[0-9]+"' <<<"$runtime" | grep -oE '[0-9]+')
[[ -n $http ]] || fail "the CMD does not turn the HTTP endpoint on (the health check needs it)"
grep -qE "^EXPOSE .*\b7878\b" <<<"$runtime" || fail "the protocol port 7878 is not exposed"
grep -qE "^EXPOSE .*\b$http\b" <<<"$runtime" || fail "the HTTP port $http is not exposed"
grep -qE "healthz\"" <<<"$runtime" && grep -q "127.0.0.1:$http/healthz" <<<"$runtime" \
  || fail "the health check does not ask the HTTP port $http"

# Shared libraries: everything ldd lists must come from the base image or
# from the runtime stage's apt-get install.
base=" libc6 libgcc-s1 libstdc++6 zlib1g libsystemd0 libcap2 libgcrypt20 libgpg-error0 liblz4-1 liblzma5 libzstd1 "
listed=" $(grep -E 'apt-get install' <<<"$runtime" | tr ' ' '\n' | grep -E '^lib' | tr '\n' ' ') "
for binary in "$build/server/tessera-server" "$build/client/cli/tessera"; do
  [[ -x $binary ]] || fail "build $binary first"
  for lib in $(ldd "$binary" | awk '/=>/ {print $3}'); do
    package=$(dpkg -S "$(readlink -f "$lib")" 2>/dev/null | head -1 | cut -d: -f1 || true)
    [[ -n $package ]] || package=$(dpkg -S "$lib" 2>/dev/null | head -1 | cut -d: -f1 || true)
    [[ -n $package ]] || fail "no Debian package owns $lib (needed by $(basename "$binary"))"
    [[ $base == *" $package "* || $listed == *" $package "* ]] \
      || fail "$(basename "$binary") needs $lib from $package, which the runtime stage does not install"
  done
done

ignore=$src/.dockerignore
[[ -f $ignore ]] && grep -qx 'build/' "$ignore" || fail ".dockerignore must exclude build/"
echo "Dockerfile: ok ($froms stages, runs as $user, volume $volume, HTTP port $http)"
