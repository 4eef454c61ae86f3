#!/usr/bin/env bash
# Whole AAL atlas -> one mesh per region: bodygen (contours + build, 1 and 2
# jobs, with the sample's --min-area 3 and with defaults) against VTK's discrete
# flying edges + windowed-sinc smoothing (the 3D Slicer route) in the same run:
# wall time, triangles, closed manifolds (strict, both sides), volume vs voxel
# count and boundary fidelity, as a markdown table.
#   bench/import_vs_vtk.sh [BODYGEN]   (default build/bin/bodygen)
set -euo pipefail
cd "$(dirname "$0")/.."
BODYGEN=${1:-$PWD/build/bin/bodygen}
ATLAS=/usr/share/mricron/templates/aal.nii.gz
NAMES=/usr/share/mricron/templates/aal.nii.txt
PY=/usr/bin/python3  # Debian's python3-vtk9 lives in the system interpreter
need=()
[ -f "$ATLAS" ] || need+=(mricron-data)
$PY -c 'import vtk, numpy' 2>/dev/null || need+=(python3-vtk9 python3-numpy)
if [ ${#need[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ]; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}"
  else
    echo "import_vs_vtk: missing; run: sudo apt-get install ${need[*]}" >&2
    exit 1
  fi
fi
[ -x "$BODYGEN" ] || { echo "import_vs_vtk: $BODYGEN not built" >&2; exit 1; }
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
# One thread for VTK's SMP loops too, so "single-threaded" means the same on both sides.
VTK_SMP_MAX_THREADS=1 OMP_NUM_THREADS=1 $PY bench/import_vs_vtk.py "$BODYGEN" "$ATLAS" "$NAMES" "$WORK"
