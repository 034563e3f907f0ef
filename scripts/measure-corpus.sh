#!/usr/bin/env bash
# Measures the asset corpus with stipple-measure and prints markdown tables (docs/measure.md):
#   a. tone under zoom, b. screen-space evenness, c. tone under stretch (the tube's "sweep"
#   clip), d. coherence (CesiumMan's walk, and a zoom sweep 1 -> 16).
#
#   scripts/measure-corpus.sh BIN_DIR OUT_DIR > table.md
#
# BIN_DIR holds stipple-bake and stipple-play (any version: a player without --mask-out gets
# its masks from a second "paper" frame, --tone 0 --background 808080, same camera).
# MEASURE=path/to/stipple-measure (default BIN_DIR/stipple-measure); JOBS=N parallel renders
# (default: the number of CPUs); REUSE=1 measures the renders already in OUT_DIR again
# without baking or rendering; SMALL_YAWS=N adds table a2, zoom 0.25 from N yaws (0, 360/N,
# ...): mean and range of the views (few-dot noise; docs/tone.md, "Small objects"). Every
# asset is baked with default options from assets/ (the tube from the checked-in,
# regenerated stretch_tube.gltf). Progress goes to stderr.
set -euo pipefail

if [ $# -ne 2 ] || [ "$1" = "-h" ] || [ "$1" = "--help" ]; then
    sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'
    [ $# -eq 2 ] && exit 0 || exit 2
fi
BIN=$(cd "$1" && pwd)
mkdir -p "$2"
OUT=$(cd "$2" && pwd)
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
MEASURE=${MEASURE:-$BIN/stipple-measure}
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}
BAKE=$BIN/stipple-bake
PLAY=$BIN/stipple-play
for tool in "$BAKE" "$PLAY" "$MEASURE"; do
    [ -x "$tool" ] || { echo "measure-corpus: no executable '$tool'" >&2; exit 1; }
done
HAS_MASK=0
if "$PLAY" --help | grep -q -- '--mask-out'; then HAS_MASK=1; fi
START=$(date +%s)
log() { echo "measure-corpus: [$(( $(date +%s) - START ))s] $*" >&2; }

# name | file under assets/ | extra camera options (the tube shows its "rest" clip)
CORPUS="CesiumMan|CesiumMan/CesiumMan.glb|
RiggedFigure|RiggedFigure/RiggedFigure.glb|
RiggedSimple|RiggedSimple/RiggedSimple.glb|
SimpleSkin|SimpleSkin/SimpleSkin.gltf|
stretch_tube|stretch_tube/stretch_tube.gltf|--clip rest
bunny|StanfordBunny/stanford-bunny.obj|
horse|Horse/horse.ply|
teapot.obj|UtahTeapot/teapot.obj|
teapot.stl|UtahTeapot/utah_teapot_solid.stl|
spot|Spot/spot_triangulated.obj|"
NAMES=$(echo "$CORPUS" | cut -d'|' -f1)
camera_of() { echo "$CORPUS" | awk -F'|' -v n="$1" '$1 == n { print $3 }'; }

ZOOMS="0.25 0.5 1 2 4 8 16"
TARGETS="0.1 0.3 0.6"
HIGH_TARGETS="0.8 0.9 1.0"
BASE="--size 640x480 --no-silhouettes --no-apng"
TUBE_VIEW="--size 960x1440 --zoom 0.4 --clip sweep --tone 0.3 --no-silhouettes --no-apng"
SWEEP_TIMES="0 0.5 1 1.5 1.999"  # scale = 0.5 + t; the clip loops at t = 2
SWEEP_FRAMES=150
SMALL_YAWS=${SMALL_YAWS:-0}
small_yaw() { awk -v k="$1" -v n="$SMALL_YAWS" 'BEGIN { printf "%g", 360 * k / n }'; }

# ---- jobs: one per line, "kind<TAB>dir<TAB>asset.stip<TAB>options" ------------------------
# ink:   the measured render (with --mask-out when the player has it);
# paper: the legacy mask render, only for players without --mask-out.
run_job() {
    local kind dir stip opts
    IFS=$'\t' read -r kind dir stip opts <<< "$1"
    # shellcheck disable=SC2086
    [ "$kind" = bake ] || mkdir -p "$dir"
    case "$kind" in
        ink)
            if [ "$HAS_MASK" = 1 ]; then opts="$opts --mask-out"; fi
            "$PLAY" "$stip" --out "$dir" $opts > /dev/null ;;
        paper)
            "$PLAY" "$stip" --out "$dir" $opts --tone 0 --background 808080 > /dev/null ;;
        bake)
            "$BAKE" "$dir" -o "$stip" $opts > "$stip.json" 2> "$stip.log" ;;
    esac || { echo "measure-corpus: failed: $1" >&2; exit 1; }
}
export -f run_job
export PLAY BAKE HAS_MASK
run_jobs() {  # reads job lines on stdin
    tr '\n' '\0' | xargs -0 -r -n1 -P "$JOBS" bash -c 'run_job "$1"' _
}
JOBLIST=$OUT/jobs.txt
: > "$JOBLIST"
job() { printf '%s\t%s\t%s\t%s\n' "$@" >> "$JOBLIST"; }
# An ink render and, for old players, the paper render whose frames become its masks.
render() {  # dir stip options (camera options first; paper gets the same)
    local dir=$1 stip=$2 camera=$3 ink=$4
    job ink "$dir" "$stip" "$camera $ink"
    if [ "$HAS_MASK" = 0 ]; then job paper "$dir.paper" "$stip" "$camera"; fi
}

