#!/usr/bin/env bash
# Installs the Debian 12 packages garment-retarget builds with; does nothing when all are
# present. Runs apt-get update once, only when something is missing.
set -euo pipefail

# libatlas3-base: the CPU-independent BLAS that CHOLMOD runs on (GR_PORTABLE_BLAS).
# libopenblas0-pthread: the system's default BLAS, so the determinism tests would see it if
# the build stopped using ATLAS. libclang-rt-14-dev: libFuzzer and the sanitizers' runtimes
# for the fuzz test (clang only recommends them, and recommends are not installed).
# strace: the interrupted-run tests kill the program at each of its writes and renames.
packages=(
  build-essential cmake ninja-build python3 python3-venv python3-dev clang clang-format libclang-rt-14-dev
  libeigen3-dev libsuitesparse-dev libatlas3-base libopenblas0-pthread libsleef-dev
  libcgal-dev libopenvdb-dev libboost-iostreams-dev libfcl-dev
  catch2 libtbb-dev libcli11-dev nlohmann-json3-dev libfmt-dev libssl-dev libtinygltf-dev
  libpng-dev chromium strace
)
# Node.js and npm bundle the report page's three.js at build time and drive the browser
# tests; a machine with both from elsewhere (a newer Node.js with its own npm) keeps them.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  packages+=(nodejs npm)
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "installing: ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
