"""A script tells a failed run from an empty result: gpudelaunay.update raises MeshingError
(with the core's status and message) where Update() alone leaves an empty output, and the
filters and readers set their error code.

Run with /usr/bin/python3 and PYTHONPATH=<build>/python:
    TestGPUDelaunayPythonErrors.py <plate.vtp> <broken.poly>
"""
import sys

import vtk  # noqa: F401  (the package must work next to the full vtk module)
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
import gpudelaunay
from python_test_support import check


def raised(algorithm):
    """The MeshingError gpudelaunay.update raises, or None."""
    try:
        gpudelaunay.update(algorithm)
    except gpudelaunay.MeshingError as e:
        return e
    return None


def main():
    plate, broken = sys.argv[1], sys.argv[2]
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(plate)
    mesher = gpudelaunay.vtkGPUConstrainedDelaunay2D()
    mesher.SetInputConnection(reader.GetOutputPort())
    mesher.SetBackendToCPU()

    # A bound out of range: refused (not clamped), and the script sees it.
    mesher.SetMinimumAngle(40)
    error = raised(mesher)
    check(error is not None, "MinimumAngle 40 did not raise")
    check(error.status == "InvalidInput" and "out of range [0, 34]" in error.message,
          "message: %s" % error)
    check(mesher.GetErrorCode() != 0, "error code after a failure")
    check(mesher.GetOutput().GetNumberOfCells() == 0, "empty output after a failure")

    # A good run: no exception, error code cleared.
    mesher.SetMinimumAngle(25)
    check(raised(mesher) is None, "a good run raised")
    check(mesher.GetErrorCode() == 0, "error code after a good run")
    check(mesher.GetOutput().GetNumberOfCells() > 0, "triangles")

    # Backend GPU: an error naming the missing device on a machine without a GPU, a mesh
    # made on the GPU on one with a GPU.
    mesher.SetBackendToGPU()
    error = raised(mesher)
    if error is not None:
        check("no usable CUDA device" in str(error), "GPU message: %s" % error)
    else:
        backend = mesher.GetOutput().GetFieldData().GetAbstractArray("Backend").GetValue(0)
        check(backend == "gpu", "Backend GPU ran on %s" % backend)

    # An empty input is an empty result, not a failure.
    empty = gpudelaunay.vtkGPUConstrainedDelaunay2D()
    empty.SetInputData(vtkPolyData())
    check(raised(empty) is None, "empty input raised")
    check(empty.GetOutput().GetNumberOfCells() == 0 and empty.GetErrorCode() == 0, "empty")

    # A malformed file: the reader's IoError with file and line.
    poly = gpudelaunay.vtkTriangleTetGenReader()
    poly.SetFileName(broken)
    error = raised(poly)
    check(error is not None and error.status == "IoError" and "broken_truncated.poly:5"
          in error.message, "reader error: %s" % error)
    print("failures raise MeshingError; empty results do not")


if __name__ == "__main__":
    main()
