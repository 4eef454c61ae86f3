#!/usr/bin/env bash
# Side by side: our progressive meshes vs meshopt_simplify vs VTK's
# vtkQuadricDecimation (Garland-Heckbert with optimal placement) on the bunny, the
# bunny subdivided twice and any NAME=FILE OBJ given, all three at VTK's triangle
# count. Prints bench_pm's table (ratios ours / baseline).
#
# usage: bench/pm_vs_vtk.sh [BUILD_DIR] [--no-big] [--accuracy-only] [NAME=FILE ...]     (default BUILD_DIR: build)
#   e.g. NAME=FILE: loop=loop.obj (bench/loop_bunny.py), anat=region.obj (`bodygen build` of an AAL region)
# PM_VTK_CACHE=DIR keeps VTK's outputs (<name>_vtk_<percent>.obj) in DIR and reuses
# them on later runs: they depend on the inputs only, not on our code.
# Needs Debian python3-vtk9 (installed with apt-get when missing and run as root).
set -euo pipefail
build=${1:-build}
shift || true
big= meshes=() names_extra=
for a in "$@"; do
  case $a in
    --no-big) big=--no-big ;;
    --accuracy-only) meshes+=(--accuracy-only) ;;
    *=*) meshes+=(--mesh "$a"); names_extra="$names_extra ${a%%=*}" ;;
    *) echo "pm_vs_vtk: unknown argument $a" >&2; exit 2 ;;
  esac
done
bench="$build/bin/bench_pm"
[ -x "$bench" ] || { echo "pm_vs_vtk: build bench_pm first ($bench missing)" >&2; exit 1; }
py=/usr/bin/python3
if ! "$py" -c 'import vtk' 2>/dev/null; then
  if [ "$(id -u)" = 0 ]; then
    apt-get install -y --no-install-recommends python3-vtk9 >/dev/null
  else
    echo "pm_vs_vtk: python3-vtk9 missing (sudo apt-get install python3-vtk9)" >&2
    exit 1
  fi
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bench" --write-dir "$work" $big "${meshes[@]}" >/dev/null
names=bunny
[ -z "$big" ] && names="bunny bunny_sub"
names="$names$names_extra"
cache=${PM_VTK_CACHE:-}
for name in $names; do
  if [ -n "$cache" ] && [ -f "$cache/${name}_vtk_10.obj" ] && [ -f "$cache/${name}_vtk_2.obj" ]; then
    echo "vtkQuadricDecimation $name: reusing $cache/${name}_vtk_{10,2}.obj" >&2
    cp "$cache/${name}_vtk_10.obj" "$cache/${name}_vtk_2.obj" "$work/"
    continue
  fi
  "$py" - "$work" "$name" <<'PY'
import sys, time, vtk
work, name = sys.argv[1], sys.argv[2]
reader = vtk.vtkOBJReader()
reader.SetFileName(f"{work}/{name}.obj")
reader.Update()
tri = vtk.vtkTriangleFilter()
tri.SetInputConnection(reader.GetOutputPort())
tri.Update()
clean = vtk.vtkCleanPolyData()  # weld the OBJ's per-face vertices
clean.SetInputConnection(tri.GetOutputPort())
clean.Update()
full = clean.GetOutput().GetNumberOfPolys()
for pct in (10, 2):
    dec = vtk.vtkQuadricDecimation()
    dec.SetInputData(clean.GetOutput())
    dec.SetTargetReduction(1.0 - pct / 100.0)
    t0 = time.process_time()
    dec.Update()
    dt = time.process_time() - t0
    out = dec.GetOutput()
    w = vtk.vtkOBJWriter()
    w.SetFileName(f"{work}/{name}_vtk_{pct}.obj")
    w.SetInputData(out)
    w.Write()
    print(f"vtkQuadricDecimation {name} {pct}%: {out.GetNumberOfPolys()} of {full} triangles in {dt:.3f} CPU s",
          file=sys.stderr)
PY
  if [ -n "$cache" ]; then
    mkdir -p "$cache"
    cp "$work/${name}_vtk_10.obj" "$work/${name}_vtk_2.obj" "$cache/"
  fi
done
"$bench" --vtk-dir "$work" $big "${meshes[@]}"
