#!/usr/bin/env bash
# Renders the pictures the README shows into docs/images/ (after ./scripts/setup.sh):
#   walk.png       one frame of CesiumMan's walk (640x480)
#   walk_anim.png  the walk as an animated PNG (320x240, 30 frames)
#   zoom_anim.png  a close-up from zoom 1 to 16 (240x180, 24 frames): the hierarchy continued
#                  at run time keeps the tone (docs/tone.md)
#   fur_anim.png   CesiumMan with 3,000 paintstroke hairs walking (320x240, 30 frames; GI'98)
#   torus.png      the sketch's torus of 1,250 strokes (320x240)
#   style_*.png    the looks of docs/styles.md (240x180)
#   particles_*.png  the particle styles of docs/particles.md (320x240) and a walk (240x180)
#   three_walkers.png  examples/three_walkers' frame (built against an install of build/)
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
"$BIN/stipple-bake" assets/CesiumMan/CesiumMan.glb -o "$TMP/fur.stip" --points 20000 --fur 3000 \
    --quiet
"$BIN/stipple-play" "$TMP/fur.stip" --out "$TMP/fur" --frames 30 --fps 30 --size 320x240 \
    --yaw -60 --no-png
cp "$TMP/fur/anim.png" "$OUT/fur_anim.png"
"$BIN/stipple-bake" assets/torus.obj -o "$TMP/torus.stip" --points 20000 --fur 1250 \
    --fur-length 0.35 --fur-radius 0.025 --fur-curl 2 --quiet
"$BIN/stipple-play" "$TMP/torus.stip" --out "$TMP/torus" --frames 1 --size 320x240 --pitch 35 \
    --no-apng
cp "$TMP/torus/frame_0000.png" "$OUT/torus.png"
# The looks (docs/styles.md): style_classic.png ... style_transparent.png (240x180).
"$BIN/stipple-bake" assets/CesiumMan/CesiumMan.glb -o "$TMP/man30k.stip" --points 30000 --quiet
for style in classic toon colour transparent; do
    "$BIN/stipple-play" "$TMP/man30k.stip" --out "$TMP/style_$style" --frames 1 --size 240x180 \
        --yaw -60 --time 0.66 --style "$style" --no-apng
    cp "$TMP/style_$style/frame_0000.png" "$OUT/style_$style.png"
done
"$BIN/stipple-bake" assets/looks/looks_scene.gltf -o "$TMP/scene.stip" --points 20000 --looks --quiet
for style in toon colour transparent; do
    "$BIN/stipple-play" "$TMP/scene.stip" --out "$TMP/scene_$style" --frames 1 --size 240x180 \
        --pitch 20 --style "$style" --no-apng
    cp "$TMP/scene_$style/frame_0000.png" "$OUT/style_scene_$style.png"
done
"$BIN/stipple-bake" assets/CesiumMan/CesiumMan.glb -o "$TMP/man_looks.stip" --points 30000 --looks \
    --quiet
"$BIN/stipple-play" "$TMP/man_looks.stip" --out "$TMP/man_colour" --frames 1 --size 240x180 \
    --yaw -60 --time 0.66 --style colour --no-apng
cp "$TMP/man_colour/frame_0000.png" "$OUT/style_looks_colour.png"
# View-dependent particles (docs/particles.md): particles_*.png, the eight GI'01 styles
# (320x240), and particles_anim.png, painterly-long walking (240x180, 30 frames).
for style in painterly-long painterly-dab sketch cartoon graftals charcoal two-tone ink; do
    "$BIN/stipple-play" "$TMP/man30k.stip" --out "$TMP/particles_$style" --frames 1 \
        --size 320x240 --yaw -60 --time 0.66 --zoom 1.6 --style "$style" --no-apng
    cp "$TMP/particles_$style/frame_0000.png" "$OUT/particles_$style.png"
done
"$BIN/stipple-play" "$TMP/man30k.stip" --out "$TMP/particles_anim" --frames 30 --fps 30 \
    --size 240x180 --yaw -60 --zoom 1.4 --style painterly-long --no-png
cp "$TMP/particles_anim/anim.png" "$OUT/particles_anim.png"
cmake --install build --prefix "$TMP/prefix" > /dev/null
cmake -S examples/three_walkers -B "$TMP/example" -DCMAKE_PREFIX_PATH="$TMP/prefix" \
    -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$TMP/example" > /dev/null
"$TMP/example/three_walkers" "$TMP/three_walkers.ppm" 0.5
python3 - "$TMP/three_walkers.ppm" "$OUT/three_walkers.png" <<'PY'
import struct, sys, zlib  # PPM (P6) to PNG, no dependencies
data = open(sys.argv[1], 'rb').read()
magic, size, depth, pixels = data.split(b'\n', 3)
w, h = map(int, size.split())
raw = b''.join(b'\0' + pixels[y * w * 3:(y + 1) * w * 3] for y in range(h))
def chunk(kind, body):
    return struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body))
open(sys.argv[2], 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0))
                              + chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))
PY
ls -l "$OUT"
