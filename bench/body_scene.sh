#!/usr/bin/env bash
# The body-scale scene against the same triangles in few models (issue 29):
# models, triangles, first frame, frame time at a fixed LOD, peak threads and
# peak RSS of `bodyview --headless` on scenes made by scripts/build-body-scene.sh.
#
#   bench/body_scene.sh [SCENE.json[@R] ...]   (default: build/body-scene/scene.json
#                                               and build/body-scene/merged/scene.json)
#   LOD=R      the fixed ratio of the frame-time runs (default 0.05); SCENE@R sets
#              a scene's own (to compare scenes at the same triangles: a ratio
#              gives small models fewer, their coarse levels being far apart)
#   UNBATCHED=1  also each scene with BODY_BATCH=0 (one draw call a model; kiosk/render/batch.h)
#   RUNS=N     runs per scene; the medians are printed (default 3)
#   FRAMES=N   frames per run (default 300); the frame time is the mean of the
#              frames after the kiosk reported "full detail" (from the next
#              60-frame mark on: the detail has streamed in and the decoding
#              threads are idle); "-" when it came later than FRAMES - 60
#   SIZE=WxH   default 1280x800
#
# First frame: the kiosk's own figure (--kiosk-stats), automatic LOD. Threads:
# the most /proc/PID/status reported over both runs, polled every 2 ms. RSS: /usr/bin/time -v.
# The runs are interleaved (run 1 of every row, then run 2, ...) so that a
# machine's changing load falls on every row alike.
set -euo pipefail
cd "$(dirname "$0")/.."
BODYVIEW=${BODYVIEW:-build/bin/bodyview}
LOD=${LOD:-0.05}
RUNS=${RUNS:-3}
FRAMES=${FRAMES:-300}
SIZE=${SIZE:-1280x800}
[ $# -gt 0 ] || set -- build/body-scene/scene.json build/body-scene/merged/scene.json
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# Runs bodyview ARGS... in the background; prints "peak_threads peak_rss_kib" after it exits.
run_watched() {
  /usr/bin/time -v -o "$TMP/time" "$BODYVIEW" "$@" 2> "$TMP/err" &
  local pid=$! peak=0 child n
  while kill -0 "$pid" 2>/dev/null; do
    child=$(pgrep -P "$pid" -n || true)
    if [ -n "$child" ] && [ -r "/proc/$child/status" ]; then
      n=$(awk '/^Threads:/ {print $2}' "/proc/$child/status" 2>/dev/null || echo 0)
      [ "${n:-0}" -gt "$peak" ] && peak=$n
    fi
    sleep 0.002
  done
  wait "$pid" || { cat "$TMP/err" >&2; return 1; }
  echo "$peak $(awk -F': ' '/Maximum resident/ {print $2}' "$TMP/time")"
}

median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

# The rows: "scene lod batch" (batch 0: BODY_BATCH=0).
ROWS=()
for arg in "$@"; do
  scene=${arg%@*}
  lod=$LOD
  [ "$arg" != "$scene" ] && lod=${arg##*@}
  ROWS+=("$scene $lod 1")
  [ "${UNBATCHED:-0}" = 1 ] && ROWS+=("$scene $lod 0")
done

for run in $(seq "$RUNS"); do
  for i in "${!ROWS[@]}"; do
    read -r scene lod batch <<< "${ROWS[$i]}"
    out="$TMP/row$i"
    mkdir -p "$out"
    [ "$run" = 1 ] && { : > "$out/first"; : > "$out/frame"; : > "$out/threads"; : > "$out/rss"; }
    export BODY_BATCH=$batch
    read -r threads rss < <(run_watched --headless --size "$SIZE" --scene "$scene" --frames 2 --kiosk-stats)
    sed -n 's/.*first frame \([0-9.]*\) ms.*/\1/p' "$TMP/err" >> "$out/first"
    sed -n 's/.*, \([0-9]*\/[0-9]*\) models,.*/\1/p' "$TMP/err" > "$out/models"
    echo "$threads" >> "$out/threads"
    echo "$rss" >> "$out/rss"
    # The same scene with every model at the fixed ratio (beside it: its paths are relative).
    fixed="$(dirname "$scene")/.fixed-lod.json"
    python3 -c "import json,sys; s=json.load(open(sys.argv[1]))
for m in s['models']: m['lod'] = float(sys.argv[2])
json.dump(s, open(sys.argv[3], 'w'))" "$scene" "$lod" "$fixed"
    read -r threads rss < <(run_watched --headless --size "$SIZE" --scene "$fixed" --frames "$FRAMES" \
      --no-auto-lod --kiosk-stats)
    rm -f "$fixed"
    echo "$threads" >> "$out/threads"
    echo "$rss" >> "$out/rss"
    # The cumulative means at the first 60-frame mark after "full detail" and
    # at FRAMES frames give the mean of the frames in between.
    awk -v total="$FRAMES" '/full detail/ {full = 1}
      /ms\/frame, [0-9]* triangles/ {n += 60; m[n] = $2; t = $4; if (full && !start) start = n}
      END {if (start && start < total) printf "%.3f %d\n", (m[total] * total - m[start] * start) / (total - start), t
           else printf "- %d\n", t}' "$TMP/err" > "$TMP/one"
    cut -d' ' -f1 "$TMP/one" | grep -v -- - >> "$out/frame" || true
    cut -d' ' -f2 "$TMP/one" > "$out/drawn"
  done
done

printf "%-40s %6s %5s %9s %14s %10s %12s %8s %8s\n" scene lod batch models first_frame_ms frame_ms "at_triangles" \
  threads rss_mib
for i in "${!ROWS[@]}"; do
  read -r scene lod batch <<< "${ROWS[$i]}"
  out="$TMP/row$i"
  full=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['models']))" "$scene")
  models=$(cat "$out/models")
  printf "%-40s %6s %5s %9s %14s %10s %12s %8s %8.1f\n" "$scene" "$lod" "$batch" "${models:-?/$full}" \
    "$(median < "$out/first")" "$(median < "$out/frame")" "$(cat "$out/drawn")" "$(sort -g "$out/threads" | tail -1)" \
    "$(echo "$(sort -g "$out/rss" | tail -1) / 1024" | bc -l)"
done
