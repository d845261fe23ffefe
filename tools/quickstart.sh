#!/usr/bin/env bash
# The README's two commands.
#   tools/quickstart.sh run    install, build, retarget the bundled scene into out/dress_form
#   tools/quickstart.sh test   install, build, run the whole test suite with CTest
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${GR_BUILD_DIR:-$root/build}"
jobs="$(nproc)"

"$root/tools/install_dependencies.sh"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release
fi

case "${1:-}" in
  run)
    cmake --build "$build" --target garment-retarget -j "$jobs"
    scene="$root/scenes/dress_form"
    out="$root/out/dress_form"
    "$build/app/garment-retarget" retarget \
      --garment "$scene/garment.obj" --avatar "$scene/avatar.obj" \
      --no-fit "$scene/no-fit.txt" --out "$out"
    echo "results in $out"
    ;;
  test)
    # The Python package's tests run beside CTest, in a virtual environment of the
    # system's Python that holds what they need from PyPI.
    venv="$build/python-venv"
    [ -x "$venv/bin/python" ] || /usr/bin/python3 -m venv "$venv"
    "$venv/bin/python" -m pip install -q --disable-pip-version-check -r "$root/python/requirements-test.txt"
    cmake -S "$root" -B "$build" -DGR_PYTHON=ON -DPython_EXECUTABLE="$venv/bin/python" >/dev/null
    cmake --build "$build" -j "$jobs"
    (cd "$build" && ctest --output-on-failure -j "$jobs")
    PYTHONPATH="$build/python" "$venv/bin/python" -m pytest -q -p no:cacheprovider "$root/python/tests"
    ;;
  *)
    echo "usage: $0 run|test" >&2
    exit 2
    ;;
esac
