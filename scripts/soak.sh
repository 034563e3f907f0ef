#!/usr/bin/env bash
# Soak test: plays FRAMES frames (default 100000) of ASSET (default: the bundled CesiumMan baked
# with default options) headless at 64x64 with the GL error checks on, animating through the
# clip while zooming from 0.5 to 32 and back every 500 frames (the close-ups run the run-time
# refinement), and checks that the process's memory stays flat and no GL error happens.
#
#   scripts/soak.sh [FRAMES] [ASSET.stip]
#
# stipple-play --rss-every samples VmRSS every FRAMES/200 frames into OUT/rss.csv (frame,
# rss_kb, ms_per_frame); OUT/summary.txt gives RSS after warm-up (frame WARMUP) against the
# largest and smallest sample after it, GL errors and frames per second; OUT/rss.svg plots the
# curve (when python3 is there). Exits 1 if RSS grows by more than MAX_GROWTH_KB after the
# warm-up or any GL error is reported. Environment: BIN_DIR (stipple-play and stipple-bake,
# default build/bin), OUT (default out/soak), SIZE (default 64x64), WARMUP (default 1000, at most
# FRAMES/4), MAX_GROWTH_KB (default 1024).
set -euo pipefail

if [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ] || [ $# -gt 2 ]; then
    sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'
    [ $# -le 2 ] && exit 0 || exit 2
fi
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
FRAMES=${1:-100000}
BIN=${BIN_DIR:-$ROOT/build/bin}
OUT=${OUT:-$ROOT/out/soak}
SIZE=${SIZE:-64x64}
MAX_GROWTH_KB=${MAX_GROWTH_KB:-1024}
WARMUP=${WARMUP:-1000}
[ "$WARMUP" -gt $((FRAMES / 4)) ] && WARMUP=$((FRAMES / 4))
EVERY=$((FRAMES / 200 > 0 ? FRAMES / 200 : 1))
PLAY=$BIN/stipple-play
[ -x "$PLAY" ] || { echo "soak: no executable '$PLAY' (set BIN_DIR)" >&2; exit 2; }
mkdir -p "$OUT"

ASSET=${2:-}
if [ -z "$ASSET" ]; then
    ASSET=$OUT/CesiumMan.stip
    if [ ! -s "$ASSET" ]; then
        echo "soak: baking CesiumMan (default options) to $ASSET" >&2
        "$BIN/stipple-bake" "$ROOT/assets/CesiumMan/CesiumMan.glb" -o "$ASSET" >/dev/null
    fi
fi

echo "soak: $FRAMES frames of $ASSET at $SIZE, RSS every $EVERY frames" >&2
START=$(date +%s.%N)
set +e
"$PLAY" "$ASSET" --out "$OUT" --frames "$FRAMES" --fps 30 --size "$SIZE" --zoom 0.5 \
    --zoom-to 32 --zoom-period 500 --no-png --no-apng --check-gl --stats --rss-every "$EVERY" \
    >"$OUT/stats.json" 2>"$OUT/play.log"
PLAY_RC=$?
set -e
END=$(date +%s.%N)
cat "$OUT/play.log" >&2

GL_ERRORS=$(sed -n 's/.*"gl_errors": \([0-9]*\).*/\1/p' "$OUT/stats.json")
awk -F, -v warmup="$WARMUP" -v frames="$FRAMES" -v start="$START" -v end="$END" \
    -v max_growth="$MAX_GROWTH_KB" -v gl_errors="${GL_ERRORS:-missing}" -v rc="$PLAY_RC" '
    NR == 1 { next }
    { rss[$1] = $2; last = $1 }
    $1 >= warmup && base == "" { base = $2; base_frame = $1 }
    $1 >= warmup { if (lo == "" || $2 < lo) lo = $2; if (hi == "" || $2 > hi) hi = $2 }
    END {
        if (base == "") { print "soak: no RSS samples after the warm-up"; exit 1 }
        wall = end - start
        printf "frames            %d in %.1f s: %.0f frames/s (wall, with load)\n", last, wall, last / wall
        printf "rss after warm-up %d KiB (frame %d)\n", base, base_frame
        printf "rss after warm-up min %d KiB, max %d KiB, growth %d KiB (limit %d)\n", lo, hi, hi - base, max_growth
        n = split("1000 10000 25000 50000 75000 100000", at, " ")
        line = "rss at frames    "
        for (i = 1; i <= n; ++i) if (at[i] in rss) line = line sprintf(" %dk: %d", at[i] / 1000, rss[at[i]])
        print line
        printf "gl errors         %s\n", gl_errors
        ok = rc == 0 && gl_errors == "0" && hi - base <= max_growth
        printf "result            %s (stipple-play exit %d)\n", ok ? "PASS" : "FAIL", rc
        exit ok ? 0 : 1
    }' "$OUT/rss.csv" | tee "$OUT/summary.txt"
RESULT=${PIPESTATUS[0]}

if command -v python3 >/dev/null; then
    python3 - "$OUT/rss.csv" "$OUT/rss.svg" <<'PY' || true
import sys
rows = [l.split(",") for l in open(sys.argv[1]).read().split()[1:]]
xs = [int(r[0]) for r in rows]
ys = [int(r[1]) / 1024 for r in rows]
lo, hi = min(ys) - 1, max(ys) + 1
w, h, m = 640, 240, 50
pts = " ".join(f"{m + (x / xs[-1]) * (w - 2 * m):.1f},{h - m - (y - lo) / (hi - lo) * (h - 2 * m):.1f}"
               for x, y in zip(xs, ys))
svg = f"""<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11">
<rect width="{w}" height="{h}" fill="white"/>
<polyline points="{pts}" fill="none" stroke="black"/>
<line x1="{m}" y1="{h - m}" x2="{w - m}" y2="{h - m}" stroke="gray"/>
<line x1="{m}" y1="{m}" x2="{m}" y2="{h - m}" stroke="gray"/>
<text x="{m}" y="{h - m + 15}">0</text><text x="{w - m}" y="{h - m + 15}" text-anchor="end">{xs[-1]} frames</text>
<text x="{m - 4}" y="{h - m}" text-anchor="end">{lo:.1f}</text><text x="{m - 4}" y="{m + 4}" text-anchor="end">{hi:.1f}</text>
<text x="{w / 2}" y="{m - 15}" text-anchor="middle">stipple-play RSS (MiB) over a soak run</text>
</svg>
"""
open(sys.argv[2], "w").write(svg)
PY
fi
exit "$RESULT"
