#!/usr/bin/env bash
# Checks the self-contained wheel on a bare Debian 12: a root made by debootstrap (minbase)
# that holds only python3 and python3-venv, none of the build's libraries. In it
# (tools/check_wheel_inside.sh) pip installs the wheel into a virtual environment, and
#   - the wheel's program and gr.retarget retarget the bundled scene to the golden bytes
#     (tests/data/golden/garment_sha256.txt, dress_form);
#   - the program and the module load no library from outside the wheel but glibc, the C++
#     runtime and zlib;
#   - the wheel's extras [dask] and [ray] install, and python/tests pass against the
#     installed package (the tests read only the bundled scene, copied beside them).
# It prints the wheel's size and the time pip took to install it.
#
#   tools/check_wheel.sh [WHEEL]     without WHEEL, builds it first (tools/build_wheel.sh)
#
# Needs root (debootstrap, chroot and mounts), debootstrap, unshare and the network to a
# Debian mirror ($GR_DEBIAN_MIRROR, by default the one this machine's apt sources name for
# bookworm, else debootstrap's own) and PyPI; without root or debootstrap it exits 77,
# which CTest reports as skipped. The bare root is made once into
# $GR_WHEEL_BARE_ROOT (default build/wheel-check/bare-debian12) and copied afresh for each
# check into build/wheel-check/root, which is removed at the end.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
check_dir="$root/build/wheel-check"
bare="${GR_WHEEL_BARE_ROOT:-$check_dir/bare-debian12}"
run_root="$check_dir/root"

# The first mirror this machine's apt sources give for bookworm (deb822 and one-line files).
apt_mirror() {
  awk '/^URIs:/ { uri = $2 } /^Suites:/ { for (i = 2; i <= NF; i++) if ($i == "bookworm") print uri }' \
    /etc/apt/sources.list.d/*.sources 2>/dev/null || true
  awk '$1 == "deb" { for (i = 2; i < NF; i++) if ($i ~ /^[a-z]+:\/\//) { if ($(i + 1) == "bookworm") print $i; break } }' \
    /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null || true
}
mirror="${GR_DEBIAN_MIRROR:-}"
[ -n "$mirror" ] || mirror="$(apt_mirror | head -n 1)" || true

skip() {
  echo "skipped: $1" >&2
  exit 77
}
[ "$(id -u)" -eq 0 ] || skip "the bare-system check needs root (debootstrap, chroot, mounts)"
command -v debootstrap >/dev/null || skip "debootstrap is not installed (apt-get install debootstrap)"
command -v unshare >/dev/null || skip "unshare (util-linux) is not installed"

if [ $# -ge 1 ]; then
  wheel="$(realpath "$1")"
else
  wheel="$("$root/tools/build_wheel.sh" | tail -n 1)"
fi
[ -f "$wheel" ] || { echo "error: no wheel at $wheel" >&2; exit 2; }

# A mount left under the root would be deleted through by rm -rf: refuse instead.
remove_root() {
  if grep -q " $run_root[/ ]" /proc/mounts; then
    echo "error: something is still mounted under $run_root; not removing it" >&2
    return 1
  fi
  rm -rf "$run_root"
}

if [ ! -f "$bare/.bare-root-complete" ]; then
  rm -rf "$bare"
  mkdir -p "$(dirname "$bare")" "$check_dir"
  echo "making a bare Debian 12 root in $bare (debootstrap, a few minutes)" >&2
  debootstrap --variant=minbase --include=python3,python3-venv bookworm "$bare" ${mirror:+"$mirror"} \
    >"$check_dir/debootstrap.log" 2>&1 ||
    { tail -n 20 "$check_dir/debootstrap.log" >&2; echo "error: debootstrap failed" >&2; exit 1; }
  rm -rf "$bare"/var/cache/apt/archives/*.deb
  touch "$bare/.bare-root-complete"
fi

remove_root
cp -a "$bare" "$run_root"
trap remove_root EXIT
# What the check brings in: the wheel, the bundled scene and the Python tests at the paths
# they have in the source tree (the tests' conftest finds the scene from its own path), the
# golden digests; resolv.conf and this machine's CA certificates, for pip to reach PyPI
# through its network (a bare root has no ca-certificates package).
stage="$run_root/opt/check"
mkdir -p "$stage/scenes" "$stage/python" "$stage/tests/data/golden"
cp "$wheel" "$stage/"
cp -r "$root/scenes/dress_form" "$stage/scenes/"
cp -r "$root/python/tests" "$stage/python/"
cp "$root/tests/data/golden/garment_sha256.txt" "$stage/tests/data/golden/"
cp "$root/tools/check_wheel_inside.sh" "$stage/"
cp -L /etc/resolv.conf "$run_root/etc/resolv.conf"
environment=(PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8)
for ca in "${PIP_CERT:-}" /etc/ssl/certs/ca-certificates.crt; do
  if [ -n "$ca" ] && [ -f "$ca" ]; then
    cp -L "$ca" "$stage/network-ca.crt"
    environment+=(PIP_CERT=/opt/check/network-ca.crt)
    break
  fi
done

echo "wheel: $(basename "$wheel"), $(du -k "$wheel" | cut -f1) KiB" >&2
# In a mount namespace of its own, so the mounts end with it whatever happens; in a clean
# environment, so nothing of this machine's Python or pip set-up leaks in.
unshare --mount --propagation private /bin/bash -euc '
  mount -t proc proc "$1/proc"
  mount -t sysfs sysfs "$1/sys"
  mount --rbind /dev "$1/dev"
  root="$1"
  shift
  exec chroot "$root" /usr/bin/env -i "$@" /bin/bash /opt/check/check_wheel_inside.sh
' check "$run_root" "${environment[@]}"
