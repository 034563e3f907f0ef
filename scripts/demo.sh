#!/usr/bin/env bash
# Bakes the bundled default asset (CesiumMan) and plays its walk cycle headless into out/:
# out/frame_0000.png ... and out/anim.png (animated PNG).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
mkdir -p out
build/bin/stipple-bake assets/CesiumMan/CesiumMan.glb -o out/CesiumMan.stip --points 60000
build/bin/stipple-play out/CesiumMan.stip --out out --frames 60 --fps 30 --size 640x480 --yaw -60 --stats
echo "frames in out/frame_*.png, animation in out/anim.png"
