#!/usr/bin/env python3
"""Where a reconstruction's Hausdorff maximum lies (issue 23): the samples of
each mesh (bodygen linear, further bodygen meshes, VTK's voxel route) whose
distance to the true surface is at least min(0.6 x VTK's H, 0.8 x the mesh's
own H), grouped by region kind and direction, with the worst sample of each
group: where (x y z), in which slice gap and at what fraction of it, and for
a true-surface sample the other meshes' distance at the same point (when all
miss it, the stack does not show it).

The region kind is the construction of the nearest triangle of the linear
mesh, read from a tag file (one integer per triangle of the linear mesh, in
its order): 1 band, 2 open-holes, 3 nested, 4 partition, 5 union-ring,
6 partition-detached, 7 hull-ring, 8 slab, 9 cap, 10 slab-cap. bodygen does
not write it; /work/notes/s6-23-diag.patch is the probe that does (the
environment variable BODY_DIAG_TAGS names the file). Without a tag file every
kind is "-".

usage: hausdorff_regions.py STACK.contours.json ORIGINAL.obj LINEAR.obj TAGS|- [LABEL OBJ]...
Same sampling, slab and VTK run (256 voxels) as reconstruct_vs_vtk.py.
"""
import json
import os
import sys

import numpy as np
import vtk

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import reconstruct_vs_vtk as R  # noqa: E402

KIND = {1: "band", 2: "open-holes", 3: "nested", 4: "partition", 5: "union-ring", 6: "partition-detached",
        7: "hull-ring", 8: "slab", 9: "cap", 10: "slab-cap"}


def nearest_cell(locator, p):
    cp, cid, sid, d2 = [0.0, 0.0, 0.0], vtk.reference(0), vtk.reference(0), vtk.reference(0.0)
    locator.FindClosestPoint(list(p), cp, cid, sid, d2)
    return int(cid)


def main():
    stack_path, original, linear, tagfile = sys.argv[1:5]
    others = sys.argv[5:]
    stack = json.load(open(stack_path))
    zs = np.array([s["z"] for s in stack["slices"]])
    zlo, zhi = zs.min(), zs.max()
    o_pts, o_tris = R.read_obj(original)
    meshes = [("linear",) + R.read_obj(linear)]
    for i in range(0, len(others), 2):
        meshes.append((others[i],) + R.read_obj(others[i + 1]))
    v_pts, v_tris, _ = R.vtk_rebuild(stack, 256)
    meshes.append(("vtk", v_pts, v_tris))
    tags = np.loadtxt(tagfile, dtype=int) if tagfile != "-" else None
    locator = vtk.vtkStaticCellLocator()
    locator.SetDataSet(R.to_polydata(meshes[0][1], meshes[0][2]))
    locator.BuildLocator()
    polys = {name: R.to_polydata(pts, tris) for name, pts, tris in meshes}
    o_poly = R.to_polydata(o_pts, o_tris)
    res = {}
    for name, pts, tris in meshes:
        sa, sb = R.samples(pts, tris, zlo, zhi), R.samples(o_pts, o_tris, zlo, zhi)
        res[name] = (sa, R.distances(sa, o_poly), sb, R.distances(sb, polys[name]))
    vh = max(res["vtk"][1].max(), res["vtk"][3].max())
    print(f"## {os.path.basename(stack_path)}: VTK H {vh:.5f}, 0.6 x VTK {0.6 * vh:.5f}, mean gap {np.diff(zs).mean():.5f}")
    for name, (sa, da, sb, db) in res.items():
        h = max(da.max(), db.max())
        groups = {}
        for direction, s, d in (("mesh->true", sa, da), ("true->mesh", sb, db)):
            for i in np.argsort(d)[::-1]:
                if d[i] < min(0.6 * vh, 0.8 * h):
                    break
                p = s[i]
                k = int(min(max(np.searchsorted(zs, p[2], side="right") - 1, 0), len(zs) - 2))
                t = (p[2] - zs[k]) / (zs[k + 1] - zs[k])
                kind = KIND.get(int(tags[nearest_cell(locator, p)]), "?") if tags is not None else "-"
                g = groups.setdefault((kind, direction), [0, 0.0, None])
                g[0] += 1
                if d[i] > g[1]:
                    g[1], g[2] = d[i], (p, k, t)
        print(f"- {name}: H {h:.5f} ({h / vh:.2f} x VTK)")
        print("  | region | direction | samples | worst | x VTK H | where (x y z) | gap + fraction | others there |")
        print("  |---|---|---|---|---|---|---|---|")
        for (kind, direction), (n, m, (p, k, t)) in sorted(groups.items(), key=lambda kv: -kv[1][1]):
            there = ""
            if direction == "true->mesh":
                there = " ".join(f"{o} {R.distances(np.array([p]), polys[o])[0]:.4f}" for o in polys if o != name)
            print(f"  | {kind} | {direction} | {n} | {m:.5f} | {m / vh:.2f} | {np.round(p, 4).tolist()} | "
                  f"{k} + {t:.2f} | {there} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
