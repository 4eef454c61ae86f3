#!/usr/bin/env bash
# Between-slice interpolation against VTK's voxel route (issue 23's table):
# glmark2 meshes (bunny.obj; the .3ds models converted with assimp) sliced with
# `bodygen slice` at 40 and 100 planes along z and x, each stack rebuilt by
# bodygen linear, with --interpolate N and with --smooth 10, and by VTK's
# vtkVoxelContoursToSurfaceFilter. Prints one markdown row per stack: the
# symmetric Hausdorff distance to the original surface within the sliced slab
# (reconstruct_vs_vtk.py) of each with the area-sampled mean distance in brackets, the
# interpolated/VTK ratios (goal: Hausdorff <= 0.6) and CPU seconds (bodygen:
# the whole build process; VTK: the filter's Update()).
# cat.3ds and horse.3ds are open meshes that `bodygen slice` refuses.
#
# usage: bench/interpolate_vs_vtk.sh [BUILD_DIR] [--rings N] [--resolution N]
#          [--meshes "bunny asteroid-low asteroid-high cube"] [--planes "40 100"] [--axes "z x"]
#   needs BUILD_DIR/bin/bodygen, glmark2-data, assimp-utils, python3-vtk9, python3-numpy.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then build=$1; shift; fi
rings=3
resolution=256
meshes="bunny asteroid-low asteroid-high cube"
plane_counts="40 100"
axes="z x"
while [ $# -gt 0 ]; do
  case $1 in
    --rings) rings=$2; shift 2 ;;
    --resolution) resolution=$2; shift 2 ;;
    --meshes) meshes=$2; shift 2 ;;
    --planes) plane_counts=$2; shift 2 ;;
    --axes) axes=$2; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
bodygen=$build/bin/bodygen
models=/usr/share/glmark2/models
py=/usr/bin/python3
[ -x "$bodygen" ] || { echo "no $bodygen: build first (cmake --build $build --target bodygen)" >&2; exit 2; }
[ -f "$models/bunny.obj" ] || { echo "no $models (Debian package glmark2-data)" >&2; exit 2; }
command -v assimp >/dev/null || { echo "no assimp (Debian package assimp-utils)" >&2; exit 2; }
$py -c 'import vtk, numpy' 2>/dev/null || { echo "needs python3-vtk9 and python3-numpy" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$models/bunny.obj" "$work/bunny.obj"
for m in asteroid-low asteroid-high cube; do
  assimp export "$models/$m.3ds" "$work/$m.obj" -jiv >/dev/null
done

# CPU seconds (user + system) of one command: the machine may be shared.
cpu() {
  $py -c 'import resource, subprocess, sys
subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(r.ru_utime + r.ru_stime)' "$@"
}

echo "| stack | VTK H (mean) | linear H (mean) | interpolated, $rings rings, H (mean) | --smooth 10 H (mean) | interpolated / VTK: H, mean | CPU s: VTK / linear / interpolated / smooth |"
echo "|---|---|---|---|---|---|---|"
for m in $meshes; do
  for axis in $axes; do
    for planes in $plane_counts; do
      name=$m-$axis$planes
      stack=$work/$name.contours.json
      "$bodygen" slice "$work/$m.obj" --planes "$planes" --axis "$axis" --avoid-self-intersections -o "$stack" 2>/dev/null
      # Along x the stack's z is the mesh's x: compare against the mesh with its axes turned the same way.
      original=$work/$m.obj
      if [ "$axis" = x ]; then
        original=$work/$m-x.obj
        [ -f "$original" ] || awk '$1 == "v" { print "v", $3, $4, $2; next } { print }' "$work/$m.obj" >"$original"
      fi
      t_lin=$(cpu "$bodygen" build "$stack" -o "$work/$name-linear.obj" --quiet --interpolate 0)
      t_int=$(cpu "$bodygen" build "$stack" -o "$work/$name-interp.obj" --quiet --interpolate "$rings")
      t_smo=$(cpu "$bodygen" build "$stack" -o "$work/$name-smooth.obj" --quiet --smooth 10 --interpolate 0)
      row=$($py bench/reconstruct_vs_vtk.py "$stack" "$original" "$work/$name-linear.obj" --resolution "$resolution" \
        --bodygen-seconds "$t_lin" --label linear --also interp "$work/$name-interp.obj" "$t_int" \
        --also smooth "$work/$name-smooth.obj" "$t_smo" --row "$name" | grep '^row ')
      read -r _ n vh vm vs _ lh lm ls _ ih im is _ sh sm ss <<<"$row"
      ratio=$($py -c "print(f'{$ih / $vh:.2f}, {$im / $vm:.2f}')")
      echo "| $n | $vh ($vm) | $lh ($lm) | $ih ($im) | $sh ($sm) | $ratio | $vs / $ls / $is / $ss |"
    done
  done
done
