#!/usr/bin/env python3
"""AAL atlas -> one mesh per region: bodygen (contours + build) against VTK's
discrete route (vtkDiscreteFlyingEdges3D + vtkWindowedSincPolyDataFilter, as 3D
Slicer does for label maps), in the same run. Prints a markdown table: wall
time, triangles, closed manifolds, volume against the voxel count, and boundary
fidelity (distances between each mesh and its region's voxel-face surface,
both directions, in mm). Ratios are against the VTK route of the same run.

usage: import_vs_vtk.py BODYGEN ATLAS NAMES WORKDIR
"""
import concurrent.futures
import json
import os
import subprocess
import sys
import time

import numpy as np
import vtk
from vtk.util import numpy_support as ns

BODYGEN, ATLAS, NAMES, WORK = sys.argv[1:5]
MIN_AREA = 3  # scripts/build-sample.sh drops per-slice islands of 1-3 voxels
os.makedirs(WORK, exist_ok=True)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


# ---------------------------------------------------------------- the atlas, voxel truth
reader = vtk.vtkNIFTIImageReader()
reader.SetFileName(ATLAS)
reader.Update()
image = reader.GetOutput()
dims = image.GetDimensions()
labels = ns.vtk_to_numpy(image.GetPointData().GetScalars()).reshape(dims[2], dims[1], dims[0])  # [k][j][i]
sform = reader.GetSFormMatrix() or reader.GetQFormMatrix()
M = np.array([[sform.GetElement(r, c) for c in range(4)] for r in range(4)])
# vtkNIFTIImageReader keeps the spacing on the image and puts the rest in the matrix.
spacing = np.array(image.GetSpacing())
origin = np.array(image.GetOrigin())
voxel_volume = abs(np.linalg.det(M[:3, :3])) * np.prod(spacing)
present = [int(v) for v in np.unique(labels) if v != 0]


def to_scanner(ijk):
    """voxel index (N x 3, i j k) -> scanner mm"""
    p = ijk * spacing + origin
    return p @ M[:3, :3].T + M[:3, 3]


def polydata(points, cells, per_cell):
    """vtkPolyData from an (n x 3) point array and an (m x per_cell) index array."""
    pts = vtk.vtkPoints()
    pts.SetData(ns.numpy_to_vtk(np.ascontiguousarray(points, dtype=float), deep=True))
    conn = np.hstack([np.full((len(cells), 1), per_cell), cells]).astype(np.int64).ravel()
    arr = vtk.vtkCellArray()
    arr.SetCells(len(cells), ns.numpy_to_vtkIdTypeArray(conn, deep=True))
    poly = vtk.vtkPolyData()
    poly.SetPoints(pts)
    poly.SetPolys(arr)
    return poly


def voxel_surface(label):
    """The region's voxel-face surface as a vtkPolyData of quads, in scanner mm."""
    m = np.pad(labels == label, 1)
    groups = []
    for axis in range(3):  # axis in array order: 0 k, 1 j, 2 i
        d = np.diff(m.astype(np.int8), axis=axis)
        idx = np.argwhere(d != 0).astype(float) - 1.0  # padded -> voxel index of the lower voxel
        if len(idx) == 0:
            continue
        idx[:, axis] += 0.5  # the face lies halfway
        ijk = idx[:, ::-1]
        a = 2 - axis  # the face normal in i j k order
        u, v = (a + 1) % 3, (a + 2) % 3
        corners = []
        for du, dv in ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)):
            c = ijk.copy()
            c[:, u] += du
            c[:, v] += dv
            corners.append(c)
        groups.append(np.stack(corners, axis=1))  # (n, 4, 3)
    quads = np.concatenate(groups)
    points = to_scanner(quads.reshape(-1, 3))
    return polydata(points, np.arange(len(points)).reshape(-1, 4), 4)


