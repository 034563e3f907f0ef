#!/bin/bash
# llvmpipe's rasterizer threads against the point part's worker (docs/performance.md,
# seventeenth round). LP_NUM_THREADS is read once per display, so the two settings cannot
# alternate inside one process: this runs stipple_bench_frame_floor RUNS times with Mesa's
# default (a rasterizer thread per core) and RUNS times with --raster-threads 0 (rasterizing
# on the calling thread), alternating, and reports for each setting
# the frame (1 and 2 threads, with and without the occluder) and the floor (ms per frame, each
# run's min over its rounds): medians over the runs, 0 / default pair by pair, and each
# setting's frame over its own floor. RASTER=N compares --raster-threads N instead of 0.
#   [RASTER=N] bench/raster_threads.sh [RUNS] [ROUNDS]   (after a Release build)
set -euo pipefail
RUNS=${1:-4}
ROUNDS=${2:-3}
RASTER=${RASTER:-0}
BIN=${BIN:-$(cd "$(dirname "$0")/.." && pwd)/build/bin/stipple_bench_frame_floor}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
for i in $(seq "$RUNS"); do
    echo "run $i of $RUNS: Mesa's default, then --raster-threads $RASTER" >&2
    "$BIN" --rounds "$ROUNDS" >"$OUT/default.$i.txt"
    "$BIN" --rounds "$ROUNDS" --raster-threads "$RASTER" >"$OUT/zero.$i.txt"
done
python3 - "$OUT" "$RUNS" "$RASTER" <<'PY'
import sys
out, runs, n = sys.argv[1], int(sys.argv[2]), sys.argv[3]
label_n = '0 (calling thread)' if n == '0' else n
def first(cell):  # "min / median" -> min
    return float(cell.split('/')[0])
def read(path):
    lines = open(path).read().splitlines()
    got = {}
    for l in lines:
        c = [x.strip() for x in l.split('|')]
        if len(c) > 8 and c[2] in ('100000', '96966'):  # the first table: frame, floor
            got.setdefault(c[1], {}).update(frame=first(c[5]), floor=first(c[7]))
    two = lines.index(next(l for l in lines if l.startswith('Two threads')))
    for l in lines[two:two + 8]:
        c = [x.strip() for x in l.split('|')]
        if len(c) > 5 and c[1] in got and '/' in c[3]:
            got[c[1]].update(two=first(c[3]), occluder_two=first(c[4]))
    return got
rows = {}  # asset -> setting -> list over runs of each figure
for setting in ('default', 'zero'):
    for i in range(1, runs + 1):
        for name, v in read(f'{out}/{setting}.{i}.txt').items():
            for k, x in v.items():
                rows.setdefault(name, {}).setdefault(setting, {}).setdefault(k, []).append(x)
def median(v):
    v = sorted(v)
    return v[len(v) // 2] if len(v) % 2 else 0.5 * (v[len(v) // 2 - 1] + v[len(v) // 2])
keys = [('floor', 'floor'), ('frame', 'frame, 1 thread'), ('two', 'frame, 2 threads'),
        ('occluder_two', 'occluder, 2 threads')]
print(f'{runs} pairs of runs (Mesa\'s default, then {n}), each run the min over its rounds; ms per')
print(f'frame, median over the runs; then {n} / default pair by pair (runs next to each other in')
print('time: the host drifts less within a pair than between pairs), median and range\n')
print(f'| asset | figure | Mesa\'s default | {label_n} | {n} / default (median; range) |')
print('| --- | --- | ---: | ---: | ---: |')
for name, s in rows.items():
    for k, label in keys:
        d, z = s['default'][k], s['zero'][k]
        r = [b / a for a, b in zip(d, z)]
        print(f'| {name} | {label} | {median(d):.2f} | {median(z):.2f} | '
              f'{median(r):.2f}; {min(r):.2f}-{max(r):.2f} |')
print('\nEach against the floor of its own setting, median over runs (frame / floor):\n')
print('| asset | rasterizer threads | frame, 1 thread | frame, 2 threads | occluder, 2 threads |')
print('| --- | --- | ---: | ---: | ---: |')
for name, s in rows.items():
    for setting, label in (('default', "Mesa's default"), ('zero', label_n)):
        v = s[setting]
        ratio = lambda k: median([a / f for a, f in zip(v[k], v['floor'])])
        print(f"| {name} | {label} | {ratio('frame'):.2f} | {ratio('two'):.2f} | "
              f"{ratio('occluder_two'):.2f} |")
PY
