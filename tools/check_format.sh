#!/usr/bin/env bash
# Checks every tracked C++ source (.cpp, .hpp) against the root .clang-format.
#   tools/check_format.sh        list the files clang-format would change; exit 1 if any
#   tools/check_format.sh --fix  reformat those files in place
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

fix=false
case "${1:-}" in
  "") ;;
  --fix) fix=true ;;
  *) echo "usage: tools/check_format.sh [--fix]" >&2; exit 2 ;;
esac

if ! command -v clang-format >/dev/null; then
  echo "clang-format not found: install the Debian package 'clang-format'" \
       "(tools/install_dependencies.sh does)" >&2
  exit 2
fi

differ=()
while IFS= read -r -d '' file; do
  if ! clang-format --style=file --dry-run --Werror "$file" >/dev/null 2>&1; then
    differ+=("$file")
  fi
done < <(git ls-files -z -- '*.cpp' '*.hpp')

if [ ${#differ[@]} -eq 0 ]; then
  echo "all C++ sources match .clang-format"
  exit 0
fi
if $fix; then
  clang-format --style=file -i "${differ[@]}"
  printf 'reformatted %s\n' "${differ[@]}"
  exit 0
fi
printf '%s\n' "${differ[@]}"
echo "${#differ[@]} file(s) differ from .clang-format; tools/check_format.sh --fix reformats them" >&2
exit 1
