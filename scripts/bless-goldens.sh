#!/usr/bin/env bash
# Re-renders every golden frame of tests/golden/cases.txt with the current build and
# overwrites tests/golden/*.png. Run only after an intended visual change; review the
# pictures and commit them together with that change.
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
grep -v '^#' tests/golden/cases.txt | while IFS='|' read -r name input bake play; do
  name=$(echo $name)
  build/bin/stipple-bake $input -o "$work/$name.stip" $bake --quiet
  build/bin/stipple-play "$work/$name.stip" --out "$work/$name" --frames 1 --no-apng $play
  cp "$work/$name/frame_0000.png" "tests/golden/$name.png"
  echo "blessed tests/golden/$name.png"
done
