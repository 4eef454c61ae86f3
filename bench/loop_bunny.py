#!/usr/bin/python3
"""Writes the bunny Loop-subdivided N times (smooth, unlike the midpoint
subdivision the tests use) as an OBJ: the issue-24 "1M smooth dense mesh".

usage: bench/loop_bunny.py OUT.obj [LEVELS=2] [IN=/usr/share/glmark2/models/bunny.obj]
Needs Debian python3-vtk9 (vtkLoopSubdivisionFilter)."""
import sys

import vtk


def main():
    out = sys.argv[1]
    levels = int(sys.argv[2]) if len(sys.argv) > 2 else 2
    src = sys.argv[3] if len(sys.argv) > 3 else "/usr/share/glmark2/models/bunny.obj"
    reader = vtk.vtkOBJReader()
    reader.SetFileName(src)
    clean = vtk.vtkCleanPolyData()  # merge the OBJ's duplicated vertices so the surface is connected
    clean.SetInputConnection(reader.GetOutputPort())
    tri = vtk.vtkTriangleFilter()
    tri.SetInputConnection(clean.GetOutputPort())
    loop = vtk.vtkLoopSubdivisionFilter()
    loop.SetNumberOfSubdivisions(levels)
    loop.SetInputConnection(tri.GetOutputPort())
    loop.Update()
    mesh = loop.GetOutput()
    pts = mesh.GetPoints()
    with open(out, "w") as f:
        for i in range(pts.GetNumberOfPoints()):
            x, y, z = pts.GetPoint(i)
            f.write(f"v {x:.7g} {y:.7g} {z:.7g}\n")
        ids = vtk.vtkIdList()
        polys = mesh.GetPolys()
        polys.InitTraversal()
        while polys.GetNextCell(ids):
            f.write("f " + " ".join(str(ids.GetId(k) + 1) for k in range(ids.GetNumberOfIds())) + "\n")
    print(f"{out}: {pts.GetNumberOfPoints()} vertices, {mesh.GetNumberOfPolys()} triangles")


if __name__ == "__main__":
    main()
