#!/usr/bin/env bash
# Builds the product's sample exhibit: the AAL brain atlas (Debian mricron-data,
# 116 regions, colours from the .lut beside it) -> one closed, smoothed mesh per
# region -> progressive meshes -> a kiosk scene grouped by lobe and side
# (builder/import/aal_groups.tsv) -> a kiosk bundle (build/sample/bundle), all
# by one `bodygen exhibit` command. Regions the pipeline rejects are reported
# and left out. Nothing derived from the atlas is committed.
#
#   scripts/build-sample.sh [BODYGEN] [OUT_DIR]
#     BODYGEN  default build/bin/bodygen
#     OUT_DIR  default build/sample
#   JOBS=N     worker threads (default: all cores)
#   SMOOTH=N   Taubin smoothing steps per region (default 0: the contours of each region's
#              blurred labels are smooth already, and stay on their slice planes)
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BODYGEN=${1:-$ROOT/build/bin/bodygen}
OUT=${2:-$ROOT/build/sample}
JOBS=${JOBS:-$(nproc)}
ATLAS=/usr/share/mricron/templates/aal.nii.gz

if [ ! -f "$ATLAS" ]; then
  if [ "$(id -u)" = 0 ]; then
    echo "build-sample: installing mricron-data (the AAL atlas)"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends mricron-data
  else
    echo "build-sample: the AAL atlas is missing; run: sudo apt-get install mricron-data" >&2
    exit 1
  fi
fi
[ -x "$BODYGEN" ] || { echo "build-sample: $BODYGEN not built (cmake --build build)" >&2; exit 1; }
mkdir -p "$OUT"
# --min-area 3: per-slice islands of 1-3 voxels are atlas speckle: dropping them gives
# cleaner models. The atlas's voxel stairs are taken out by the contours themselves
# (--label-smooth, default 2 voxels), less terraced than --smooth 10 on voxel faces.
"$BODYGEN" exhibit "$ATLAS" --groups "$ROOT/builder/import/aal_groups.tsv" --min-area 3 \
  --smooth "${SMOOTH:-0}" --view left --jobs "$JOBS" -o "$OUT/bundle"
echo "build-sample: done: open it with: bodyview $OUT/bundle"