R=$OUT/render
if [ "${REUSE:-0}" != 1 ]; then
# ---- bake ---------------------------------------------------------------------------------
log "baking $(echo "$NAMES" | wc -l) assets + 2 tubes with $BAKE (masks: $([ $HAS_MASK = 1 ] && echo --mask-out || echo paper frames))"
rm -rf "$OUT/render"
mkdir -p "$OUT/stip" "$OUT/render"
{
    while IFS='|' read -r name file _; do
        printf 'bake\t%s\t%s\t%s\n' "$ROOT/assets/$file" "$OUT/stip/$name.stip" ""
    done <<< "$CORPUS"
    for n in 20000 100000; do
        printf 'bake\t%s\t%s\t%s\n' "$ROOT/assets/stretch_tube/stretch_tube.gltf" \
            "$OUT/stip/tube_$n.stip" "--points $n"
    done
} | run_jobs

# ---- render -------------------------------------------------------------------------------
for name in $NAMES; do
    stip=$OUT/stip/$name.stip
    cam=$(camera_of "$name")
    for z in $ZOOMS; do
        # One paper render per zoom serves every target.
        if [ "$HAS_MASK" = 0 ]; then job paper "$R/$name/mask_z$z" "$stip" "$BASE $cam --zoom $z"; fi
        for t in $TARGETS; do
            dots=""
            [ "$t" = 0.3 ] && { [ "$z" = 1 ] || [ "$z" = 4 ]; } && dots="--dots-out"
            job ink "$R/$name/t${t}_z$z" "$stip" "$BASE $cam --zoom $z --frames 1 --tone $t $dots"
        done
    done
    for t in $HIGH_TARGETS; do
        job ink "$R/$name/t${t}_z1" "$stip" "$BASE $cam --zoom 1 --frames 1 --tone $t"
    done
    for ((k = 0; k < SMALL_YAWS; ++k)); do
        for t in $TARGETS; do
            job ink "$R/$name/small_t${t}_y$k" "$stip" \
                "$BASE $cam --zoom 0.25 --yaw $(small_yaw "$k") --frames 1 --tone $t"
        done
    done
done
for n in 20000 100000; do
    for t in $SWEEP_TIMES; do
        render "$R/tube_$n/t$t" "$OUT/stip/tube_$n.stip" "$TUBE_VIEW --time $t --frames 1" ""
    done
done
render "$R/walk" "$OUT/stip/CesiumMan.stip" "$BASE --frames 60 --fps 30" "--tone 0.3 --dots-out"
for i in $(seq 0 $((SWEEP_FRAMES - 1))); do
    z=$(awk -v i="$i" -v n="$SWEEP_FRAMES" 'BEGIN { printf "%.6f", 16 ^ (i / (n - 1)) }')
    render "$R/zoom/$i" "$OUT/stip/CesiumMan.stip" "$BASE --frames 1 --zoom $z" "--tone 0.3 --dots-out"
done
log "rendering $(wc -l < "$JOBLIST") stipple-play runs on $JOBS jobs"
run_jobs < "$JOBLIST"

# Old players: the paper frames become mask_NNNN.png next to the ink frames.
if [ "$HAS_MASK" = 0 ]; then
    for name in $NAMES; do
        for z in $ZOOMS; do
            for t in $TARGETS $HIGH_TARGETS; do
                [ -d "$R/$name/t${t}_z$z" ] && cp "$R/$name/mask_z$z/frame_0000.png" "$R/$name/t${t}_z$z/mask_0000.png"
            done
        done
    done
    for paper in $(find "$R" -name '*.paper' -type d); do
        for f in "$paper"/frame_*.png; do
            b=$(basename "$f"); cp "$f" "${paper%.paper}/mask_${b#frame_}"
        done
    done
