#!/usr/bin/env python3
"""Side-by-side helper for bench/reconstruct_vs_vtk.sh.

Rebuilds a contour stack (*.contours.json) with VTK's
vtkVoxelContoursToSurfaceFilter, then measures the symmetric Hausdorff
distance of each reconstruction to the original surface, restricted to the
slab the slices span (points of either surface with z outside it are ignored).
Each mesh is sampled area-uniformly within the slab (--samples points per mesh,
whatever its triangle count: systematic along the cumulative area, fixed seed,
so deterministic per OBJ) and each sample's distance to the other surface is
measured with vtkImplicitPolyDataDistance. The mean is the mean of the two
directions' means, so it does not depend on where a mesh puts its vertices.
The Hausdorff distance is the maximum over both directions of those samples,
of denser samples around the worst of them, and, as before, of each mesh's
vertices and triangle centroids, so it is never below the vertex-and-centroid
estimate.

usage: reconstruct_vs_vtk.py STACK.contours.json ORIGINAL.obj BODYGEN.obj [--resolution N]
                              [--samples K] [--also LABEL OBJ SECONDS]... [--row NAME]
Prints one line per reconstruction: name, time, Hausdorff (absolute and relative to the
original's bounding-box diagonal), area-sampled mean distance, triangles. --also adds further bodygen
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
    """The mesh's vertices and triangle centroids with z inside [zlo, zhi]."""
    s = np.vstack([pts, pts[tris].mean(axis=1)]) if len(tris) else pts
    return s[(s[:, 2] >= zlo) & (s[:, 2] <= zhi)]


def clip_to_slab(pts, tris, zlo, zhi):
    """The part of the surface with z inside [zlo, zhi], as an (n, 3, 3) array of
    triangle corners: triangles inside kept, triangles across a bound clipped
    (Sutherland-Hodgman against both planes, the polygon fanned)."""
    corners = pts[tris]
    z = corners[:, :, 2]
    inside = (z.min(axis=1) >= zlo) & (z.max(axis=1) <= zhi)
    across = ~inside & (z.max(axis=1) >= zlo) & (z.min(axis=1) <= zhi)
    out = [corners[inside]]
    extra = []
    for tri in corners[across]:
        poly = list(tri)
        for sign, bound in ((1.0, zlo), (-1.0, zhi)):
            clipped = []
            for i, p in enumerate(poly):
                q = poly[(i + 1) % len(poly)]
                p_in, q_in = sign * (p[2] - bound) >= 0, sign * (q[2] - bound) >= 0
                if p_in:
                    clipped.append(p)
                if p_in != q_in:
                    clipped.append(p + (bound - p[2]) / (q[2] - p[2]) * (q - p))
            poly = clipped
            if len(poly) < 3:
                break
        for k in range(1, len(poly) - 1):
            extra.append([poly[0], poly[k], poly[k + 1]])
    if extra:
        out.append(np.array(extra, dtype=float))
    return np.concatenate(out)


def area_samples(pts, tris, zlo, zhi, count, seed=23):
    """`count` points on the surface inside [zlo, zhi], each triangle getting
    points in proportion to its area (see samples_on)."""
    return samples_on(clip_to_slab(pts, tris, zlo, zhi), count, seed)[0]


def samples_on(corners, count, seed):
    """(points, triangle of each): `count` points on the triangles `corners`
    (n, 3, 3) in proportion to their areas: systematic sampling along the
    cumulative area (one seeded offset; a point's place inside its triangle's
    share gives one barycentric coordinate, a seeded random number the other)."""
    area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    cum = np.cumsum(area)
    rng = np.random.default_rng(seed)
    u = (np.arange(count) + rng.random()) * (cum[-1] / count)
    t = np.minimum(np.searchsorted(cum, u, side="right"), len(area) - 1)
    r1 = np.clip((u - (cum[t] - area[t])) / np.maximum(area[t], 1e-300), 0.0, 1.0)
    r2 = rng.random(count)
    s = np.sqrt(r1)
    a, b, c = corners[t, 0], corners[t, 1], corners[t, 2]
    return (1 - s)[:, None] * a + (s * (1 - r2))[:, None] * b + (s * r2)[:, None] * c, t


