#!/usr/bin/env bash
# Runs one libFuzzer target (docs/fuzzing.md) for SECONDS seconds:
#   scripts/fuzz.sh TARGET SECONDS [extra libFuzzer flags...]
#   TARGET: asset_load | asset_frame | gltf_import | mesh_import
# Configures build-fuzz with clang-14 (STIPPLE_FUZZ=ON, STIPPLE_FUZZ_SKIP_CRC=ON), builds
# fuzz_TARGET, grows a working corpus in build-fuzz/corpus/TARGET (seeded from the committed
# tests/fuzz/corpus/TARGET) and prints executions, exec/s, cov, ft and any crash file.
# Needs clang-14 and libclang-rt-14-dev (not part of scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ $# -lt 2 ]]; then
  echo "usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags...]" >&2
  exit 2
fi
target=$1 seconds=$2
shift 2
[[ -f tests/fuzz/fuzz_${target}.cpp ]] || { echo "fuzz.sh: no target '$target'" >&2; exit 2; }
jobs=${FUZZ_BUILD_JOBS:-$(nproc)}
if [[ ! -f build-fuzz/CMakeCache.txt ]]; then
  CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSTIPPLE_FUZZ=ON -DSTIPPLE_FUZZ_SKIP_CRC=ON -DSTIPPLE_WERROR=OFF \
    -DSTIPPLE_BUILD_TESTS=OFF -DSTIPPLE_BUILD_BENCH=OFF > build-fuzz.log 2>&1 ||
    { cat build-fuzz.log; exit 1; }
fi
cmake --build build-fuzz -j"$jobs" --target "fuzz_${target}" >> build-fuzz.log 2>&1 ||
  { tail -50 build-fuzz.log; exit 1; }
corpus=build-fuzz/corpus/$target artifacts=build-fuzz/artifacts/$target
mkdir -p "$corpus" "$artifacts"
cp -n tests/fuzz/corpus/"$target"/* "$corpus"/ 2>/dev/null || true
log=build-fuzz/fuzz-$target.log
status=0
ASAN_OPTIONS=${ASAN_OPTIONS:-allocator_may_return_null=1} \
  UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
  build-fuzz/bin/fuzz_"$target" "$corpus" -dict=tests/fuzz/"$target".dict \
  -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
  -artifact_prefix="$artifacts"/ "$@" > "$log" 2>&1 || status=$?
# libFuzzer's last status line: "#N DONE cov: C ft: F corp: ... exec/s: E ..."
last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
echo "target:     $target ($seconds s, log $log)"
echo "executions: $(grep -oE '^stat::number_of_executed_units: +[0-9]+' "$log" | awk '{print $2}')"
echo "exec/s:     $(grep -oE '^stat::average_exec_per_sec: +[0-9]+' "$log" | awk '{print $2}')"
echo "cov:        $(grep -oE 'cov: [0-9]+' <<<"$last" | awk '{print $2}')"
echo "ft:         $(grep -oE 'ft: [0-9]+' <<<"$last" | awk '{print $2}')"
crash=$(grep -oE "Test unit written to [^ ]+" "$log" | awk '{print $5}' || true)
if [[ -n "$crash" ]]; then
  echo "finding:    $crash"
  grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error)' "$log" | head -5
else
  echo "finding:    none"
fi
exit "$status"