def distances(points, surface):
    loc = vtk.vtkCellLocator()
    loc.SetDataSet(surface)
    loc.BuildLocator()
    out = np.empty(len(points))
    closest = [0.0, 0.0, 0.0]
    cell, sub, d2 = vtk.reference(0), vtk.reference(0), vtk.reference(0.0)
    for i, p in enumerate(points):
        loc.FindClosestPoint(p, closest, cell, sub, d2)
        out[i] = float(d2) ** 0.5
    return out


def triangles_of(poly):
    """(points n x 3, triangles m x 3) of a vtkPolyData of triangles (others triangulated)."""
    tri = vtk.vtkTriangleFilter()
    tri.SetInputData(poly)
    tri.PassVertsOff()
    tri.PassLinesOff()
    tri.Update()
    out = tri.GetOutput()
    pts = ns.vtk_to_numpy(out.GetPoints().GetData()).astype(float)
    conn = ns.vtk_to_numpy(out.GetPolys().GetConnectivityArray()).astype(np.int64)
    return pts, conn.reshape(-1, 3)


def is_closed_manifold(poly):
    """What bodygen's Mesh::closed_manifold() asks (shared/mesh.h), for either
    side: every edge in exactly two triangles traversed in opposite directions,
    every vertex's fan one disc, no triangle with a repeated vertex or zero area.
    (vtkFeatureEdges alone sees only boundary and non-manifold edges.)"""
    pts, tris = triangles_of(poly)
    if len(tris) == 0:
        return False
    if np.any((tris[:, 0] == tris[:, 1]) | (tris[:, 1] == tris[:, 2]) | (tris[:, 0] == tris[:, 2])):
        return False
    a, b, c = pts[tris[:, 0]], pts[tris[:, 1]], pts[tris[:, 2]]
    if np.any(np.linalg.norm(np.cross(b - a, c - a), axis=1) == 0.0):
        return False
    directed = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    n = int(tris.max()) + 1
    key = directed[:, 0] * n + directed[:, 1]
    if len(np.unique(key)) != len(key):  # an edge twice the same way: misoriented or non-manifold
        return False
    if not np.all(np.isin(directed[:, 1] * n + directed[:, 0], key)):  # an edge without its twin: boundary
        return False
    # Vertex fans: around each vertex, the opposite edges (b, c) of its triangles
    # must chain into one cycle: with paired edges, each vertex's fan is a union
    # of cycles, one cycle iff (fan edges) == (distinct fan vertices) and connected.
    corner = np.concatenate([tris[:, [0, 1, 2]], tris[:, [1, 2, 0]], tris[:, [2, 0, 1]]])
    order = np.argsort(corner[:, 0], kind="stable")
    corner = corner[order]
    starts = np.flatnonzero(np.r_[True, corner[1:, 0] != corner[:-1, 0]])
    ends = np.r_[starts[1:], len(corner)]
    for s0, e0 in zip(starts, ends):
        nxt = dict(zip(corner[s0:e0, 1].tolist(), corner[s0:e0, 2].tolist()))
        if len(nxt) != e0 - s0:
            return False
        v0 = corner[s0, 1]
        v, steps = nxt[v0], 1
        while v != v0 and steps <= len(nxt):
            v = nxt.get(v, v0)
            steps += 1
        if steps != len(nxt):
            return False
    return True


def volume(poly):
    tri = vtk.vtkTriangleFilter()
    tri.SetInputData(poly)
    mp = vtk.vtkMassProperties()
    mp.SetInputConnection(tri.GetOutputPort())
    mp.Update()
    return mp.GetVolume()


