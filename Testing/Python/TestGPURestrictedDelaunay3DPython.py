"""Plain VTK Python: vtkGPURestrictedDelaunay3D from the gpudelaunay package next to vtk; mesh
a closed surface, write the tetrahedra as .vtu and the surface as .vtp, read them back; a
refused parameter raises gpudelaunay.MeshingError.

Run with /usr/bin/python3 and PYTHONPATH=<build>/python:
    TestGPURestrictedDelaunay3DPython.py <closed surface .vtp> <output directory>
"""
import os
import sys

import vtk  # noqa: F401  (the package must work next to the full vtk module)
from vtkmodules.vtkIOXML import (vtkXMLPolyDataReader, vtkXMLPolyDataWriter,
                                 vtkXMLUnstructuredGridReader, vtkXMLUnstructuredGridWriter)
import gpudelaunay
from gpudelaunay import vtkGPURestrictedDelaunay3D
from python_test_support import check, write_and_read


def main():
    source, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)

    reader = vtkXMLPolyDataReader()
    reader.SetFileName(source)
    mesher = vtkGPURestrictedDelaunay3D()
    mesher.SetInputConnection(reader.GetOutputPort())
    mesher.SetFacetSize(0.25)
    mesher.SetFacetDistance(0.01)
    mesher.SetBackendToCPU()
    gpudelaunay.update(mesher)

    tets = mesher.GetOutput()
    ntets = tets.GetNumberOfCells()
    check(ntets > 0, "no tetrahedra")
    check(all(tets.GetCellType(i) == vtk.VTK_TETRA for i in range(ntets)), "not only tetrahedra")
    tet_arrays = ("RadiusEdgeRatio", "MinDihedralAngle", "MaxDihedralAngle", "Volume", "IsBad")
    for name in tet_arrays:
        array = tets.GetCellData().GetArray(name)
        check(array is not None and array.GetNumberOfTuples() == ntets, "cell array " + name)
    check(tets.GetPointData().GetArray("PointType") is not None, "PointType")
    check(tets.GetFieldData().GetAbstractArray("Backend").GetValue(0) == "cpu", "Backend field")

    surface = mesher.GetOutputDataObject(1)
    ntris = surface.GetNumberOfCells()
    surface_arrays = ("MinAngle", "Size", "Distance", "IsBad")
    for name in surface_arrays:
        array = surface.GetCellData().GetArray(name)
        check(array is not None and array.GetNumberOfTuples() == ntris, "surface array " + name)
    smallest = surface.GetCellData().GetArray("MinAngle").GetRange()[0]
    check(smallest >= 30 - 1e-4, "facet angle bound")

    histogram = mesher.GetOutputDataObject(2)
    check(histogram.GetNumberOfRows() == 180, "histogram rows")
    for column, total in (("DihedralAngleCount", 6 * ntets), ("FacetAngleCount", ntris)):
        counts = histogram.GetColumnByName(column)
        check(counts is not None and sum(counts.GetValue(i) for i in range(180)) == total,
              "histogram " + column)

    copy = write_and_read(tets, os.path.join(outdir, "hollow_sphere_rdt.vtu"),
                          vtkXMLUnstructuredGridWriter(), vtkXMLUnstructuredGridReader())
    check(copy.GetNumberOfCells() == ntets, "cells read back")
    for name in tet_arrays:
        check(copy.GetCellData().GetArray(name).GetRange() ==
              tets.GetCellData().GetArray(name).GetRange(), name + " read back")
    check(copy.GetFieldData().GetArray("FacetSize").GetValue(0) == 0.25, "field data read back")
    faces = write_and_read(surface, os.path.join(outdir, "hollow_sphere_rdt_surface.vtp"),
                           vtkXMLPolyDataWriter(), vtkXMLPolyDataReader())
    check(faces.GetNumberOfCells() == ntris, "surface read back")

    # Refused, not clamped: MeshingError with the core's status and message, empty outputs.
    mesher.SetCellRadiusEdgeRatio(0.5)
    try:
        gpudelaunay.update(mesher)
        check(False, "CellRadiusEdgeRatio 0.5 accepted")
    except gpudelaunay.MeshingError as e:
        check(e.status == "InvalidInput" and "radius-edge ratio" in e.message, "error %s" % e)
    check(mesher.GetOutput().GetNumberOfCells() == 0, "no tetrahedra after the error")
    check(mesher.GetOutputDataObject(1).GetNumberOfCells() == 0, "no surface after the error")
    print("%d tetrahedra, %d surface triangles, smallest facet angle %.2f deg -> %s"
          % (ntets, ntris, smallest, outdir))


if __name__ == "__main__":
    main()
