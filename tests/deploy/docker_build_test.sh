#!/usr/bin/env bash
# Builds deploy/Dockerfile, starts the image and talks to it: waits for the
# container's health check, checks the server runs as tessera, that no build
# toolchain is left in the image, GETs /healthz through a port published on
# 127.0.0.1, makes a token inside the container and creates and lists a
# document over the protocol with the tessera CLI.
#
# Skipped (exit 77, saying why) without a docker command or without a
# reachable engine (the image is built wherever Docker is available; docs/OPERATIONS.md
# "Container image"), and
# when TESSERA_DOCKER_TEST=0: building the image compiles the whole project
# (547 s on one core on 2026-11-26), which a quick local run may not want.
# Where no registry is reachable, the Debian base images are made first
# from Debian's archive (deploy/build-base-images.sh, as root).
#
# Usage: [TESSERA_DOCKER_TEST=0] docker_build_test.sh SOURCE_DIR
#   TESSERA_DOCKER_BUILD_ARGS   more `docker build` options, e.g. "--cpuset-cpus 1" (classic builder)
#   TESSERA_DOCKER_BUILD_TIMEOUT  seconds the build may take (default 2400)
#   TESSERA_DOCKER_KEEP_IMAGE=1 keep the image (tessera-server-test:PID) for a look afterwards
#   TESSERA_CLI                 the host's tessera CLI (default SOURCE_DIR/build/release/client/cli/tessera);
#                               without it the image's own CLI is used through docker exec
# Every wait is bounded (base images 900 s, build 2400 s, health 180 s, each
# docker exec and CLI call 30 s), within ctest's TIMEOUT of 3600 s.
set -euo pipefail
src=$(cd "$1" && pwd)
skip() { echo "SKIPPED: $*"; exit 77; }
if ! command -v docker >/dev/null 2>&1; then
  skip "no docker command on this machine; deploy/Dockerfile is checked by Deploy.Dockerfile instead"
fi
if ! info=$(timeout 30 docker info 2>&1); then
  skip "no Docker engine reachable (docker info: $(grep -m1 -iE "error|cannot" <<<"$info" || head -1 <<<"$info")); deploy/Dockerfile is checked by Deploy.Dockerfile instead"
fi
if [[ ${TESSERA_DOCKER_TEST:-} == 0 ]]; then
  skip "a Docker engine is reachable, but TESSERA_DOCKER_TEST=0 asks not to build the image (about 10 minutes on one core; docs/OPERATIONS.md, Container image)"
fi

say() { echo "docker-test: $*"; }
fail() { echo "FAIL: $*" >&2; exit 1; }
tag=tessera-server-test:$$
name=tessera-test-$$
tmp=$(mktemp -d)
cleanup() {
  docker rm -f -v "$name" >/dev/null 2>&1 || true
  if [[ ${TESSERA_DOCKER_KEEP_IMAGE:-} == 1 ]]; then
    say "image kept: $tag"
  else
    docker rmi "$tag" >/dev/null 2>&1 || true
  fi
  rm -rf "$tmp"
}
trap cleanup EXIT

# Base images: where no registry is reachable, from Debian's archive.
missing=()
for base in debian:12 debian:12-slim; do
  docker image inspect "$base" >/dev/null 2>&1 || missing+=("$base")