# ---------------------------------------------------------------- bodygen
def bodygen_route(jobs, min_area):
    """`bodygen contours` then one `bodygen build` of the whole stack, both with
    --jobs; if that build fails, each region on its own says which ones fail."""
    stack = os.path.join(WORK, "aal.contours.json")
    obj = os.path.join(WORK, "aal.obj")
    t0 = time.perf_counter()
    rc, out = run([BODYGEN, "contours", ATLAS, "--labels", NAMES, "--min-area", str(min_area), "--jobs", str(jobs),
                   "--quiet", "-o", stack])
    if rc != 0:
        raise SystemExit("bodygen contours failed: " + out)
    t_contours = time.perf_counter() - t0
    t1 = time.perf_counter()
    rc, out = run([BODYGEN, "build", stack, "--jobs", str(jobs), "--quiet", "-o", obj])
    t_build = time.perf_counter() - t1
    if rc == 0:
        return t_contours, t_build, read_obj(obj), []
    data = json.load(open(stack))
    tasks = []
    for s in data["structures"]:
        part = dict(data)
        part["structures"] = [s]
        part["slices"] = [{"z": sl["z"], "contours": [c for c in sl["contours"] if c["structure"] == s["id"]]}
                          for sl in data["slices"]]
        part["slices"] = [sl for sl in part["slices"] if sl["contours"]]
        path = os.path.join(WORK, "%s.contours.json" % s["id"])
        json.dump(part, open(path, "w"))
        tasks.append((s["id"], path, os.path.join(WORK, "%s.obj" % s["id"])))

    def build(task):
        sid, p, o = task
        rc, out = run([BODYGEN, "build", p, "-o", o, "--quiet"])
        return sid, o, rc, out

    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        results = list(pool.map(build, tasks))
    errors = ["%s: %s" % (sid, out.strip()) for sid, _, rc, out in results if rc != 0]
    meshes = {}
    for sid, o, rc, _ in results:
        if rc == 0:
            meshes.update(read_obj(o))
    return t_contours, t_build, meshes, errors


def read_obj(path):
    meshes, name, verts, faces = {}, None, [], {}
    for line in open(path):
        if line.startswith("o "):
            name = line[2:].strip()
            faces[name] = []
        elif line.startswith("v "):
            verts.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            faces[name].append([int(t.split("/")[0]) - 1 for t in line.split()[1:]])
    verts = np.array(verts)
    for name, fs in faces.items():
        fs = np.array(fs, dtype=np.int64)
        used, inverse = np.unique(fs, return_inverse=True)
        meshes[name] = polydata(verts[used], inverse.reshape(-1, 3), 3)
    return meshes


# ---------------------------------------------------------------- VTK discrete route
def vtk_route():
    t0 = time.perf_counter()
    fe = vtk.vtkDiscreteFlyingEdges3D()
    fe.SetInputConnection(reader.GetOutputPort())
    for n, l in enumerate(present):
        fe.SetValue(n, l)
    fe.ComputeScalarsOn()
    fe.ComputeNormalsOff()
    fe.ComputeGradientsOff()
    fe.Update()
    surface = fe.GetOutput()
    meshes = {}
    for l in present:
        th = vtk.vtkThreshold()
        th.SetInputData(surface)
        th.SetLowerThreshold(l - 0.5)
        th.SetUpperThreshold(l + 0.5)
        th.SetThresholdFunction(vtk.vtkThreshold.THRESHOLD_BETWEEN)
        # Flying edges writes each triangle's label on its points (scalars named after the image array).
        th.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS,
                                  surface.GetPointData().GetScalars().GetName())
        geo = vtk.vtkGeometryFilter()
        geo.SetInputConnection(th.GetOutputPort())
        # Slicer's label-map smoothing: windowed sinc, smoothing factor 0.5 -> passband 10^(-4*0.5).
        smooth = vtk.vtkWindowedSincPolyDataFilter()
        smooth.SetInputConnection(geo.GetOutputPort())
        smooth.SetNumberOfIterations(20)
        smooth.SetPassBand(10 ** (-4.0 * 0.5))
        smooth.BoundarySmoothingOff()
        smooth.FeatureEdgeSmoothingOff()
        smooth.NonManifoldSmoothingOn()
        smooth.NormalizeCoordinatesOn()
        xf = vtk.vtkTransform()
        xf.SetMatrix(sform)
        tf = vtk.vtkTransformPolyDataFilter()
        tf.SetInputConnection(smooth.GetOutputPort())
        tf.SetTransform(xf)
        tf.Update()
        meshes[l] = tf.GetOutput()
    return time.perf_counter() - t0, meshes


