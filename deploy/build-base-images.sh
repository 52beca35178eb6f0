#!/usr/bin/env bash
# Makes the local Docker images debian:12 and debian:12-slim, which
# deploy/Dockerfile builds FROM, out of Debian's own archive, for machines
# that reach Debian's mirrors but no container registry (Docker Hub, where
# `docker pull debian:12` goes, is not reachable from them). Nothing is
# downloaded from anywhere but the Debian mirror, and debootstrap checks
# what it fetches against the host's Debian archive keyring.
#
# Each image is made the way Debian's official images are (debuerreotype):
# a minbase debootstrap of bookworm, updated from bookworm-updates and
# bookworm-security, apt set up for containers (no cache kept, no
# translations, no recommends of suggests), apt lists removed, CMD bash;
# the slim one also tells dpkg to leave out documentation, manuals and
# locales (copyright files kept), and deletes those already installed.
#
# Idempotent: an image that already exists is left alone (FORCE=1 remakes
# both); when both exist nothing is fetched. Needs root, docker and
# debootstrap (apt-get install docker.io debootstrap).
#
# Usage: deploy/build-base-images.sh
#   MIRROR=http://deb.debian.org/debian           where debootstrap and apt fetch from
#   SECURITY_MIRROR=http://deb.debian.org/debian-security
set -euo pipefail