fi
# The zoom sweep as one sequence.
mkdir -p "$R/zoom_seq"
for i in $(seq 0 $((SWEEP_FRAMES - 1))); do
    n=$(printf '%04d' "$i")
    cp "$R/zoom/$i/dots_0000.csv" "$R/zoom_seq/dots_$n.csv"
    cp "$R/zoom/$i/mask_0000.png" "$R/zoom_seq/mask_$n.png"
done
fi
log "measuring"

# ---- measure and print --------------------------------------------------------------------
jnum() { sed -n "s/.*\"$2\": \\([-0-9.eE+]*\\|null\\).*/\\1/p" <<< "$1"; }
jpair() { sed -n "s/.*\"$2\": \\[\\([-0-9]*\\), \\([-0-9]*\\)\\].*/\\1 \\2/p" <<< "$1"; }
tone_of() { "$MEASURE" tone "$1/frame_0000.png" --mask "$1/mask_0000.png" "${@:2}"; }
fmt() { awk -v v="$1" 'BEGIN { printf "%.3f", v }'; }
# "0.297" or "0.352*" when off the target by more than 10 %.
mark() {
    awk -v v="$1" -v t="$2" 'BEGIN { d = v - t; if (d < 0) d = -d;
        printf "%.3f%s", v, (d > 0.1 * t) ? "*" : "" }'
}

echo "Binaries: \`$BIN\` (masks from $([ $HAS_MASK = 1 ] && echo 'stipple-play --mask-out' || echo 'paper frames: --tone 0 --background 808080')); measured with \`$(basename "$MEASURE")\`."
echo "All renders 640x480, \`--no-silhouettes\`, default camera, clip 0 at t = 0 (the tube: its \"rest\" clip); assets baked with default options."
echo
echo "Corpus: points baked, object pixels at zoom 1."
echo
echo "| asset | points | mask px (zoom 1) |"
echo "| --- | ---: | ---: |"
for name in $NAMES; do
    points=$(jnum "$(cat "$OUT/stip/$name.stip.json")" points)
    j=$(tone_of "$R/$name/t0.3_z1")
    echo "| $name | ${points:-?} | $(jnum "$j" mask_pixels) |"
done

echo
echo "### a. Tone under zoom"
echo
echo "Mean darkness inside the mask against the constant target (\`--tone T\`); \`*\`: more than 10 % off the target."
for t in $TARGETS; do
    echo
    echo "Target $t:"
    echo
    header="| asset |"; rule="| --- |"
    for z in $ZOOMS; do header="$header zoom $z |"; rule="$rule ---: |"; done
    echo "$header"; echo "$rule"
    for name in $NAMES; do
        row="| $name |"
        for z in $ZOOMS; do row="$row $(mark "$(jnum "$(tone_of "$R/$name/t${t}_z$z")" tone)" "$t") |"; done
        echo "$row"
    done
done
echo
echo "Dark targets at zoom 1:"
echo
echo "| asset | 0.8 | 0.9 | 1.0 |"
echo "| --- | ---: | ---: | ---: |"
for name in $NAMES; do
    row="| $name |"
    for t in $HIGH_TARGETS; do row="$row $(mark "$(jnum "$(tone_of "$R/$name/t${t}_z1")" tone)" "$t") |"; done
    echo "$row"
done

if [ "$SMALL_YAWS" -gt 0 ]; then
    echo
    echo "### a2. Zoom 0.25 from $SMALL_YAWS yaws"
    echo
    echo "Mean darkness inside the mask at zoom 0.25, mean over the views (\`*\`: more than 10 % off the target) and the views' range."
    echo
    echo "| asset | 0.1 mean | 0.1 range | 0.3 mean | 0.3 range | 0.6 mean | 0.6 range |"
    echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
    for name in $NAMES; do
        row="| $name |"
        for t in $TARGETS; do
            values=""
            for ((k = 0; k < SMALL_YAWS; ++k)); do
                values="$values $(jnum "$(tone_of "$R/$name/small_t${t}_y$k")" tone)"
            done
            read -r mean lo hi <<< "$(echo "$values" | awk '{ lo = $1; hi = $1; s = 0;
                for (i = 1; i <= NF; ++i) { s += $i; if ($i < lo) lo = $i; if ($i > hi) hi = $i }
                printf "%.6f %.3f %.3f", s / NF, lo, hi }')"
            row="$row $(mark "$mean" "$t") | $lo–$hi |"
        done
        echo "$row"
    done
