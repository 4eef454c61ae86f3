#!/usr/bin/env bash
# A full disk leaves nothing half-written (issue 30): on a small tmpfs whose
# free space is set per case, `bodygen build -o DIR/` (new and over an old
# output), `build -o X.obj`, `lod -o X.bpm` and `exhibit -o BUNDLE/` that do
# not fit exit 1 with one line naming the output (never a temporary), and the disk holds exactly
# what it held before (old outputs byte-identical, no temporaries). `pack`
# has its own check (check-full-disk.sh). Needs mount(2): exit 77 (skipped)
# where a tmpfs cannot be mounted.
#   scripts/check-full-disk-outputs.sh BUILD_DIR
set -uo pipefail
. "$(dirname "$0")/full-disk-tmpfs.sh" check-full-disk-outputs 1m "${1:-}"
BODYGEN=$BUILD/bin/bodygen
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Four structures of ~230 KB of OBJ each (linear), and one of them as a mesh for lod.
python3 - "$tmp/big.contours.json" <<'PY'
import json, math, sys
def ring(cx, n, z):
    pts = []
    for i in range(n):
        a = 2 * math.pi * i / n
        r = 10 + 0.3 * math.sin(9 * a + z)
        pts.append([round(cx + r * math.cos(a), 4), round(r * math.sin(a), 4)])
    return pts
json.dump({"format": "bodygen.contours", "version": 1, "structures": [{"id": f"s{k}"} for k in range(4)],
           "slices": [{"z": z, "contours": [{"structure": f"s{k}", "points": ring(30 * k, 3000, z)} for k in range(4)]}
                      for z in (0, 2, 4)]}, open(sys.argv[1], "w"))
PY
"$BODYGEN" build "$tmp/big.contours.json" -o "$tmp/mesh/" --quiet || { echo "cannot build the inputs"; exit 1; }
"$BODYGEN" build "$ROOT/tests/data/stacks/small.contours.json" -o "$mnt/old/" --quiet --interpolate 0 || { echo "no old output"; exit 1; }

# Leaves about KB kilobytes free (a filler file takes the rest).
leave() {
    rm -f "$mnt/.filler"
    local free_kb
    free_kb=$(df -k --output=avail "$mnt" | tail -1)
    [ "$free_kb" -gt "$1" ] && head -c "$(( (free_kb - $1) * 1024 ))" /dev/zero > "$mnt/.filler" 2>/dev/null
}
snapshot() { (cd "$mnt" && find . -path ./.filler -prune -o -print0 | sort -z | xargs -0 md5sum 2>/dev/null; find . | sort); }

# case NAME FREE_KB OUTPUT bodygen-args...: exit 1, one line naming OUTPUT, disk unchanged.
case_() {
    local name=$1 free=$2 output=$3; shift 3
    leave "$free"
    local before after rc lines
    before=$(snapshot)
    "$BODYGEN" "$@" --quiet > "$tmp/out" 2> "$tmp/err"
    rc=$?
    after=$(snapshot)
    lines=$(wc -l < "$tmp/err")
    echo "$name: exit $rc: $(head -c 300 "$tmp/err")"
    [ "$rc" -eq 1 ] || fail "$name: exit $rc, expected 1"
    [ "$lines" -eq 1 ] || fail "$name: $lines lines on stderr, expected 1"
    grep -qE -- "^bodygen: $output/?: " "$tmp/err" || fail "$name: the message does not begin with $output"
    grep -qiE "disk full|no space" "$tmp/err" || fail "$name: the message does not say the disk is full"
    ! grep -qE "\.tmp-[0-9]|\.work" "$tmp/err" || fail "$name: the message names a temporary, gone by now"
    [ "$before" = "$after" ] || { diff <(echo "$before") <(echo "$after"); fail "$name: the disk changed"; }
}

case_ "build -o NEW/" 300 "$mnt/new" build "$tmp/big.contours.json" -o "$mnt/new/"
case_ "build -o OLD/ (replacing)" 300 "$mnt/old" build "$tmp/big.contours.json" -o "$mnt/old/"
case_ "build -o X.obj" 300 "$mnt/x.obj" build "$tmp/big.contours.json" -o "$mnt/x.obj"
case_ "build -o X.bpm" 40 "$mnt/x.bpm" build "$tmp/big.contours.json" -o "$mnt/x.bpm"
case_ "lod -o X.bpm" 24 "$mnt/x.bpm" lod "$tmp/mesh/s0.obj" -o "$mnt/x.bpm"
case_ "exhibit -o BUNDLE/" 100 "$mnt/bundle" exhibit "$tmp/big.contours.json" -o "$mnt/bundle/"
rm -f "$mnt/.filler"
# With room again, the same commands succeed and replace the old output (linear
# bands: the ~920 KB of OBJ must fit the 1 MB disk; interpolated it would not).
"$BODYGEN" build "$tmp/big.contours.json" -o "$mnt/old/" --quiet --interpolate 0 && [ "$(ls "$mnt/old" | wc -l)" -eq 4 ] \
    || fail "build -o OLD/ with room did not replace the old output"
if [ "$failures" -eq 0 ]; then
    echo "check-full-disk-outputs: every output that did not fit failed cleanly and left the disk as it was"
else
    echo "check-full-disk-outputs: $failures failure(s)"
fi
[ "$failures" -eq 0 ]
