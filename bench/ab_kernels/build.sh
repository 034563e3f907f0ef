#!/bin/bash
# A/B of the AVX2 point kernels (place, then relevance + size fused) of two source trees in one
# process, alternating run by run, on one frame's level-of-detail lists: the machine's speed
# drifts between processes far more than the differences looked for (docs/performance.md,
# thirteenth round). Each tree's kernel files are compiled with its own namespace
# (-Dstipple=stipple_old / stipple_new); loading and the frame come from NEW's Release build.
#   OLD=/path/to/old/checkout bench/ab_kernels/build.sh      (NEW defaults to this checkout)
#   /tmp/ab_kernels/ab FILE.stip [REPS] [PARTS: 1 place, 2 relevance + size, 3 both] [FLUSH_MB]
# NEW_RELEVANCE_SIZE=relevance_size_avx512 times NEW's AVX-512 fused kernel instead of its AVX2 one.
# OLD_FRAME=SizeKernelFrame for trees before the one SizeFrame (commit after 7909cf5).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${OUT:-/tmp/ab_kernels}
source "$HERE/../ab_common.sh"
for side in old new; do
  if [ $side = old ]; then R=$OLD; X="-DFRAME=${OLD_FRAME:-SizeFrame} -DSTAGES=old_stages"
  else R=$NEW; X="-DSTAGES=new_stages -DRELEVANCE_SIZE=${NEW_RELEVANCE_SIZE:-relevance_size_avx2}"; fi
  # (place has its own file since the fourteenth round)
  ab_compile $side "$R" point_simd_avx2 point_simd_avx512 point_place_avx2 point_simd stipple_size
  g++ $F -I"$R" -I"$HERE" -Dstipple=stipple_$side $X -c "$HERE/adapter.cpp" -o "$OUT/${side}_adapter.o"
done
g++ $F -I"$NEW" -I"$HERE" -DSTIPPLE_SOURCE_DIR=\"$NEW\" -c "$HERE/main.cpp" -o "$OUT/main.o"
ab_link ab
