# Reads a VRML97 file with VTK's vtkVRMLImporter (an independent reader) and
# prints one line per shape: triangles, then the diffuse colour.
import sys

import vtk

importer = vtk.vtkVRMLImporter()
importer.SetFileName(sys.argv[1])
importer.Read()
actors = importer.GetRenderer().GetActors()
actors.InitTraversal()
for _ in range(actors.GetNumberOfItems()):
    actor = actors.GetNextActor()
    actor.GetMapper().Update()
    data = actor.GetMapper().GetInput()
    r, g, b = actor.GetProperty().GetDiffuseColor()
    print(data.GetNumberOfCells(), data.GetNumberOfPoints(), "%.4f %.4f %.4f" % (r, g, b))
