#!/usr/bin/env bash
# Side by side: the glmark2 bunny sliced into contour stacks (40 and 100
# planes), rebuilt by bodygen (both tiling methods, linear bands: --interpolate 0) and by VTK's
# vtkVoxelContoursToSurfaceFilter from the same stack; prints for each the
# build time, the symmetric Hausdorff distance to the original surface within
# the slab the slices span, and the bodygen/VTK ratios. Times are CPU seconds
# (bodygen: the whole build process; VTK: the filter's Update()).
#
# usage: bench/reconstruct_vs_vtk.sh [BUILD_DIR] [--resolution N]
#   BUILD_DIR defaults to build; needs BUILD_DIR/bin/bodygen.
#   VTK comes from Debian's python3-vtk9 (installed with apt-get when missing and run as root).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
resolution=256
if [ "${1:-}" = "--resolution" ]; then resolution=$2; fi
bodygen=$build/bin/bodygen
bunny=/usr/share/glmark2/models/bunny.obj
py=/usr/bin/python3

[ -x "$bodygen" ] || { echo "no $bodygen: build first (cmake --build $build --target bodygen)" >&2; exit 2; }
[ -f "$bunny" ] || { echo "no $bunny (Debian package glmark2-data)" >&2; exit 2; }
if ! $py -c 'import vtk, numpy' 2>/dev/null; then
  if [ "$(id -u)" = 0 ]; then
    apt-get install -y python3-vtk9 python3-numpy >/dev/null || { apt-get update >/dev/null && apt-get install -y python3-vtk9 python3-numpy >/dev/null; }
  else
    echo "python3-vtk9 and python3-numpy are missing; run as root or: sudo apt-get install python3-vtk9 python3-numpy" >&2
    exit 2
  fi
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for planes in 40 100; do
  stack=$work/bunny$planes.contours.json
  "$bodygen" slice "$bunny" --planes "$planes" --avoid-self-intersections -o "$stack"
  for tiling in multires optimal; do
    out=$work/bunny${planes}_$tiling.obj
    # CPU seconds (user + system) of the build: the machine may be shared, so wall time is not comparable.
    seconds=$($py -c 'import resource, subprocess, sys
subprocess.run(sys.argv[1:], check=True)
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(r.ru_utime + r.ru_stime)' "$bodygen" build "$stack" -o "$out" --tiling "$tiling" --interpolate 0 --quiet)
    echo "== bunny, $planes planes, bodygen --tiling $tiling vs VTK (voxel resolution $resolution)"
    $py bench/reconstruct_vs_vtk.py "$stack" "$bunny" "$out" --resolution "$resolution" \
      --bodygen-seconds "$seconds" --label "bodygen $tiling"
  done
done
