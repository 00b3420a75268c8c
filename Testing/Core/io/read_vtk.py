"""Reads a .vtu/.vtp/.vtk (legacy polydata) with VTK and checks its sizes and arrays, and that tetrahedra have a
positive volume in VTK's convention.

usage: read_vtk.py FILE POINTS CELLS CELL_TYPE [ARRAY ...]
Exit 0 on success, 1 on a mismatch, 77 when VTK is not importable.
"""
import sys

try:
    from vtkmodules.vtkIOLegacy import vtkPolyDataReader
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader
except ImportError:
    sys.exit(77)

path, points, cells, cell_type = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
if path.endswith(".vtk"):
    reader = vtkPolyDataReader()
elif path.endswith(".vtp"):
    reader = vtkXMLPolyDataReader()
else:
    reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(path)
reader.Update()
data = reader.GetOutput()
errors = []
if data.GetNumberOfPoints() != points:
    errors.append("points %d != %d" % (data.GetNumberOfPoints(), points))
if data.GetNumberOfCells() != cells:
    errors.append("cells %d != %d" % (data.GetNumberOfCells(), cells))
for i in range(data.GetNumberOfCells()):
    if data.GetCellType(i) != cell_type:
        errors.append("cell %d has type %d" % (i, data.GetCellType(i)))
        break
for i in range(data.GetNumberOfCells()):
    cell = data.GetCell(i)
    if cell.GetCellType() != 10:
        continue
    p = [cell.GetPoints().GetPoint(k) for k in range(4)]
    u, v, w = ([p[k][j] - p[0][j] for j in range(3)] for k in (1, 2, 3))
    volume = ((u[1] * v[2] - u[2] * v[1]) * w[0] + (u[2] * v[0] - u[0] * v[2]) * w[1]
              + (u[0] * v[1] - u[1] * v[0]) * w[2])
    if volume <= 0:
        errors.append("tetrahedron %d has volume %r in VTK's orientation" % (i, volume / 6))
        break
for name in sys.argv[5:]:
    if data.GetPointData().GetArray(name) is None and data.GetCellData().GetArray(name) is None:
        errors.append("array %s missing" % name)
# The last point must read back exactly (binary doubles).
if points and data.GetPoint(points - 1)[0] != 0.1 * (points - 1):
    errors.append("last point x %r" % (data.GetPoint(points - 1)[0],))
if errors:
    print("; ".join(errors))
    sys.exit(1)
