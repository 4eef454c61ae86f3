#!/usr/bin/env python3
"""Side-by-side helper for bench/reconstruct_vs_vtk.sh.

Rebuilds a contour stack (*.contours.json) with VTK's
vtkVoxelContoursToSurfaceFilter, then measures the symmetric Hausdorff
distance of each reconstruction to the original surface, restricted to the
slab the slices span (points of either surface with z outside it are ignored).
Distances are sampled at the vertices and triangle centroids of each mesh and
measured to the other surface with vtkImplicitPolyDataDistance.

usage: reconstruct_vs_vtk.py STACK.contours.json ORIGINAL.obj BODYGEN.obj [--resolution N]
                              [--also LABEL OBJ SECONDS]... [--row NAME]
Prints one line per reconstruction: name, time, Hausdorff (absolute and relative to the
original's bounding-box diagonal), mean distance, triangles. --also adds further bodygen
meshes of the same stack (VTK runs once); --row prints one more line,
"row NAME vtk_h vtk_mean vtk_s [label h mean s]...", for tables.
"""
import argparse
import json
import math
import os
import sys
import time

import vtk
from vtk.util import numpy_support  # noqa: F401  (numpy is a dependency of python3-vtk9)
import numpy as np


def read_obj(path):
    pts, tris = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                pts.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                idx = [int(tok.split("/")[0]) for tok in line.split()[1:]]
                idx = [i - 1 if i > 0 else len(pts) + i for i in idx]
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return np.array(pts, dtype=float), np.array(tris, dtype=np.int64)


def to_polydata(pts, tris):
    poly = vtk.vtkPolyData()
    points = vtk.vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(np.ascontiguousarray(pts), deep=True))
    poly.SetPoints(points)
    cells = vtk.vtkCellArray()
    conn = np.hstack([np.full((len(tris), 1), 3, dtype=np.int64), tris]).ravel()
    cells.SetCells(len(tris), numpy_support.numpy_to_vtkIdTypeArray(conn, deep=True))
    poly.SetPolys(cells)
    return poly


def from_polydata(poly):
    pts = numpy_support.vtk_to_numpy(poly.GetPoints().GetData()).astype(float)
    conn = numpy_support.vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).astype(np.int64)
    offsets = numpy_support.vtk_to_numpy(poly.GetPolys().GetOffsetsArray()).astype(np.int64)
    tris = []
    for a, b in zip(offsets[:-1], offsets[1:]):
        for k in range(a + 1, b - 1):
            tris.append((conn[a], conn[k], conn[k + 1]))
    return pts, np.array(tris, dtype=np.int64)


def vtk_rebuild(stack, resolution):
    """Contours -> vtkVoxelContoursToSurfaceFilter. The filter wants integer
    coordinates on unit-spaced slices, so x, y are scaled to `resolution`
    voxels across the stack and slice k is put at z = k; the output's z is
    mapped back through the slices' heights (they may be unevenly spaced)."""
    slices = stack["slices"]
    zs = [s["z"] for s in slices]
    allp = np.array([p for s in slices for c in s["contours"] for p in c["points"]], dtype=float)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    scale = resolution / max(hi - lo)
    origin = lo - 2.0 / scale
    points = vtk.vtkPoints()
    polys = vtk.vtkCellArray()
    for k, s in enumerate(slices):
        for c in s["contours"]:
            ids = []
            for x, y in c["points"]:
                ids.append(points.InsertNextPoint(round((x - origin[0]) * scale), round((y - origin[1]) * scale), k))
            polys.InsertNextCell(len(ids))
            for i in ids:
                polys.InsertCellPoint(i)
    poly = vtk.vtkPolyData()
    poly.SetPoints(points)
    poly.SetPolys(polys)
    t0 = time.process_time()  # CPU time: the machine may be shared
    f = vtk.vtkVoxelContoursToSurfaceFilter()
    f.SetInputData(poly)
    f.SetMemoryLimitInBytes(1 << 30)
    f.Update()
    seconds = time.process_time() - t0
    pts, tris = from_polydata(f.GetOutput())
    # Back to model units: x, y unscaled; z through the slice heights.
    out = np.empty_like(pts)
    out[:, 0] = pts[:, 0] / scale + origin[0]
    out[:, 1] = pts[:, 1] / scale + origin[1]
    out[:, 2] = np.interp(pts[:, 2], np.arange(len(zs)), zs)
    return out, tris, seconds


