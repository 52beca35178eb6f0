#!/usr/bin/env bash
# Builds deploy/Dockerfile and checks the container comes up healthy, when a
# Docker engine is available; otherwise says why and exits 77 (skipped).
# Usage: docker_build_test.sh SOURCE_DIR
set -euo pipefail
src=$1
if ! command -v docker >/dev/null 2>&1; then
  echo "SKIPPED: no docker command on this machine; deploy/Dockerfile is checked by Deploy.Dockerfile instead"
  exit 77
fi
if ! info=$(docker info 2>&1); then
  echo "SKIPPED: no Docker engine reachable (docker info: $(grep -m1 -iE "error|cannot" <<<"$info" || head -1 <<<"$info")); deploy/Dockerfile is checked by Deploy.Dockerfile instead"
  exit 77
fi
tag=tessera-server-test:$$
name=tessera-test-$$
trap 'docker rm -f "$name" >/dev/null 2>&1 || true; docker rmi "$tag" >/dev/null 2>&1 || true' EXIT
docker build -f "$src/deploy/Dockerfile" -t "$tag" "$src"
docker run -d --name "$name" "$tag" >/dev/null
for _ in $(seq 1 60); do
  status=$(docker inspect -f '{{.State.Health.Status}}' "$name")
  [[ $status == healthy ]] && break
  sleep 2
done
[[ $status == healthy ]] || { docker logs "$name"; echo "FAIL: container health is '$status'" >&2; exit 1; }
[[ $(docker exec "$name" id -un) == tessera ]] || { echo "FAIL: the container does not run as tessera" >&2; exit 1; }
echo "image: built, healthy, runs as tessera"
