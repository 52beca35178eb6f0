#!/usr/bin/env bash
# `cmake --install` into a scratch root (DESTDIR; the build's prefix, /usr
# by default, must be /usr for this check), then the
# installed pieces: the four binaries run and print their version, the unit
# passes `systemd-analyze verify` with no complaint at all (parse warnings
# do not change its exit code, so its output must be empty) and its
# sandboxing scores as "OK" in `systemd-analyze security`, and the example
# configuration is accepted by the installed server.
# Usage: install_test.sh BUILD_DIR
set -euo pipefail
build=$1
root=$(mktemp -d "${TMPDIR:-/tmp}/tessera-install.XXXXXX")
trap 'rm -rf "$root"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

prefix=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
[[ $prefix == /usr ]] || fail "configure $build with the default prefix /usr (it has '$prefix')"
DESTDIR=$root cmake --install "$build" >"$root.log" 2>&1 || { cat "$root.log"; fail "cmake --install"; }
rm -f "$root.log"
for f in usr/bin/tessera usr/bin/tessera-server usr/bin/tessera-view usr/bin/tessera-replay \
         usr/lib/systemd/system/tessera-server.service usr/lib/sysusers.d/tessera.conf \
         etc/tessera/tessera-server.conf usr/share/doc/Tessera/OPERATIONS.md; do
  [[ -e $root/$f ]] || fail "cmake --install did not install /$f"
done
for b in tessera tessera-server tessera-view tessera-replay; do
  out=$("$root/usr/bin/$b" --version) || fail "$b --version exited non-zero"
  [[ $out == "$b "[0-9]* ]] || fail "$b --version printed '$out'"
done

unit=$root/usr/lib/systemd/system/tessera-server.service
grep -q '^ExecStart=/usr/bin/tessera-server --config /etc/tessera/tessera-server.conf$' "$unit" \
  || fail "the installed unit does not start the installed binary with the installed configuration"
# systemd-analyze verify resolves the targets the unit names and the
# commands it runs inside --root: give it the system's units and kill.
mkdir -p "$root/usr/lib/systemd/system" "$root/bin"
cp -rn /lib/systemd/system/. "$root/usr/lib/systemd/system/"
cp /bin/kill "$root/bin/kill"
verify=$(systemd-analyze verify --root="$root" tessera-server.service 2>&1) || fail "systemd-analyze verify: $verify"
[[ -z $verify ]] || fail "systemd-analyze verify complained: $verify"
security=$(systemd-analyze security --offline=yes --root="$root" tessera-server.service 2>&1 | tail -1)
# systemd rates 0 (locked down) to 10 (exposed); below 2 is its "OK".
[[ $security =~ exposure\ level\ for\ tessera-server\.service:\ ([0-9]+)\.[0-9]+\ OK ]] && ((BASH_REMATCH[1] < 2)) \
  || fail "systemd-analyze security: $security"
echo "unit: $security"

# Every serving option is documented in the example configuration.
for opt in $("$root/usr/bin/tessera-server" --help | grep -oE -- '--[a-z][a-z-]+' | sort -u); do
  name=${opt#--}
  case $name in help | version | config) continue ;; esac
  grep -qE "^(# )?$name = " "$root/etc/tessera/tessera-server.conf" \
    || fail "option --$name is missing from deploy/tessera-server.conf"
done

# The installed example configuration, read by the installed server: every
# option it sets and every commented one must be a real option. Uncomment
# them all (values are the defaults), pointing the data directory elsewhere.
conf=$root/all-options.conf
sed -E 's/^# ([a-z-]+ = .*)$/\1/' "$root/etc/tessera/tessera-server.conf" \
  | grep -vE '^(data|port-file|http-port-file|admin-token-file|tls-cert|tls-key|log-file) = ' >"$conf"
echo "data = \"$root/data\"" >>"$conf"
echo "port = 0" >>"$conf"
echo "http-port = 0" >>"$conf"
# 'health' with an unreachable URL parses the whole configuration, then fails
# to connect: exit 1 with a JSON error, while a bad name would exit 2.
set +e
"$root/usr/bin/tessera-server" --config "$conf" health --url http://127.0.0.1:1/healthz >/dev/null 2>"$root/err"
rc=$?
set -e
[[ $rc -eq 1 ]] || fail "the example configuration was refused (exit $rc): $(cat "$root/err")"
echo "install: ok"
