#!/usr/bin/env bash
# Renders the pictures the README shows into docs/images/ (after ./scripts/setup.sh):
#   walk.png       one frame of CesiumMan's walk (640x480)
#   walk_anim.png  the walk as an animated PNG (320x240, 30 frames)
#   zoom_anim.png  a close-up from zoom 1 to 16 (240x180, 24 frames): the hierarchy continued
#                  at run time keeps the tone (docs/tone.md)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=build/bin
OUT=docs/images
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT"
"$BIN/stipple-bake" assets/CesiumMan/CesiumMan.glb -o "$TMP/man60k.stip" --points 60000 --quiet
"$BIN/stipple-bake" assets/CesiumMan/CesiumMan.glb -o "$TMP/man.stip" --quiet
"$BIN/stipple-play" "$TMP/man60k.stip" --out "$TMP/walk" --frames 1 --time 0.4 --yaw -60 --no-apng
cp "$TMP/walk/frame_0000.png" "$OUT/walk.png"
"$BIN/stipple-play" "$TMP/man60k.stip" --out "$TMP/walk_anim" --frames 30 --fps 30 --size 320x240 \
    --yaw -60 --no-png
cp "$TMP/walk_anim/anim.png" "$OUT/walk_anim.png"
"$BIN/stipple-play" "$TMP/man.stip" --out "$TMP/zoom" --frames 24 --fps 12 --size 240x180 \
    --yaw -30 --pitch 10 --zoom 1 --zoom-to 16 --no-png --no-silhouettes
cp "$TMP/zoom/anim.png" "$OUT/zoom_anim.png"
ls -l "$OUT"