def refined_max(corners, points, tri_of, d, surface, seed, places=8, count=20000):
    """The largest distance to `surface` found by sampling `count` more points
    on the triangles around each of the `places` worst of `points` (samples on
    `corners`, distances `d`) that lie apart: a sampled maximum lies below the
    true one by up to the samples' spacing times the distance's slope, which
    for H on large triangles is a few per cent."""
    centroid = corners.mean(axis=1)
    radius = np.linalg.norm(corners - centroid[:, None, :], axis=2).max(axis=1)
    area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    spacing = math.sqrt(area.sum() / len(d))
    best, chosen = float(d.max()), []
    for i in np.argsort(d)[::-1][:5000]:
        x = points[i]
        reach = max(4 * spacing, 2 * radius[tri_of[i]])
        if any(np.linalg.norm(x - c) < r for c, r in chosen):
            continue
        chosen.append((x, reach))
        near = np.nonzero(np.linalg.norm(centroid - x, axis=1) < reach + radius)[0]
        s, _ = samples_on(corners[near], count, seed + len(chosen))
        best = max(best, float(distances(s, surface).max()))
        if len(chosen) == places:
            break
    return best


def distances(sample_points, surface):
    d = vtk.vtkImplicitPolyDataDistance()
    d.SetInput(surface)
    # All points in one call (the same EvaluateFunction per point, without a Python loop).
    values = vtk.vtkDoubleArray()
    d.FunctionValue(numpy_support.numpy_to_vtk(np.ascontiguousarray(sample_points, dtype=float), deep=True), values)
    return np.abs(numpy_support.vtk_to_numpy(values).astype(float))


def hausdorff(a_pts, a_tris, b_pts, b_tris, zlo, zhi, count, seed=23):
    """(Hausdorff, mean): the maximum over both directions of the area samples,
    the vertex-and-centroid samples and denser samples around the worst of them
    (refined_max); the mean of the two directions' means over the area samples."""
    a_poly, b_poly = to_polydata(a_pts, a_tris), to_polydata(b_pts, b_tris)
    h, means = 0.0, []
    for pts, tris, other, name in ((a_pts, a_tris, b_poly, "rebuilt->original"), (b_pts, b_tris, a_poly, "original->rebuilt")):
        corners = clip_to_slab(pts, tris, zlo, zhi)
        area_pts, tri_of = samples_on(corners, count, seed)
        d = distances(area_pts, other)
        means.append(d.mean())
        vc = samples(pts, tris, zlo, zhi)
        dv = distances(vc, other)
        h = max(h, float(dv.max()), refined_max(corners, area_pts, tri_of, d, other, seed))
        if os.environ.get("HAUSDORFF_WHERE"):  # where the worst samples lie, for diagnosis
            for s, ds in ((area_pts, d), (vc, dv)):
                for i in np.argsort(ds)[-3:]:
                    print(f"  {name}: {ds[i]:.5f} at {s[i]}")
    return h, 0.5 * (means[0] + means[1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("stack")
    ap.add_argument("original")
    ap.add_argument("bodygen")
    ap.add_argument("--resolution", type=int, default=256)
    ap.add_argument("--samples", type=int, default=1000000, help="area samples per mesh")
    ap.add_argument("--seed", type=int, default=23, help="the area samples' seed (to see their spread)")
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
        h, mean = hausdorff(pts, tris, orig_pts, orig_tris, zlo, zhi, args.samples, args.seed)
        results.append((name, seconds, h, mean, len(tris)))
        print(f"{name:24s} cpu {seconds:8.3f} s  hausdorff {h:.5f} ({h / diag:.2e} of diag)  "
              f"mean {mean:.6g}  triangles {len(tris)}")
    (_, bs, bh, bm, _), (_, vs, vh, vm, _) = results
    print(f"ratio bodygen/vtk: hausdorff {bh / vh:.3f}  mean {bm / vm:.3f}  time {bs / vs:.3f}"
          f"  -> bodygen {'not worse' if bh <= vh else 'WORSE'} than VTK on Hausdorff")
    row = [args.row, f"{vh:.6g}", f"{vm:.5g}", f"{vs:.4g}", args.label, f"{bh:.6g}", f"{bm:.5g}", f"{bs:.4g}"]
    for label, obj, seconds in args.also:
        pts, tris = read_obj(obj)
        h, mean = hausdorff(pts, tris, orig_pts, orig_tris, zlo, zhi, args.samples, args.seed)
        print(f"{label:24s} cpu {float(seconds):8.3f} s  hausdorff {h:.5f} ({h / diag:.2e} of diag)  "
              f"mean {mean:.6g}  triangles {len(tris)}  ratio to vtk {h / vh:.3f}")
        row += [label, f"{h:.6g}", f"{mean:.5g}", f"{float(seconds):.4g}"]
    if args.row:
        print("row " + " ".join(row))
    return 0


if __name__ == "__main__":
    sys.exit(main())
