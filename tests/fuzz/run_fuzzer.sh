#!/usr/bin/env bash
# Builds the parser fuzzer with clang (libFuzzer + AddressSanitizer) and runs it for a
# fixed time on the seed corpus. A crash is copied into tests/fuzz/regressions/, which
# the regular test suite replays, and fails this test.
#   run_fuzzer.sh BUILD_DIR SECONDS
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$1/fuzz"
seconds="$2"
mkdir -p "$build/corpus" "$build/artifacts"

binary="$build/fuzz_parsers"
sources=("$here/fuzz_parsers.cpp" "$root"/core/io/*.cpp "$root"/core/mesh/*.cpp
         "$root"/core/common/*.cpp)
newest_source="$(ls -t "${sources[@]}" "$root"/core/io/*.hpp | head -n 1)"
if [ ! -x "$binary" ] || [ "$newest_source" -nt "$binary" ]; then
  clang++ -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -I"$root" -isystem /usr/include/eigen3 -DGR_VERSION='"fuzz"' "${sources[@]}" -lfmt -ltinygltf -o "$binary"
fi
cp -n "$here"/corpus/* "$build/corpus/" 2>/dev/null || true
# Crashes of earlier runs were copied into regressions/ already; this run reports its own.
rm -f "$build"/artifacts/*
status=0
"$binary" "$build/corpus" -max_total_time="$seconds" -max_len=4096 -timeout=5 \
  -artifact_prefix="$build/artifacts/" -print_final_stats=1 || status=$?
for crash in "$build"/artifacts/*; do
  [ -e "$crash" ] || continue
  cp "$crash" "$here/regressions/"
  echo "fuzzer found a failing input, kept as tests/fuzz/regressions/$(basename "$crash")" >&2
  status=1
done
exit $status
