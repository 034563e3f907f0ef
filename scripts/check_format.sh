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
# One clang-format run over every file (a process per file costs seconds): its warnings name
# each file that differs, once per differing line.
report=$("$cf" --style=file --dry-run "${files[@]}" 2>&1 >/dev/null || true)
mapfile -t bad < <(grep -oE '^[^:]+\.(c|cpp|h|hpp):[0-9]+:[0-9]+: (warning|error)' <<<"$report" |
  cut -d: -f1 | sort -u)
if [[ ${#bad[@]} -gt 0 ]]; then
  printf 'not formatted: %s\n' "${bad[@]}"
  echo "check_format: run scripts/check_format.sh --fix" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files formatted"