suite=bookworm
mirror=${MIRROR:-http://deb.debian.org/debian}
security_mirror=${SECURITY_MIRROR:-http://deb.debian.org/debian-security}
full=debian:12
slim=debian:12-slim
say() { echo "build-base-images: $*" >&2; }

have() { docker image inspect "$1" >/dev/null 2>&1; }
wanted=()
for tag in "$full" "$slim"; do
  if [[ ${FORCE:-0} != 1 ]] && have "$tag"; then
    say "$tag exists ($(docker image inspect -f '{{.Id}}' "$tag" | cut -c1-19)); left alone"
  else
    wanted+=("$tag")
  fi
done
((${#wanted[@]})) || exit 0

[[ $(id -u) == 0 ]] || { say "must run as root (debootstrap and chroot)"; exit 1; }
for tool in docker debootstrap chroot; do
  command -v "$tool" >/dev/null || { say "no $tool; on Debian: apt-get install docker.io debootstrap"; exit 1; }
done

work=$(mktemp -d /var/tmp/tessera-base.XXXXXX)
root=$work/rootfs
# Unmount whatever is still mounted inside (our /proc; debootstrap's own if it
# failed half-way), deepest first, before removing anything; and never cross
# into another file system while removing.
cleanup() {
  local m
  for m in $(awk -v r="$root/" 'index($2, r) == 1 {print $2}' /proc/mounts | sort -r); do
    umount "$m" || umount -l "$m" || true
  done
  if awk -v r="$root/" 'index($2, r) == 1 {found=1} END {exit !found}' /proc/mounts; then
    say "left $work in place: something is still mounted in it"
  else
    rm -rf --one-file-system "$work"
  fi
}
trap cleanup EXIT

say "debootstrap --variant=minbase $suite from $mirror into $root"
debootstrap --variant=minbase --keyring=/usr/share/keyrings/debian-archive-keyring.gpg \
  "$suite" "$root" "$mirror" >"$work/debootstrap.log" 2>&1 \
  || { tail -20 "$work/debootstrap.log" >&2; say "debootstrap failed"; exit 1; }

say "apt sources: $suite, $suite-updates ($mirror), $suite-security ($security_mirror)"
rm -f "$root/etc/apt/sources.list"
cat >"$root/etc/apt/sources.list.d/debian.sources" <<EOF
Types: deb
URIs: $mirror
Suites: $suite $suite-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb
URIs: $security_mirror
Suites: $suite-security
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF

# apt and dpkg set up for containers, as in Debian's official images.
# No daemon may start inside the build (policy-rc.d), ...
printf '#!/bin/sh\nexit 101\n' >"$root/usr/sbin/policy-rc.d"
chmod 0755 "$root/usr/sbin/policy-rc.d"
# ... no .deb kept after installing, no package cache, ...
cat >"$root/etc/apt/apt.conf.d/docker-clean" <<'EOF'
DPkg::Post-Invoke { "rm -f /var/cache/apt/archives/*.deb /var/cache/apt/archives/partial/*.deb /var/cache/apt/*.bin || true"; };
APT::Update::Post-Invoke { "rm -f /var/cache/apt/archives/*.deb /var/cache/apt/archives/partial/*.deb /var/cache/apt/*.bin || true"; };
Dir::Cache::pkgcache "";
Dir::Cache::srcpkgcache "";
EOF
# ... no translations of package descriptions, lists kept compressed, ...
echo 'Acquire::Languages "none";' >"$root/etc/apt/apt.conf.d/docker-no-languages"
printf 'Acquire::GzipIndexes "true";\nAcquire::CompressionTypes::Order:: "gz";\n' \
  >"$root/etc/apt/apt.conf.d/docker-gzip-indexes"
# ... and packages only suggested are removable.
echo 'Apt::AutoRemove::SuggestsImportant "false";' >"$root/etc/apt/apt.conf.d/docker-autoremove-suggests"
# dpkg: no fsync per file (a container layer is written once).
echo 'force-unsafe-io' >"$root/etc/dpkg/dpkg.cfg.d/docker-apt-speedup"

say "applying $suite-updates and $suite-security"
mount -t proc proc "$root/proc"
chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get -y -qq upgrade >"$work/upgrade.log" 2>&1 \
  || { tail -20 "$work/upgrade.log" >&2; say "apt-get upgrade failed"; exit 1; }
chroot "$root" apt-get clean
umount "$root/proc"

# What a fresh container should not inherit from this machine or the bootstrap.
tidy() {
  rm -rf "$root"/var/lib/apt/lists/* "$root"/var/cache/apt/*.bin "$root"/var/cache/apt/archives/*.deb \
    "$root"/var/cache/debconf/*-old "$root"/var/lib/dpkg/*-old "$root"/var/log/* "$root"/tmp/* "$root"/var/tmp/*
  mkdir -p "$root/var/lib/apt/lists/partial"
  : >"$root/etc/machine-id"
  : >"$root/etc/hostname"
  : >"$root/etc/resolv.conf"  # docker mounts the container's own over it
}
tidy

import() {
  local tag=$1
  say "importing $root as $tag"
  tar --numeric-owner --xattrs -C "$root" -c . \
    | docker import --change 'CMD ["bash"]' \
        --message "debootstrap --variant=minbase $suite $mirror (deploy/build-base-images.sh)" - "$tag" >/dev/null
  say "$tag: $(docker image inspect -f '{{.Id}} {{.Size}}' "$tag" | awk '{printf "%s, %.1f MB", substr($1,1,19), $2/1e6}')"
}
[[ " ${wanted[*]} " == *" $full "* ]] && import "$full"

if [[ " ${wanted[*]} " == *" $slim "* ]]; then
  say "slimming: no documentation, manuals or locales (copyright files kept)"
  cat >"$root/etc/dpkg/dpkg.cfg.d/docker" <<'EOF'
# Debian's slim images: leave out what a container does not read.
path-exclude /usr/share/doc/*
path-include /usr/share/doc/*/copyright
path-exclude /usr/share/man/*
path-exclude /usr/share/groff/*
path-exclude /usr/share/info/*
path-exclude /usr/share/lintian/*
path-exclude /usr/share/linda/*
path-exclude /usr/share/locale/*
path-include /usr/share/locale/locale.alias
EOF
  find "$root/usr/share/doc" -mindepth 1 -not -name copyright -not -type d -delete
  find "$root/usr/share/doc" -mindepth 1 -type d -empty -delete
  rm -rf "$root"/usr/share/{man,groff,info,lintian,linda}/*
  find "$root/usr/share/locale" -mindepth 1 -maxdepth 1 -not -name locale.alias -exec rm -rf {} +
  import "$slim"
fi
