#!/bin/bash
# A/B of the level-of-detail selection of two source trees in one process (bench/ab_select/
# main.cpp): the selection's files of each tree compiled with its own namespace
# (-Dstipple=stipple_old / stipple_new); loading, the pipelines and the frames come from NEW's
# Release build (run ./scripts/setup.sh or cmake --build build first).
#   OLD=/path/to/old/checkout bench/ab_select/build.sh     (NEW defaults to this checkout)
#   /tmp/ab_select/ab_select FILE.stip [CALLS] [FRAMES]
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${OUT:-/tmp/ab_select}
source "$HERE/../ab_common.sh"
FILES="point_clusters_select normal_bounds point_simd point_simd_avx2 point_place_avx2 stipple_size
  thread_pool status"
ab_compile old "$OLD" $FILES
ab_compile new "$NEW" $FILES
g++ $F -I"$NEW" -DSTIPPLE_SOURCE_DIR=\"$NEW\" -c "$HERE/main.cpp" -o "$OUT/main.o"
ab_link ab_select
