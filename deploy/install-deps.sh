#!/usr/bin/env bash
# Installs every Debian package Tessera needs to build, test and benchmark
# (with --build: only what building tessera-server and tessera needs).
# Idempotent: packages already present are skipped, and apt is not touched at all
# when nothing is missing. Debian packages only; nothing is downloaded from elsewhere.
set -euo pipefail

# What building the server and the CLI needs (the container image's build
# stage installs only these: `install-deps.sh --build`).
build_packages=(
  # toolchain
  build-essential cmake pkg-config
  # core: base mesh, mesh I/O, glTF, compression
  libopenmesh-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libdraco-dev zlib1g-dev
  # a view's first picture: tiles simplified by edge collapses (docs/VIEWS.md)
  libmeshoptimizer-dev
  # protocol and server
  libboost-dev libboost-system-dev libprotobuf-dev protobuf-compiler libsqlite3-dev libssl-dev
  # command lines (one options library for every binary)
  libcli11-dev
  # exact limit masks: eigenvectors of local subdivision matrices (header-only)
  libeigen3-dev
  # polygon triangulation on import: constrained Delaunay (header-only; GMP at run time)
  libcgal-dev
  # operations: Prometheus metrics (the text format), sd_notify; HTTP is Boost.Beast (libboost-dev)
  prometheus-cpp-dev libsystemd-dev
  # cluster mode (docs/CLUSTER.md): the NATS C client (JetStream, key-value buckets)
  libnats-dev
)
# Everything else for the whole tree, its tests and benchmarks.
packages=(
  "${build_packages[@]}"
  ninja-build git openssl
  # the unit check (systemd-analyze verify)
  systemd
  # viewer, and its headless rendering without an X server (EGL surfaceless, OSMesa)
  libglfw3-dev libgl-dev libimgui-dev libegl1-mesa-dev libgbm-dev libosmesa6-dev
  # tests and benchmarks: OpenSubdiv is the oracle, never a runtime dependency
  libgtest-dev libgmock-dev libbenchmark-dev libosd-dev
  # test data and tools: real meshes (CGAL demo data), the Khronos glTF validator (npm),
  # an X server for the viewer and X input events for it (xdotool), also for the Blender
  # add-on's grab test (tests/blender/run_ui_grab.py)
  libcgal-demo xvfb xauth xdotool
  # coverage-guided fuzzing: libFuzzer with ASan and UBSan (tests/fuzz)
  clang-14 libfuzzer-14-dev libclang-rt-14-dev
  # the format check of the formatted folders (tests/format)
  clang-format-14
  # the cluster tests and deploy/cluster-loopback.sh start real NATS servers
  nats-server
  # the Python package (client/python, docs/PYTHON.md): pybind11 and Python's headers to
  # build it, NumPy for its arrays, pytest for its tests (tests/python)
  pybind11-dev python3-dev python3-numpy python3-pytest
  # the Blender add-on (client/blender, docs/BLENDER.md) and its tests run Debian's Blender,
  # whose Python is Debian's python3 (the tessera package's)
  blender
  # the browser viewer's tests drive Debian's Chromium headless (docs/WEB_VIEWER.md "Tests")
  chromium
)
if [[ ${1:-} == --build ]]; then
  packages=("${build_packages[@]}")
elif ! command -v npm >/dev/null 2>&1; then
  # The glTF validator runs on Node. A machine may already carry a newer Node with its own
  # npm (which conflicts with Debian's npm package): only ask Debian for it when absent.
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} > 0)); then
  echo "install-deps: installing ${missing[*]}" >&2
  if [[ $(id -u) -ne 0 ]]; then
    echo "install-deps: missing packages and not root; run as root or install them: ${missing[*]}" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The web viewer's npm packages (three, draco3d, protobufjs, esbuild,
# puppeteer-core), pinned by client/web/package-lock.json, into
# client/web/node_modules: the only download outside Debian's packages.
# Skipped when that lock file is already installed, so builds and tests run
# offline afterwards. puppeteer-core never downloads a browser (the tests
# use Debian's chromium).
if [[ ${1:-} != --build ]]; then
  web=$(cd "$(dirname "$0")/../client/web" && pwd)
  lock_hash=$(sha256sum "$web/package-lock.json" | cut -d' ' -f1)
  stamp=$web/node_modules/.tessera-lock-sha256
  if [[ ! -f $stamp || $(cat "$stamp") != "$lock_hash" ]]; then
    echo "install-deps: npm ci in client/web" >&2
    (cd "$web" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
    echo "$lock_hash" >"$stamp"
  fi
fi
