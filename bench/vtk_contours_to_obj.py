#!/usr/bin/env python3
"""VTK's whole route from a contour stack to a mesh file, as one process (the
VTK side of bench/time_vs_vtk.sh): read STACK.contours.json, build the
polygons the way reconstruct_vs_vtk.py does (x, y scaled to RESOLUTION voxels,
slice k at z = k), run vtkVoxelContoursToSurfaceFilter, map z back through the
slice heights and write OUT.obj with vtkOBJWriter. Imports only the VTK modules
it uses (and numpy for the z mapping). Prints the filter's Update() CPU seconds alone on stdout.

usage: vtk_contours_to_obj.py STACK.contours.json OUT.obj [--resolution N]
"""
import argparse
import json
import time

import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersGeneral import vtkVoxelContoursToSurfaceFilter
from vtkmodules.vtkIOGeometry import vtkOBJWriter


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("stack")
    ap.add_argument("out")
    ap.add_argument("--resolution", type=int, default=256)
    args = ap.parse_args()
    with open(args.stack) as f:
        slices = json.load(f)["slices"]
    xs = [p[0] for s in slices for c in s["contours"] for p in c["points"]]
    ys = [p[1] for s in slices for c in s["contours"] for p in c["points"]]
    scale = args.resolution / max(max(xs) - min(xs), max(ys) - min(ys))
    ox, oy = min(xs) - 2.0 / scale, min(ys) - 2.0 / scale
    points, polys = vtkPoints(), vtkCellArray()
    for k, s in enumerate(slices):
        for c in s["contours"]:
            polys.InsertNextCell(len(c["points"]))
            for x, y in c["points"]:
                polys.InsertCellPoint(points.InsertNextPoint(round((x - ox) * scale), round((y - oy) * scale), k))
    poly = vtkPolyData()
    poly.SetPoints(points)
    poly.SetPolys(polys)
    t0 = time.process_time()
    f = vtkVoxelContoursToSurfaceFilter()
    f.SetInputData(poly)
    f.SetMemoryLimitInBytes(1 << 30)
    f.Update()
    update_seconds = time.process_time() - t0
    out = f.GetOutput()
    # Back to model units, vectorised (slices may be unevenly spaced).
    xyz = numpy_support.vtk_to_numpy(out.GetPoints().GetData()).astype(float)
    xyz[:, 0] = xyz[:, 0] / scale + ox
    xyz[:, 1] = xyz[:, 1] / scale + oy
    xyz[:, 2] = np.interp(xyz[:, 2], np.arange(len(slices)), [s["z"] for s in slices])
    out.GetPoints().SetData(numpy_support.numpy_to_vtk(np.ascontiguousarray(xyz), deep=True))
    w = vtkOBJWriter()
    w.SetInputData(out)
    w.SetFileName(args.out)
    w.Write()
    print(f"{update_seconds:.4f}")


if __name__ == "__main__":
    main()
