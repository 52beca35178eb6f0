#!/usr/bin/env bash
# A Tessera cluster on this machine's loopback (docs/CLUSTER.md): a 3-server
# NATS JetStream cluster and 3 tessera-server nodes on it, an admin token,
# and the creased cube as a sample document. Serves until Ctrl-C, then stops
# everything it started.
#
#   bash deploy/cluster-loopback.sh            # builds what is missing first
#   TESSERA_CLUSTER_DIR=/tmp/tc bash deploy/cluster-loopback.sh
#   TESSERA_CLUSTER_ONCE=1 bash deploy/cluster-loopback.sh   # start, check, stop
#
# Ports: NATS clients 14222-14224, NATS routes 16222-16224, tessera nodes
# 17878-17880 (TESSERA_CLUSTER_BASE_PORT moves the last ones).
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${TESSERA_CLUSTER_DIR:-tessera-cluster}"
base="${TESSERA_CLUSTER_BASE_PORT:-17878}"

bash deploy/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target tessera tessera-server

server=build/release/server/tessera-server
cli=build/release/client/cli/tessera
mkdir -p "$dir"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
trap cleanup EXIT INT TERM

# 1. Three NATS servers with JetStream, clustered (JetStream needs a name
# per server and a cluster name). max_payload 8MB: snapshot frames of large
# documents travel between nodes in one message. From nats-server 2.10 on,
# sync_interval: always puts each write on disk before JetStream
# acknowledges it (docs/CLUSTER.md "What an acknowledged edit survives");
# 2.9 refuses the option, and its acknowledgements are from memory.
nats_version=$(nats-server --version | sed 's/^.*v//')
sync=""
if [ "$(printf '%s\n' 2.10.0 "$nats_version" | sort -V | head -1)" = 2.10.0 ]; then
  sync="sync_interval: always, "
fi
echo "nats-server $nats_version: ${sync:-no sync_interval (acknowledged from memory and the page cache)}"
urls=()
for i in 1 2 3; do
  cat >"$dir/nats$i.conf" <<CONF
server_name: nats$i
listen: 127.0.0.1:$((14221 + i))
max_payload: 8MB
jetstream { ${sync}store_dir: "$dir/nats$i", max_mem: 256MB, max_file: 8GB }
cluster {
  name: tessera
  listen: 127.0.0.1:$((16221 + i))
  routes: [nats://127.0.0.1:16222, nats://127.0.0.1:16223, nats://127.0.0.1:16224]
}
CONF
  nats-server -c "$dir/nats$i.conf" 2>>"$dir/nats$i.log" &
  pids+=($!)
  urls+=("nats://127.0.0.1:$((14221 + i))")
done
cluster=$(IFS=,; echo "${urls[*]}")

# 2. An admin token, stored (hashed) in the cluster's token bucket. The
# first tessera command waits for JetStream to elect its leaders.
token_file="$dir/admin.token"
for attempt in $(seq 1 60); do
  if [ -s "$token_file" ] || (umask 077; "$server" token new --role admin --cluster "$cluster" \
        2>>"$dir/token.log" >"$token_file.tmp" && mv "$token_file.tmp" "$token_file"); then
    break
  fi
  sleep 0.5
done
[ -s "$token_file" ] || { echo "NATS JetStream did not come up; see $dir/nats*.log" >&2; exit 1; }

# 3. Three nodes on the same NATS cluster, each with its own client port.
for i in 0 1 2; do
  rm -f "$dir/node$i.port"
  "$server" --cluster "$cluster" --node-name "node$i" --port $((base + i)) --port-file "$dir/node$i.port" \
    2>>"$dir/node$i.log" &
  pids+=($!)
done
for i in 0 1 2; do
  for attempt in $(seq 1 100); do [ -s "$dir/node$i.port" ] && break; sleep 0.1; done
  [ -s "$dir/node$i.port" ] || { echo "node$i did not start; see $dir/node$i.log" >&2; exit 1; }
done

# 4. A sample document created through node 0 and listed through node 2.
doc=$("$cli" remote create tests/data/cube.obj --tags tests/data/cube.tags --port "$base" --token-file "$token_file")
"$cli" remote list --port $((base + 2)) --token-file "$token_file"
echo "cluster up: NATS $cluster; nodes on 127.0.0.1 ports $base-$((base + 2)); document $doc; admin token in $token_file"
echo "view it through any node: build/release/client/view/tessera-view --connect 127.0.0.1:$((base + 1)) --token-file $token_file --document $doc"
if [ -n "${TESSERA_CLUSTER_ONCE:-}" ]; then exit 0; fi
wait
