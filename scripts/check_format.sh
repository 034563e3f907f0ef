#!/usr/bin/env bash
# Checks that every C/C++ source is formatted by the repo's .clang-format (clang-format 14,
# Debian 12). Prints the files that differ and exits 1 if there is any.
# To fix: scripts/check_format.sh --fix (rewrites the files in place).
set -euo pipefail
cd "$(dirname "$0")/.."
fix=0
[[ "${1:-}" == "--fix" ]] && fix=1
cf=$(command -v clang-format-14 || command -v clang-format || true)
if [[ -z "$cf" ]]; then
  echo "check_format: clang-format not found (apt install clang-format)" >&2
  exit 1
fi
dirs=()
for d in anim runtime bake platform tools tests bench examples; do [[ -d $d ]] && dirs+=("$d"); done
mapfile -t files < <(find "${dirs[@]}" -type f \( -name '*.c' -o -name '*.cpp' -o -name '*.h' \
  -o -name '*.hpp' \) | sort)
if [[ $fix == 1 ]]; then
  "$cf" -i --style=file "${files[@]}"
  exit 0
fi
bad=0
for f in "${files[@]}"; do
  if ! "$cf" --style=file --dry-run -Werror "$f" >/dev/null 2>&1; then
    echo "not formatted: $f"
    bad=1
  fi
done
[[ $bad == 0 ]] && echo "check_format: ${#files[@]} files formatted"
exit $bad
