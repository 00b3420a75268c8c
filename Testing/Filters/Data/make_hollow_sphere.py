#!/usr/bin/env python3
"""Writes hollow_sphere.vtp, the closed surface the 3D filter tests and the main job mesh: a
ball of radius 1 with a spherical cavity of radius 0.5 (two icospheres, 1280 and 320
triangles, the inner one facing the cavity). Run it with a Python that has VTK:

    /usr/bin/python3 Testing/Filters/Data/make_hollow_sphere.py Testing/Filters/Data/hollow_sphere.vtp
"""
import math
import sys

from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter


def icosphere(subdivisions, radius):
    """Points on the sphere and outward triangles: an icosahedron, each triangle split in
    four `subdivisions` times with the new points pushed onto the sphere."""
    t = (1 + math.sqrt(5)) / 2
    points = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
              (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9),
                 (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2),
                 (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
                 (8, 6, 7), (9, 8, 1)]

    def on_sphere(p):
        n = math.sqrt(sum(c * c for c in p))
        return tuple(c / n for c in p)

    points = [on_sphere(p) for p in points]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                points.append(on_sphere([(points[a][i] + points[b][i]) / 2 for i in range(3)]))
                middle[key] = len(points) - 1
            return middle[key]

        finer = []
        for a, b, c in triangles:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        triangles = finer
    return [tuple(radius * c for c in p) for p in points], triangles


def main():
    outer_points, outer = icosphere(3, 1.0)
    inner_points, inner = icosphere(2, 0.5)
    offset = len(outer_points)
    points = vtkPoints()
    points.SetDataTypeToDouble()
    for p in outer_points + inner_points:
        points.InsertNextPoint(p)
    polys = vtkCellArray()
    for a, b, c in outer:
        polys.InsertNextCell(3, (a, b, c))
    for a, b, c in inner:  # reversed: facing the cavity
        polys.InsertNextCell(3, (a + offset, c + offset, b + offset))
    surface = vtkPolyData()
    surface.SetPoints(points)
    surface.SetPolys(polys)
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(sys.argv[1])
    writer.SetInputData(surface)
    if writer.Write() != 1:
        sys.exit("cannot write " + sys.argv[1])


if __name__ == "__main__":
    main()