done
if ((${#missing[@]})); then
  say "no local ${missing[*]}: making them from Debian's archive (deploy/build-base-images.sh)"
  timeout 900 bash "$src/deploy/build-base-images.sh" || fail "deploy/build-base-images.sh failed"
fi

read -r -a build_args <<<"${TESSERA_DOCKER_BUILD_ARGS:-}"
say "docker build ${build_args[*]} -f deploy/Dockerfile -t $tag (at most ${TESSERA_DOCKER_BUILD_TIMEOUT:-2400} s)"
start=$(date +%s)
timeout "${TESSERA_DOCKER_BUILD_TIMEOUT:-2400}" docker build "${build_args[@]}" -f "$src/deploy/Dockerfile" -t "$tag" "$src" \
  || fail "docker build failed or timed out (exit $?)"
built=$(date +%s)
say "built in $((built - start)) s; image $(docker image inspect -f '{{.Size}}' "$tag" | awk '{printf "%.1f MB", $1/1e6}')"
docker history --format '{{.Size}}\t{{.CreatedBy}}' "$tag" | cut -c1-150

# No compiler, build tool or package sources in the runtime image.
toolchain=$(docker run --rm --entrypoint sh "$tag" -c 'for t in gcc g++ cc c++ cmake make ld protoc; do command -v $t; done; true')
[[ -z $toolchain ]] || fail "build tools in the runtime image: $(tr '\n' ' ' <<<"$toolchain")"
[[ -z $(docker run --rm --entrypoint sh "$tag" -c 'ls /src /build /out 2>/dev/null || true') ]] \
  || fail "the build stage's /src, /build or /out is in the runtime image"

# Ports on loopback only, the host ports chosen by the engine.
docker run -d --name "$name" -p 127.0.0.1::7878 -p 127.0.0.1::9478 "$tag" >/dev/null
run=$(date +%s)
status=
while (($(date +%s) - run < 180)); do
  [[ $(docker inspect -f '{{.State.Running}}' "$name") == true ]] \
    || { docker logs "$name" 2>&1 | tail -20; fail "the container stopped: $(docker inspect -f '{{.State.ExitCode}}' "$name")"; }
  status=$(docker inspect -f '{{if .State.Health}}{{.State.Health.Status}}{{end}}' "$name")
  [[ $status == healthy || $status == unhealthy ]] && break
  sleep 2
done
[[ $status == healthy ]] || { docker logs "$name" 2>&1 | tail -20; fail "container health is '$status' after $(($(date +%s) - run)) s"; }
healthy=$(($(date +%s) - run))
say "healthy $healthy s after docker run (the first health check runs 30 s after the start)"

# The server (PID 1) and docker exec both run as tessera.
server_user=$(docker exec "$name" stat -c %U /proc/1)
exec_user=$(docker exec "$name" id -un)
[[ $server_user == tessera && $exec_user == tessera ]] \
  || fail "the container runs as '$server_user' (server) and '$exec_user' (exec), not tessera"
say "the server runs as $server_user ($(docker exec "$name" id))"

# /healthz from the host, through the published port.
http=$(docker port "$name" 9478/tcp | head -1)
proto=$(docker port "$name" 7878/tcp | head -1)
[[ $http == 127.0.0.1:* && $proto == 127.0.0.1:* ]] || fail "ports not published on 127.0.0.1 only: $http $proto"
command -v curl >/dev/null || fail "this test needs curl on the host"
code=$(curl -sS --max-time 10 -o "$tmp/healthz" -w '%{http_code}' "http://$http/healthz") || fail "GET http://$http/healthz failed"
[[ $code == 200 ]] || fail "GET http://$http/healthz: HTTP $code: $(head -c 300 "$tmp/healthz")"
say "GET http://$http/healthz: HTTP $code: $(head -c 300 "$tmp/healthz")"

# A token made inside the container, then a document created and listed.
token=$(timeout 30 docker exec "$name" tessera-server token new --role admin --data /var/lib/tessera) \
  || fail "tessera-server token new failed"
[[ $token =~ ^[0-9a-f]{64}$ ]] || fail "token new printed '$token', not 64 hex digits"
(umask 077 && printf '%s\n' "$token" >"$tmp/token")
cli=${TESSERA_CLI:-$src/build/release/client/cli/tessera}
if [[ -x $cli ]]; then
  where="the host's $cli through 127.0.0.1:${proto#*:}"
  remote() { timeout 30 "$cli" remote --host 127.0.0.1 --port "${proto#*:}" --token-file "$tmp/token" "$@"; }
  mesh=$src/tests/data/cube.obj
else
  where="the image's tessera through docker exec (no host CLI at $cli)"
  docker exec -i "$name" sh -c 'umask 077 && cat >/tmp/token' <"$tmp/token"
  docker exec -i "$name" sh -c 'cat >/tmp/cube.obj' <"$src/tests/data/cube.obj"
  remote() { timeout 30 docker exec "$name" tessera remote --token-file /tmp/token "$@"; }
  mesh=/tmp/cube.obj
fi
doc=$(remote create "$mesh" --doc-name docker-test) || fail "tessera remote create failed ($where)"
list=$(remote list) || fail "tessera remote list failed ($where)"
grep -qE "^$doc"$'\t'"docker-test"$'\t' <<<"$list" || fail "tessera remote list does not show document $doc: $list"
say "tessera remote create and list with $where: $(tr '\t\n' '  ' <<<"$list")"
say "server log:"
docker logs "$name" 2>&1 | tail -8
echo "image: built in $((built - start)) s, healthy after $healthy s, runs as tessera, /healthz 200, remote create and list work"
