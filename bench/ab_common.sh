# Sourced by the in-process A/B tools' build.sh (bench/ab_kernels, bench/ab_select) after they
# set HERE (their folder) and OUT (the output folder): the two trees, the flags, and
#   ab_compile SIDE TREE FILE...   each runtime/FILE.cpp of TREE into $OUT/SIDE_FILE.o, in
#                                  namespace stipple_SIDE (files a tree lacks are skipped)
#   ab_link BINARY                 main.o and every SIDE object against NEW's Release build
NEW=${NEW:-$(cd "$HERE/../.." && pwd)}
OLD=${OLD:?set OLD to the other tree (git worktree add /tmp/old <commit>)}
mkdir -p "$OUT"
F="-O3 -DNDEBUG -std=c++17 -ffp-contract=off"
ab_compile() {
  local side=$1 tree=$2 f
  shift 2
  for f in "$@"; do
    [ -f "$tree/runtime/$f.cpp" ] || continue
    g++ $F -I"$tree" -Dstipple=stipple_$side -c "$tree/runtime/$f.cpp" -o "$OUT/${side}_$f.o"
  done
}
ab_link() {
  g++ "$OUT"/main.o "$OUT"/old_*.o "$OUT"/new_*.o -o "$OUT/$1" "$NEW/build/runtime/libstipple_runtime.a" \
    "$NEW/build/platform/libstipple_platform.a" "$NEW/build/anim/libstipple_anim.a" \
    -lEGL -lGLESv2 -lOSMesa -lpthread -ldl
  echo "$OUT/$1"
}