def samples(pts, tris, zlo, zhi):
    s = np.vstack([pts, pts[tris].mean(axis=1)]) if len(tris) else pts
    return s[(s[:, 2] >= zlo) & (s[:, 2] <= zhi)]


def distances(sample_points, surface):
    d = vtk.vtkImplicitPolyDataDistance()
    d.SetInput(surface)
    # All points in one call (the same EvaluateFunction per point, without a Python loop).
    values = vtk.vtkDoubleArray()
    d.FunctionValue(numpy_support.numpy_to_vtk(np.ascontiguousarray(sample_points, dtype=float), deep=True), values)
    return np.abs(numpy_support.vtk_to_numpy(values).astype(float))


def hausdorff(a_pts, a_tris, b_pts, b_tris, zlo, zhi):
    a_poly, b_poly = to_polydata(a_pts, a_tris), to_polydata(b_pts, b_tris)
    sa, sb = samples(a_pts, a_tris, zlo, zhi), samples(b_pts, b_tris, zlo, zhi)
    ab = distances(sa, b_poly)
    ba = distances(sb, a_poly)
    if os.environ.get("HAUSDORFF_WHERE"):  # where the worst samples lie, for diagnosis
        for name, s, d in (("rebuilt->original", sa, ab), ("original->rebuilt", sb, ba)):
            for i in np.argsort(d)[-3:]:
                print(f"  {name}: {d[i]:.5f} at {s[i]}")
    return max(ab.max(), ba.max()), (ab.sum() + ba.sum()) / (len(ab) + len(ba))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("stack")
    ap.add_argument("original")
    ap.add_argument("bodygen")
    ap.add_argument("--resolution", type=int, default=256)
    ap.add_argument("--bodygen-seconds", type=float, default=float("nan"))
    ap.add_argument("--label", default="bodygen")
    ap.add_argument("--also", nargs=3, action="append", default=[], metavar=("LABEL", "OBJ", "SECONDS"))
    ap.add_argument("--row")
    args = ap.parse_args()

    with open(args.stack) as f:
        stack = json.load(f)
    zs = [s["z"] for s in stack["slices"]]
    zlo, zhi = min(zs), max(zs)
    orig_pts, orig_tris = read_obj(args.original)
    diag = float(np.linalg.norm(orig_pts.max(axis=0) - orig_pts.min(axis=0)))

    bg_pts, bg_tris = read_obj(args.bodygen)
    v_pts, v_tris, v_seconds = vtk_rebuild(stack, args.resolution)

    rows = [(args.label, args.bodygen_seconds, bg_pts, bg_tris), (f"vtk voxel r={args.resolution}", v_seconds, v_pts, v_tris)]
    results = []
    for name, seconds, pts, tris in rows:
        h, mean = hausdorff(pts, tris, orig_pts, orig_tris, zlo, zhi)
        results.append((name, seconds, h, mean, len(tris)))
        print(f"{name:24s} cpu {seconds:8.3f} s  hausdorff {h:.5f} ({h / diag:.2e} of diag)  "
              f"mean {mean:.5f}  triangles {len(tris)}")
    (_, bs, bh, bm, _), (_, vs, vh, vm, _) = results
    print(f"ratio bodygen/vtk: hausdorff {bh / vh:.3f}  mean {bm / vm:.3f}  time {bs / vs:.3f}"
          f"  -> bodygen {'not worse' if bh <= vh else 'WORSE'} than VTK on Hausdorff")
    row = [args.row, f"{vh:.6g}", f"{vm:.4g}", f"{vs:.4g}", args.label, f"{bh:.6g}", f"{bm:.4g}", f"{bs:.4g}"]
    for label, obj, seconds in args.also:
        pts, tris = read_obj(obj)
        h, mean = hausdorff(pts, tris, orig_pts, orig_tris, zlo, zhi)
        print(f"{label:24s} cpu {float(seconds):8.3f} s  hausdorff {h:.5f} ({h / diag:.2e} of diag)  "
              f"mean {mean:.5f}  triangles {len(tris)}  ratio to vtk {h / vh:.3f}")
        row += [label, f"{h:.6g}", f"{mean:.4g}", f"{float(seconds):.4g}"]
    if args.row:
        print("row " + " ".join(row))
    return 0


if __name__ == "__main__":
    sys.exit(main())
