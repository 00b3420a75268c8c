"""Plain VTK Python: import the gpudelaunay package next to vtk, mesh, write .vtp, read back.

Run with /usr/bin/python3 and PYTHONPATH=<build>/python:
    TestGPUDelaunayPython.py <input.vtp> <output directory>
"""
import os
import sys

import vtk  # noqa: F401  (the package must work next to the full vtk module)
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkCommonCore import vtkPoints
from gpudelaunay import vtkGPUConstrainedDelaunay2D
from python_test_support import check


def main():
    source, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)

    reader = vtkXMLPolyDataReader()
    reader.SetFileName(source)

    seeds = vtkPolyData()
    seed_points = vtkPoints()
    seed_points.InsertNextPoint(2.0, 3.0, 0.0)
    seeds.SetPoints(seed_points)

    mesher = vtkGPUConstrainedDelaunay2D()
    mesher.SetInputConnection(reader.GetOutputPort())
    mesher.SetHoleSeedsData(seeds)
    mesher.SetMinimumAngle(28)
    mesher.SetBackendToCPU()
    mesher.RemoveExteriorOn()
    mesher.Update()

    mesh = mesher.GetOutput()
    ncells = mesh.GetNumberOfCells()
    check(ncells > 0, "no triangles")
    check(mesh.GetNumberOfPolys() == ncells, "not only triangles")
    for name in ("MinAngle", "MaxAngle", "RadiusEdgeRatio", "Area", "IsBad"):
        array = mesh.GetCellData().GetArray(name)
        check(array is not None and array.GetNumberOfTuples() == ncells, "cell array " + name)
    check(mesh.GetPointData().GetArray("PointType") is not None, "PointType")
    check(mesh.GetFieldData().GetAbstractArray("Backend").GetValue(0) in ("cpu", "gpu"),
          "Backend field")
    histogram = mesher.GetOutputDataObject(1)
    check(histogram.GetNumberOfRows() == 60, "histogram rows")
    counts = histogram.GetColumnByName("bin_values")
    check(sum(counts.GetValue(i) for i in range(60)) == ncells, "histogram total")

    path = os.path.join(outdir, "plate_mesh.vtp")
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(mesh)
    check(writer.Write() == 1, "write " + path)

    back = vtkXMLPolyDataReader()
    back.SetFileName(path)
    back.Update()
    copy = back.GetOutput()
    check(copy.GetNumberOfCells() == ncells, "cells read back")
    check(copy.GetNumberOfPoints() == mesh.GetNumberOfPoints(), "points read back")
    original = mesh.GetCellData().GetArray("MinAngle")
    reread = copy.GetCellData().GetArray("MinAngle")
    check(reread is not None and original.GetRange() == reread.GetRange(), "MinAngle read back")
    check(copy.GetFieldData().GetAbstractArray("Backend") is not None, "field data read back")
    print("%d triangles, %d points, min angle %.2f deg -> %s"
          % (ncells, copy.GetNumberOfPoints(), reread.GetRange()[0], path))


if __name__ == "__main__":
    main()