# ---------------------------------------------------------------- measure
names = {}
for line in open(NAMES):
    parts = line.split()
    if len(parts) >= 2 and parts[0].isdigit():
        names[int(parts[0])] = parts[1]
by_name = {v: k for k, v in names.items()}
surfaces = {l: voxel_surface(l) for l in present}
counts = {l: int((labels == l).sum()) for l in present}


def score(meshes_by_label):
    tris, closed, vol_err, d_mesh, d_vox = 0, 0, [], [], []
    for l, poly in meshes_by_label.items():
        tris += poly.GetNumberOfPolys()
        closed += is_closed_manifold(poly)
        vol_err.append(100.0 * (abs(volume(poly)) / (counts[l] * voxel_volume) - 1.0))
        pts = ns.vtk_to_numpy(poly.GetPoints().GetData())
        d_mesh.append(distances(pts[:: max(1, len(pts) // 2000)], surfaces[l]))
        centres = ns.vtk_to_numpy(surfaces[l].GetPoints().GetData()).reshape(-1, 4, 3).mean(axis=1)
        d_vox.append(distances(centres[:: max(1, len(centres) // 2000)], poly))
    dm, dv = np.concatenate(d_mesh), np.concatenate(d_vox)
    return {"triangles": tris, "closed": closed, "regions": len(meshes_by_label),
            "vol_err_median": float(np.median(vol_err)), "vol_err_abs_max": float(np.max(np.abs(vol_err))),
            "mesh_to_voxels_mean": float(dm.mean()), "voxels_to_mesh_mean": float(dv.mean()),
            "hausdorff95": float(max(np.percentile(dm, 95), np.percentile(dv, 95)))}


rows = []
t_vtk, vtk_meshes = vtk_route()
rows.append(("VTK discrete flying edges + windowed sinc", 1, t_vtk, score(vtk_meshes), [], None))
# --min-area 3 as scripts/build-sample.sh (per-slice islands of 1-3 voxels
# dropped), and plain defaults (every island kept).
for min_area in (MIN_AREA, 0):
    for jobs in (1, 2):
        tc, tb, meshes, errors = bodygen_route(jobs, min_area)
        by_label = {by_name.get(n, n): m for n, m in meshes.items()}
        by_label = {k: v for k, v in by_label.items() if isinstance(k, int)}
        label = "bodygen contours%s + build, --jobs %d" % (" --min-area %g" % min_area if min_area else "", jobs)
        rows.append((label, jobs, tc + tb, score(by_label), errors, (tc, tb)))

base = rows[0][2]
print("AAL atlas %s: %d regions, %s voxels of %.3g mm^3\n" % (ATLAS, len(present), "x".join(map(str, dims)),
                                                               voxel_volume))
print("| route | wall s | vs VTK | regions built | closed 2-manifolds | triangles | vs VTK | volume err median / max %"
      " | mesh->voxels mm | voxels->mesh mm | 95% Hausdorff mm |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for name, jobs, t, s, errors, split in rows:
    extra = " (contours %.2f + meshes %.2f)" % split if split else ""
    print("| %s | %.2f%s | %.2fx | %d/%d | %d | %d | %.2fx | %+.1f / %.1f | %.3f | %.3f | %.3f |" % (
        name, t, extra, t / base, s["regions"], len(present), s["closed"], s["triangles"],
        s["triangles"] / rows[0][3]["triangles"], s["vol_err_median"], s["vol_err_abs_max"], s["mesh_to_voxels_mean"],
        s["voxels_to_mesh_mean"], s["hausdorff95"]))
print("\nclosed 2-manifolds: every edge in two triangles, opposite ways; every vertex fan one disc; no zero-area"
      " triangle (bodygen's Mesh::closed_manifold, applied to both sides).")
for name, _, _, _, errors, _ in rows[1:]:
    if errors:
        print("\n%s: regions the pipeline rejected:" % name)
        for e in errors:
            print("- " + e[:200])
