#!/usr/bin/env bash
# Builds stipple and runs every test (unit tests and headless EGL frame checks).
#   scripts/test.sh             Release build in build/
#   scripts/test.sh --sanitize  AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/
#                               (STIPPLE_SANITIZE=address,undefined; leaks inside Mesa/EGL are
#                               suppressed by tests/sanitizers/lsan.supp, set by the tests' CMake)
# Extra arguments after the mode go to ctest (e.g. -R Anim).
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ "${1:-}" == "--sanitize" ]]; then
  shift
  ./scripts/setup.sh  # the packages, and the Release stipple-bake that bakes the fixtures
  # -g1: line tables for the sanitizers' stack traces, not full debug info (less to compile
  # and link: the clean-clone CI run took 42.1 min with it, 44.7 without).
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTIPPLE_SANITIZE=address,undefined \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" \
    -DSTIPPLE_BUILD_BENCH=OFF "-DSTIPPLE_FIXTURE_BAKE=$PWD/build/bin/stipple-bake" > build-asan.log 2>&1 || { cat build-asan.log; exit 1; }
  cmake --build build-asan -j"$(nproc)" >> build-asan.log 2>&1 || { tail -50 build-asan.log; exit 1; }
  cd build-asan && ctest --output-on-failure -j2 "$@"
  exit
fi
./scripts/setup.sh
cd build && ctest --output-on-failure -j2 "$@"
