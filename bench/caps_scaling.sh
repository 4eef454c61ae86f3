#!/usr/bin/env bash
# Cap triangulation scaling (issue 30): one wavy circle of N points on two
# slices, built with --caps none, flat and dome (the default), each RUNS times
# (default 3); prints every run's wall and user seconds and the median user
# seconds with its ratio to --caps none (same run, same machine). --strict
# keeps every point: the default repair would merge the ring's nearly
# collinear points (10^6 points -> about 1,200).
#   bench/caps_scaling.sh [BODYGEN] [N...]     (default N: 10000 100000 1000000)
set -euo pipefail
BODYGEN=${1:-build/bin/bodygen}
shift || true
SIZES=("${@:-10000 100000 1000000}")
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
for n in ${SIZES[@]}; do
    python3 - "$n" "$WORK/c$n.contours.json" <<'PY'
import json, math, sys
n, out = int(sys.argv[1]), sys.argv[2]
def ring(n):
    pts = []
    for i in range(n):
        a = 2 * math.pi * i / n
        r = 100 + 5 * math.sin(50 * a)
        pts.append([round(r * math.cos(a), 5), round(r * math.sin(a), 5)])
    return pts
json.dump({"format": "bodygen.contours", "version": 1, "structures": [{"id": "a"}],
           "slices": [{"z": z, "contours": [{"points": ring(n), "structure": "a"}]} for z in (0, 2)]}, open(out, "w"))
PY
    declare -A median
    for caps in none flat dome; do
        times=()
        for ((run = 0; run < ${RUNS:-3}; run++)); do
            /usr/bin/time -o "$WORK/time" -f "%e %U %M" \
                "$BODYGEN" build "$WORK/c$n.contours.json" --caps "$caps" --interpolate 0 --strict --quiet -o "$WORK/out.obj"
            read -r wall user kib < "$WORK/time"
            echo "points $n caps $caps: $wall s wall, $user s user, $kib KiB"
            times+=("$user")
        done
        median[$caps]=$(printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR + 1) / 2)]}')
    done
    for caps in none flat dome; do
        echo "median points $n caps $caps: ${median[$caps]} s user ($(awk -v a="${median[$caps]}" -v b="${median[none]}" \
            'BEGIN {printf "%.2f", a / b}')x none)"
    done
done
