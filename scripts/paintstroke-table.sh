#!/usr/bin/env bash
# Reruns GI'98 Table 1 (paintstrokes against static extrusions, docs/paintstrokes.md): builds
# stipple-paintstroke-table and stipple_bench_paintstrokes in BUILD (default build/, the
# Release tree scripts/setup.sh makes), rewrites the table and compositing sections of docs/paintstrokes.md and the
# docs/images/paintstrokes_*.png, then runs the benchmark.
#   scripts/paintstroke-table.sh [BUILD] [-- extra stipple-paintstroke-table options]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
[ $# -gt 0 ] && shift
[ "${1:-}" = "--" ] && shift
JOBS=${JOBS:-2}
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
    cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$BUILD" --target stipple-paintstroke-table stipple_bench_paintstrokes -j"$JOBS"
mkdir -p docs/images
"$BUILD/bin/stipple-paintstroke-table" --out docs/paintstrokes.md --images docs/images --runs 5 "$@"
"$BUILD/bin/stipple_bench_paintstrokes"