fi
echo
echo "### b. Evenness at tone 0.3"
echo
echo "Dots counted inside the mask; clump share = NN distance < half the median NN distance (Poisson: 0.159); NN CV = stddev / mean of NN distances (Poisson: 0.52, lattice: 0); empty = 16-px blocks wholly inside the mask with no dot centre."
echo
echo "| asset | z1 dots | z1 clump | z1 NN CV | z1 empty / inside | z4 dots | z4 clump | z4 NN CV | z4 empty / inside |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for name in $NAMES; do
    row="| $name |"
    for z in 1 4; do
        d=$R/$name/t0.3_z$z
        j=$("$MEASURE" evenness "$d/dots_0000.csv" --mask "$d/mask_0000.png")
        row="$row $(jnum "$j" dots) | $(fmt "$(jnum "$j" clump_share)") | $(fmt "$(jnum "$j" nn_cv)") | $(jnum "$j" empty_blocks) / $(jnum "$j" blocks_inside) |"
    done
    echo "$row"
done

echo
echo "### c. Tone under stretch (tube, clip \"sweep\", \`--tone 0.3 --size 960x1440 --zoom 0.4\`)"
echo
echo "Bands in image rows, from each frame's own mask: its bottom row B is the tube's bottom (y = 0) and its top row T the top (y = 0.5 + 1.5 s), mapped linearly. Rest band: y in [0.10, 0.40] (rigid on \"lower\"); stretched band: rest-pose y in [0.65, 1.85] on \"upper\", i.e. y in [0.5 + 0.15 s, 0.5 + 1.35 s]. Ratio = stretched / rest band in the same frame; also the stretched band against itself at scale 1 (t = 0.5); \`*\`: more than 10 % off 1. Scale 2.5 is rendered at t = 1.999 (the clip loops at t = 2)."
echo
echo "| points | scale | rest band | stretched band | ratio | stretched / stretched at scale 1 | rest px | stretched px |"
echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for n in 20000 100000; do
    rows=(); s1=""
    for t in $SWEEP_TIMES; do
        d=$R/tube_$n/t$t
        j=$(tone_of "$d")
        read -r top bottom <<< "$(jpair "$j" mask_rows)"
        s=$(awk -v t="$t" 'BEGIN { printf "%.3f", 0.5 + t }')
        band() {  # world y range -> --rows A:B (A top, B exclusive)
            awk -v lo="$1" -v hi="$2" -v T="$top" -v B="$bottom" -v s="$s" 'BEGIN {
                k = (B - T) / (0.5 + 1.5 * s);
                printf "%d:%d", int(B - k * hi + 0.5), int(B - k * lo + 0.5) + 1 }'
        }
        rest=$(tone_of "$d" --rows "$(band 0.10 0.40)")
        up_lo=$(awk -v s="$s" 'BEGIN { print 0.5 + 0.15 * s }')
        up_hi=$(awk -v s="$s" 'BEGIN { print 0.5 + 1.35 * s }')
        str=$(tone_of "$d" --rows "$(band "$up_lo" "$up_hi")")
        tr=$(jnum "$rest" tone); ts=$(jnum "$str" tone)
        [ "$t" = 0.5 ] && s1=$ts
        edge=""; [ "$top" -le 0 ] && edge=" (top cut)"
        rows+=("$n|$s|$tr|$ts|$(jnum "$rest" mask_pixels)|$(jnum "$str" mask_pixels)$edge")
    done
    for r in "${rows[@]}"; do
        IFS='|' read -r pts s tr ts prest pstr <<< "$r"
        ratio=$(awk -v a="$ts" -v b="$tr" 'BEGIN { printf "%.6f", (b > 0) ? a / b : 0 }')
        self=$(awk -v a="$ts" -v b="$s1" 'BEGIN { printf "%.6f", (b > 0) ? a / b : 0 }')
        echo "| $pts | $(awk -v s="$s" 'BEGIN { printf "%g", s }') | $(fmt "$tr") | $(fmt "$ts") | $(mark "$ratio" 1) | $(mark "$self" 1) | $prest | $pstr |"
    done
done
echo
echo "### d. Coherence (CesiumMan, \`--tone 0.3\`)"
echo
echo "Persistence = share of frame f's dots (ids) still drawn in f + 1; pop share = dots bigger than half the median size that appear or vanish more than 4 px inside the mask, per dot of f + 1."
echo
echo "| sequence | pairs | mean persistence | worst persistence | mean pop share | max pop share |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for seq in walk zoom_seq; do
    j=$("$MEASURE" coherence "$R/$seq")
    label="walk, 30 fps, 60 frames"
    [ "$seq" = zoom_seq ] && label="zoom 1 -> 16 over $SWEEP_FRAMES frames (t = 0)"
    echo "| $label | $(jnum "$j" pairs) | $(fmt "$(jnum "$j" mean_persistence)") | $(fmt "$(jnum "$j" worst_persistence)") | $(awk -v v="$(jnum "$j" mean_pop_share)" 'BEGIN { printf "%.4f", v }') | $(awk -v v="$(jnum "$j" max_pop_share)" 'BEGIN { printf "%.4f", v }') |"
done
echo
log "done"
echo "Measured in $(( $(date +%s) - START )) s with $JOBS parallel renders."
