#!/usr/bin/env bash
# Builds stipple and runs every test (unit tests and headless EGL frame checks).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cd build && ctest --output-on-failure -j2
