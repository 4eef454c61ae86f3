#!/usr/bin/env bash
# Cap triangulation scaling (issue 30): one wavy circle of N points on two
# slices, built with --caps none, flat and dome (the default); prints wall and
# user seconds. The ratio to --caps none is the figure (same run, same machine).
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
    for caps in none flat dome; do
        /usr/bin/time -f "points $n caps $caps: %e s wall, %U s user, %M KiB" \
            "$BODYGEN" build "$WORK/c$n.contours.json" --caps "$caps" --quiet -o "$WORK/out.obj"
    done
done
