#!/bin/bash
# A/B of the AVX2 point kernels (place, then relevance + size fused) of two source trees in one
# process, alternating run by run, on one frame's level-of-detail lists: the machine's speed
# drifts between processes far more than the differences looked for (docs/performance.md,
# thirteenth round). Each tree's kernel files are compiled with its own namespace
# (-Dstipple=stipple_old / stipple_new); loading and the frame come from NEW's Release build.
#   OLD=/path/to/old/checkout bench/ab_kernels/build.sh      (NEW defaults to this checkout)
#   /tmp/ab_kernels/ab FILE.stip [REPS] [PARTS: 1 place, 2 relevance + size, 3 both] [FLUSH_MB]
# OLD_FRAME=SizeKernelFrame for trees before the one SizeFrame (commit after 7909cf5).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
NEW=${NEW:-$(cd "$HERE/../.." && pwd)}
OLD=${OLD:?set OLD to the other tree (git worktree add /tmp/old <commit>)}
OUT=${OUT:-/tmp/ab_kernels}
mkdir -p "$OUT"
F="-O3 -DNDEBUG -std=c++17 -ffp-contract=off"
for side in old new; do
  if [ $side = old ]; then R=$OLD; X="-DFRAME=${OLD_FRAME:-SizeFrame} -DSTAGES=old_stages"
  else R=$NEW; X="-DSTAGES=new_stages"; fi
  for f in point_simd_avx2 point_place_avx2 point_simd stipple_size; do
    [ -f "$R/runtime/$f.cpp" ] || continue  # place has its own file since the fourteenth round
    g++ $F -I"$R" -Dstipple=stipple_$side -c "$R/runtime/$f.cpp" -o "$OUT/${side}_$f.o"
  done
  g++ $F -I"$R" -I"$HERE" -Dstipple=stipple_$side $X -c "$HERE/adapter.cpp" -o "$OUT/${side}_adapter.o"
done
g++ $F -I"$NEW" -I"$HERE" -DSTIPPLE_SOURCE_DIR=\"$NEW\" -c "$HERE/main.cpp" -o "$OUT/main.o"
g++ "$OUT"/main.o "$OUT"/old_*.o "$OUT"/new_*.o -o "$OUT/ab" "$NEW/build/runtime/libstipple_runtime.a" \
  "$NEW/build/platform/libstipple_platform.a" "$NEW/build/anim/libstipple_anim.a" \
  -lEGL -lGLESv2 -lOSMesa -lpthread -ldl
echo "$OUT/ab"
