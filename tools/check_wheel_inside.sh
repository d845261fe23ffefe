#!/bin/bash
# The wheel check inside the bare Debian 12 root (tools/check_wheel.sh copies this to
# /opt/check with the wheel, the bundled scene, python/tests and the golden digests, and runs
# it under chroot). Exits non-zero at the first check that fails.
set -euo pipefail

check=/opt/check
venv=/opt/venv
wheel="$(ls "$check"/garment_retarget-*.whl)"
golden="$(awk '$1 == "dress_form" { print $2 }' "$check/tests/data/golden/garment_sha256.txt")"
scene="$check/scenes/dress_form"
fail() {
  echo "FAILED: $1" >&2
  exit 1
}
# Runs a command and sets `seconds` to its wall time.
timed() {
  local start
  start=$(date +%s.%N)
  "$@"
  seconds=$(awk -v start="$start" -v end="$(date +%s.%N)" 'BEGIN { printf "%.1f", end - start }')
}

echo "system: $(. /etc/os-release && echo "$PRETTY_NAME"), $(python3 --version), $(dpkg-query -W | wc -l) Debian packages"
# None of the build's libraries (GMP and OpenSSL are in any Debian 12, for apt and Python's
# ssl module; the wheel brings its own and loads those).
for package in libcholmod3 libatlas3-base libblas3 libopenblas0 libopenblas0-pthread libgfortran5 libgomp1 libtbb12 \
  libopenvdb10.0 libboost-iostreams1.74.0 libblosc1 libmpfr6 libfcl0.7 libsleef3 libfmt9 libpng16-16; do
  if dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    fail "$package is installed: the root is not bare"
  fi
done

python3 -m venv "$venv"
timed "$venv/bin/pip" install -q --disable-pip-version-check "$wheel"
echo "pip install of the wheel (with NumPy from PyPI): $seconds s"

package="$("$venv/bin/python" -c 'import garment_retarget, os; print(os.path.dirname(garment_retarget.__file__))')"
[[ "$package" == "$venv"/* ]] || fail "garment_retarget imported from $package, not the installed wheel"
program="$package/garment-retarget"
echo "installed: $(du -sk "$package" "$package.libs" | awk '{ k += $1 } END { printf "%.1f", k / 1024 }') MiB (the package and its libraries)"

# Every library the program and the module load comes from the wheel, but for glibc's, the
# C++ runtime's and zlib (which the manylinux policy lets a wheel take from the system).
for elf in "$program" "$package"/_core*.so; do
  libraries="$(ldd "$elf")"
  if grep -q "not found" <<<"$libraries"; then
    fail "$(basename "$elf") misses libraries: $(grep 'not found' <<<"$libraries" | tr -s ' \t' ' ')"
  fi
  outside="$(awk '$2 == "=>" { print $3 }' <<<"$libraries" | grep -v "^$venv/" |
    grep -Ev '/(libc|libm|libstdc\+\+|libgcc_s|libpthread|libdl|librt|ld-linux-x86-64|libz)\.so' || true)"
  [ -z "$outside" ] || fail "$(basename "$elf") loads libraries from outside the wheel: $outside"
  echo "$(basename "$elf"): $(grep -c "$venv/" <<<"$libraries") libraries from the wheel, the rest glibc, the C++ runtime and zlib"
done

# The bundled scene, by the program and in Python, to the golden bytes.
"$program" retarget --garment "$scene/garment.obj" --avatar "$scene/avatar.obj" \
  --no-fit "$scene/no-fit.txt" --quiet --out /tmp/dress_form_cli
digest="$(sha256sum /tmp/dress_form_cli/garment.obj | cut -d' ' -f1)"
[ "$digest" = "$golden" ] || fail "the program wrote $digest, the golden digest is $golden"
echo "program: the bundled scene's garment.obj has the golden digest $digest"
"$venv/bin/python" - "$scene" <<'EOF'
import sys
from pathlib import Path

import garment_retarget as gr

scene = Path(sys.argv[1])
result = gr.retarget(scene / "garment.obj", scene / "avatar.obj", out="/tmp/dress_form_python",
                     no_fit=scene / "no-fit.txt", quiet=True)
assert result["status"] == "certified", result["status"]
EOF
digest="$(sha256sum /tmp/dress_form_python/garment.obj | cut -d' ' -f1)"
[ "$digest" = "$golden" ] || fail "gr.retarget wrote $digest, the golden digest is $golden"
echo "gr.retarget: certified, the golden digest $digest"

# The extras, from the installed wheel's metadata, and the Python tests against the installed
# package (Ray's cluster test too, with the [ray] extra).
timed "$venv/bin/pip" install -q --disable-pip-version-check "$wheel[dask,ray,test]"
echo "pip install of the extras [dask,ray,test]: $seconds s"
cd "$check"
"$venv/bin/python" -m pytest -q -p no:cacheprovider -rs python/tests
