"""Plain VTK Python: vtkGPUQualityTetMesh from the gpudelaunay package next to vtk; mesh a
closed surface, write the tetrahedra as .vtu and the subfaces as .vtp, read them back.

Run with /usr/bin/python3 and PYTHONPATH=<build>/python:
    TestGPUQualityTetMeshPython.py <closed surface .vtp> <output directory>
"""
import os
import sys

import vtk  # noqa: F401  (the package must work next to the full vtk module)
from vtkmodules.vtkIOXML import (vtkXMLPolyDataReader, vtkXMLPolyDataWriter,
                                 vtkXMLUnstructuredGridReader, vtkXMLUnstructuredGridWriter)
from gpudelaunay import vtkGPUQualityTetMesh
from python_test_support import check, write_and_read


def main():
    source, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)

    reader = vtkXMLPolyDataReader()
    reader.SetFileName(source)
    mesher = vtkGPUQualityTetMesh()
    mesher.SetInputConnection(reader.GetOutputPort())
    mesher.SetRadiusEdgeRatio(1.4)
    mesher.SetMaximumVolume(0.01)
    mesher.SetBackendToCPU()
    mesher.Update()

    tets = mesher.GetOutput()
    ntets = tets.GetNumberOfCells()
    check(ntets > 0, "no tetrahedra")
    check(all(tets.GetCellType(i) == vtk.VTK_TETRA for i in range(ntets)), "not only tetrahedra")
    names = ("RadiusEdgeRatio", "MinDihedralAngle", "MaxDihedralAngle", "Volume", "IsBad",
             "Region")
    for name in names:
        array = tets.GetCellData().GetArray(name)
        check(array is not None and array.GetNumberOfTuples() == ntets, "cell array " + name)
    check(tets.GetCellData().GetArray("Volume").GetRange()[1] <= 0.01 * (1 + 1e-9),
          "volume bound")
    check(tets.GetPointData().GetArray("PointType") is not None, "PointType")
    check(tets.GetFieldData().GetAbstractArray("Backend").GetValue(0) in ("cpu", "gpu"),
          "Backend field")
    histogram = mesher.GetOutputDataObject(1)
    counts = histogram.GetColumnByName("DihedralAngleCount")
    check(histogram.GetNumberOfRows() == 180 and counts is not None, "histogram")
    check(sum(counts.GetValue(i) for i in range(180)) == 6 * ntets, "histogram total")
    subfaces = mesher.GetOutputDataObject(2)
    check(subfaces.GetNumberOfCells() > 0 and
          subfaces.GetCellData().GetArray("FacetId") is not None, "subfaces")

    copy = write_and_read(tets, os.path.join(outdir, "hollow_sphere.vtu"),
                          vtkXMLUnstructuredGridWriter(), vtkXMLUnstructuredGridReader())
    check(copy.GetNumberOfCells() == ntets, "cells read back")
    check(copy.GetNumberOfPoints() == tets.GetNumberOfPoints(), "points read back")
    for name in names:
        reread = copy.GetCellData().GetArray(name)
        check(reread is not None and
              reread.GetRange() == tets.GetCellData().GetArray(name).GetRange(),
              name + " read back")
    check(copy.GetFieldData().GetArray("BadTetrahedra") is not None, "field data read back")
    faces = write_and_read(subfaces, os.path.join(outdir, "hollow_sphere_subfaces.vtp"),
                           vtkXMLPolyDataWriter(), vtkXMLPolyDataReader())
    check(faces.GetNumberOfCells() == subfaces.GetNumberOfCells(), "subfaces read back")
    print("%d tetrahedra, %d points, smallest dihedral angle %.2f deg -> %s"
          % (ntets, copy.GetNumberOfPoints(),
             copy.GetCellData().GetArray("MinDihedralAngle").GetRange()[0], outdir))


if __name__ == "__main__":
    main()
