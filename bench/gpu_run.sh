#!/usr/bin/env bash
# The GPU rows of issues 24, 27 and 29, on a machine that has an NVIDIA GPU but
# none of this project's packages: unpacks bench/gpu_kit.sh's archive, runs
# bodyview headless (EGL) and writes every log into OUT_DIR.
#
#   bench/gpu_run.sh KIT_DIR OUT_DIR
#   QUICK=1  one run each and short tables (a smoke test of the kit)
#
# Rows: the draw-order tables (the .bpm level against a meshoptimizer-ordered
# static mesh of the same triangles, GPU time) and the memory figures of the
# bunny and of its 1.1M-triangle Loop subdivision; the cut-plane and pinned-label
# cost tables on the 100k-triangle benchmark model; the body scene (2,088
# models) and its 48-model baseline at full detail, 1920x1080: first frame,
# frame time, threads, peak RSS; the AAL sample's first frame.
set -uo pipefail
KIT=$1
OUT=$2
RUNS=${RUNS:-3}
SECONDS_PER_CELL=1
[ "${QUICK:-0}" = 1 ] && RUNS=1 SECONDS_PER_CELL=0
mkdir -p "$OUT" /tmp/gpukit
tar -C /tmp/gpukit -xJf "$KIT/kit.tar.xz"
K=/tmp/gpukit/kit
mkdir -p /usr/share/fonts/truetype/dejavu /usr/share/glmark2/models
cp -n "$K"/data/DejaVuSans*.ttf /usr/share/fonts/truetype/dejavu/
cp -n "$K/data/bunny.obj" /usr/share/glmark2/models/
export LD_LIBRARY_PATH=$K/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
BV=$K/bin/bodyview
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; } > "$OUT/machine.txt" 2>&1

# Runs bodyview ARGS...; appends "peak_threads peak_rss_kib" of the run to $OUT/$1.watch.
watched() {
  local name=$1; shift
  "$BV" "$@" >> "$OUT/$name.log" 2>&1 &
  local pid=$! threads=0 hwm=0 n h
  while kill -0 "$pid" 2>/dev/null; do
    n=$(awk '/^Threads:/ {print $2}' "/proc/$pid/status" 2>/dev/null)
    h=$(awk '/^VmHWM:/ {print $2}' "/proc/$pid/status" 2>/dev/null)
    [ "${n:-0}" -gt "$threads" ] && threads=$n
    [ "${h:-0}" -gt "$hwm" ] && hwm=$h
    sleep 0.005
  done
  wait "$pid"
  echo "rc $? threads $threads vmhwm_kib $hwm" >> "$OUT/$name.log"
}

# Issue 24: draw order against the static mesh, memory (full benchmark on the .bpm).
for m in bunny loop; do
  "$BV" --headless --benchmark --model "$K/data/$m.bpm" --bench-frames 9 --bench-seconds "$SECONDS_PER_CELL" \
    > "$OUT/bench-$m.log" 2>&1
done
# Issue 27: the cut plane and the pins on the 100k benchmark model (as on llvmpipe).
for t in cut pins; do
  for r in $(seq "$RUNS"); do
    "$BV" --headless --benchmark --bench-triangles 100000 --bench-frames 100 --bench-seconds 0 --bench-only "$t" \
      >> "$OUT/bench-$t.log" 2>&1
  done
done
# Issue 29: first frame (automatic LOD), then frame time at full detail, 1920x1080.
for r in $(seq "$RUNS"); do
  for s in body/scene.json body/merged/scene.json body/sample/bundle/scene.json; do
    watched "first-$(echo "$s" | tr / _)" --headless --size 1920x1080 --scene "$K/$s" --frames 2 --kiosk-stats
  done
  for s in body/full.json body/merged/full.json; do
    watched "full-$(echo "$s" | tr / _)" --headless --size 1920x1080 --scene "$K/$s" --frames 600 --no-auto-lod \
      --kiosk-stats
  done
done
ls -la "$OUT"
