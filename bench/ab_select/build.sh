#!/bin/bash
# A/B of the level-of-detail selection of two source trees in one process (bench/ab_select/
# main.cpp): the selection's files of each tree compiled with its own namespace
# (-Dstipple=stipple_old / stipple_new); loading, the pipelines and the frames come from NEW's
# Release build (run ./scripts/setup.sh or cmake --build build first).
#   OLD=/path/to/old/checkout bench/ab_select/build.sh     (NEW defaults to this checkout)
#   /tmp/ab_select/ab_select FILE.stip [CALLS] [FRAMES]
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
NEW=${NEW:-$(cd "$HERE/../.." && pwd)}
OLD=${OLD:?set OLD to the other tree (git worktree add /tmp/old <commit>)}
OUT=${OUT:-/tmp/ab_select}
mkdir -p "$OUT"
F="-O3 -DNDEBUG -std=c++17 -ffp-contract=off"
FILES="point_clusters_select normal_bounds point_simd point_simd_avx2 point_place_avx2 stipple_size
  thread_pool status"
for side in old new; do
  R=$([ $side = old ] && echo "$OLD" || echo "$NEW")
  for f in $FILES; do
    [ -f "$R/runtime/$f.cpp" ] || continue
    g++ $F -I"$R" -Dstipple=stipple_$side -c "$R/runtime/$f.cpp" -o "$OUT/${side}_$f.o"
  done
done
g++ $F -I"$NEW" -DSTIPPLE_SOURCE_DIR=\"$NEW\" -c "$HERE/main.cpp" -o "$OUT/main.o"
B="$NEW/build"
g++ "$OUT"/main.o "$OUT"/old_*.o "$OUT"/new_*.o -o "$OUT/ab_select" "$B/runtime/libstipple_runtime.a" \
  "$B/platform/libstipple_platform.a" "$B/anim/libstipple_anim.a" -lEGL -lGLESv2 -lOSMesa -lpthread -ldl
echo "$OUT/ab_select"
