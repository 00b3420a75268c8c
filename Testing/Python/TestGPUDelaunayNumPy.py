"""The NumPy API: gpudelaunay.refine_2d with arrays in and out, Triangle's switches and
dict input, warnings and errors as Python exceptions carrying the core's messages.

Run with /usr/bin/python3 and PYTHONPATH=<build>/python:
    TestGPUDelaunayNumPy.py
"""
import os
import sys
import warnings

import numpy as np

import gpudelaunay
from python_test_support import check


def angles_and_areas(points, triangles):
    """Smallest angle (degrees) and area of each triangle, from the arrays alone."""
    p = points[triangles]  # (t, 3, 2)
    e = [p[:, (i + 2) % 3] - p[:, (i + 1) % 3] for i in range(3)]  # edge opposite corner i
    length = [np.linalg.norm(v, axis=1) for v in e]
    cross = e[0][:, 0] * e[1][:, 1] - e[0][:, 1] * e[1][:, 0]
    area = 0.5 * cross
    angles = []
    for i in range(3):
        a, b = length[(i + 1) % 3], length[(i + 2) % 3]
        angles.append(np.degrees(np.arcsin(np.clip(2 * np.abs(area) / (a * b), 0, 1))))
    smallest = np.min(angles, axis=0)  # the smallest angle is below 60: arcsin is exact
    return smallest, area


def square_with_hole():
    outer = [[0, 0], [4, 0], [4, 4], [0, 4]]
    inner = [[1, 1], [2, 1], [2, 2], [1, 2]]
    points = np.array(outer + inner, dtype=float)
    segments = np.array([[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]])
    return points, segments, np.array([[1.5, 1.5]])


def test_arrays_in_and_out():
    points, segments, holes = square_with_hole()
    mesh = gpudelaunay.refine_2d(points, segments, holes, min_angle=28, max_area=0.05,
                                 backend="cpu")
    check(isinstance(mesh, dict), "the result is a dict")
    check(mesh.points is mesh["points"], "keys are attributes")
    check(mesh.points.shape[1] == 2 and mesh.points.dtype == np.float64, "points (m, 2)")
    check(mesh.triangles.shape[1] == 3 and mesh.triangles.dtype == np.int64, "triangles (t, 3)")
    t = len(mesh.triangles)
    check(t > 100, "refined: %d triangles" % t)
    for key in ("min_angle", "max_angle", "radius_edge_ratio", "area", "is_bad"):
        check(key in mesh and mesh[key].shape == (t,), "cell array " + key)
    check(mesh.point_type.shape == (len(mesh.points),), "point_type per point")
    check(np.all(mesh.points[:8] == points), "input points first, in input order")
    smallest, area = angles_and_areas(mesh.points, mesh.triangles)
    check(np.all(area > 0), "counter-clockwise triangles")
    check(smallest.min() >= 28 - 1e-9, "minimum angle %.3f >= 28" % smallest.min())
    check(area.max() <= 0.05 * (1 + 1e-12), "maximum area %.4f <= 0.05" % area.max())
    check(abs(area.sum() - 15.0) < 1e-9, "area 16 - 1 (hole emptied): %.12f" % area.sum())
    check(np.allclose(mesh.min_angle, smallest, atol=1e-6), "min_angle matches the arrays")
    check(not mesh.is_bad.any(), "no bad triangles")
    check(mesh.stats["Backend"] == "cpu" and mesh.stats["SteinerPoints"] > 0, "stats")


def test_triangle_style():
    # The `triangle` package's dict and switches: an L-shape, p removes the exterior.
    shape = {"vertices": [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]],
             "segments": [[i, (i + 1) % 6] for i in range(6)]}
    mesh = gpudelaunay.refine_2d(shape, switches="pq32a0.02", backend="cpu")
    smallest, area = angles_and_areas(mesh.points, mesh.triangles)
    check(abs(area.sum() - 3.0) < 1e-9, "the L-shape's area: %.12f" % area.sum())
    check(smallest.min() >= 32 - 1e-9, "q32: %.3f" % smallest.min())
    check(area.max() <= 0.02 * (1 + 1e-12), "a0.02: %.4f" % area.max())
    # No q, no a: the constrained Delaunay triangulation only.
    cdt = gpudelaunay.refine_2d(shape, switches="p", backend="cpu")
    check(len(cdt.points) == 6 and len(cdt.triangles) == 4, "p alone: the CDT")


def test_regions():
    # Triangle's regions: the inner square gets attribute 7 and an area bound of 0.01, the
    # ring around it attribute 3 and no bound.
    points, segments, _ = square_with_hole()
    regions = np.array([[1.5, 1.5, 7, 0.01], [3.0, 3.0, 3, 0]])
    mesh = gpudelaunay.refine_2d(points, segments, regions=regions, min_angle=20, backend="cpu")
    smallest, area = angles_and_areas(mesh.points, mesh.triangles)
    check(mesh.region.shape == (len(mesh.triangles),), "region per triangle")
    centre = mesh.points[mesh.triangles].mean(axis=1)
    inside = np.all((centre > 1) & (centre < 2), axis=1)
    check(np.all(mesh.region[inside] == 7) and np.all(mesh.region[~inside] == 3),
          "attributes 7 inside, 3 around")
    check(area[inside].max() <= 0.01 * (1 + 1e-12), "inner bound: %.4f" % area[inside].max())
    check(area[~inside].max() > 0.01, "no bound around: %.4f" % area[~inside].max())
    check(abs(area.sum() - 16.0) < 1e-9 and smallest.min() >= 20 - 1e-9, "area 16, angles >= 20")
    as_dict = gpudelaunay.refine_2d({"vertices": points, "segments": segments, "regions": regions},
                                    min_angle=20, backend="cpu")
    check(len(as_dict.triangles) == len(mesh.triangles), "regions from a triangle-style dict")


def test_markers_and_attributes():
    # Triangle's data carried as Triangle carries it: a 4 x 4 square of segments marked 1 to
    # 4 with unmarked corners, a free point (1, 1) marked 7, the attributes 2x + 3y + 1
    # (linear: reproduced exactly) and x^2.
    points = np.array([[0, 0], [4, 0], [4, 4], [0, 4], [1, 1]], dtype=float)
    segments = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])
    f = lambda p: 2 * p[:, 0] + 3 * p[:, 1] + 1
    attributes = np.column_stack([f(points), points[:, 0] ** 2])
    mesh = gpudelaunay.refine_2d(points, segments, point_markers=[0, 0, 0, 0, 7],
                                 segment_markers=[1, 2, 3, 4], point_attributes=attributes,
                                 min_angle=25, max_area=0.1, backend="cpu")
    m = len(mesh.points)
    check(np.all(mesh.points[:5] == points), "input points first, the free point kept")
    check(mesh.point_markers.shape == (m,) and mesh.point_attributes.shape == (m, 2),
          "per point: markers %s, attributes %s" % (mesh.point_markers.shape,
                                                   mesh.point_attributes.shape))
    # An unmarked corner takes the marker of the first marked segment through it.
    check(list(mesh.point_markers[:5]) == [1, 1, 2, 3, 7],
          "input points: %s" % mesh.point_markers[:5])
    x, y = mesh.points[5:, 0], mesh.points[5:, 1]
    side = np.select([y == 0, x == 4, y == 4, x == 0], [1, 2, 3, 4], 0)  # segment marker
    check(np.all((side > 0) == (mesh.point_type[5:] == 1)), "points on segments typed 1")
    for k in (1, 2, 3, 4):
        check(np.any(side == k), "Steiner points on segment %d" % k)
    check(np.all(mesh.point_markers[5:] == side), "on a segment its marker, inside 0")
    check(np.abs(mesh.point_attributes[:, 0] - f(mesh.points)).max() <= 1e-12 * 21,
          "the linear attribute is reproduced")
    x2 = mesh.point_attributes[5:, 1]  # between the ends' values along each segment
    check(np.all(x2[side == 1] >= 0) and np.all(x2[side == 1] <= 16) and
          np.all(np.abs(x2[(side == 2)] - 16) <= 1e-12) and np.all(x2[side == 3] <= 16) and
          np.all(np.abs(x2[side == 4]) <= 1e-12), "x^2 along the segments")
    check(np.all(np.abs(mesh.point_attributes[:5] - attributes) == 0), "input attributes kept")

    # The subsegments, each with its segment's marker, cover the segments once.
    on_boundary = 4 + np.count_nonzero(side)
    check(mesh.segments.shape == (len(mesh.segment_markers), 2) and
          len(mesh.segments) == on_boundary, "subsegments: %s" % (mesh.segments.shape,))
    a, b = mesh.points[mesh.segments[:, 0]], mesh.points[mesh.segments[:, 1]]
    mid = (a + b) / 2
    side = np.select([mid[:, 1] == 0, mid[:, 0] == 4, mid[:, 1] == 4, mid[:, 0] == 0], [1, 2, 3, 4], 0)
    check(np.all(mesh.segment_markers == side), "subsegment markers")
    length = np.linalg.norm(b - a, axis=1)
    for k in (1, 2, 3, 4):
        check(abs(length[side == k].sum() - 4) < 1e-12, "segment %d covered" % k)

    # The `triangle` package's names and (n, 1) markers give the same.
    same = gpudelaunay.refine_2d({"vertices": points, "segments": segments,
                                  "vertex_markers": [[0], [0], [0], [0], [7]],
                                  "segment_markers": [[1], [2], [3], [4]],
                                  "vertex_attributes": attributes},
                                 min_angle=25, max_area=0.1, backend="cpu")
    check(len(same.points) == m and np.all(same.point_markers[:5] == mesh.point_markers[:5]),
          "triangle-style dict")
    # Without markers, as Triangle: 1 on the boundary, 0 inside; no attributes.
    plain = gpudelaunay.refine_2d(points, segments, min_angle=25, backend="cpu")
    x, y = plain.points[:, 0], plain.points[:, 1]
    boundary = (x == 0) | (x == 4) | (y == 0) | (y == 4)
    check(np.all(plain.point_markers == boundary) and np.all(plain.segment_markers == 1) and
          "point_attributes" not in plain, "without markers")
    for bad in (dict(point_markers=[1, 2]), dict(segment_markers=[1]),
                dict(point_attributes=np.zeros((4, 2)))):
        try:
            gpudelaunay.refine_2d(points, segments, backend="cpu", **bad)
            check(False, "accepted %r" % bad)
        except ValueError:
            pass


def read_poly(path):
    """Points, segments (0-based) and holes of a Triangle .poly file with its points in it."""
    rows = [line.split("#")[0].split() for line in open(path)]
    rows = [r for r in rows if r]
    n = int(rows[0][0])
    first = int(rows[1][0])
    points = np.array([[float(r[1]), float(r[2])] for r in rows[1:1 + n]])
    k = int(rows[1 + n][0])
    segments = np.array([[int(r[1]) - first, int(r[2]) - first] for r in rows[2 + n:2 + n + k]])
    h = int(rows[2 + n + k][0])
    holes = np.array([[float(r[1]), float(r[2])] for r in rows[3 + n + k:3 + n + k + h]])
    return points, segments, holes


def test_rules():
    # Triangle's rules by default (lens, off-centres); diametral circles (mode="ruppert" or
    # Triangle's D) and circumcentres on request, with more points.
    gear = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "apps", "gdr",
                        "examples", "gear.poly")
    points, segments, holes = read_poly(gear)
    steiner = {}
    for name, kwargs in (("default", {}), ("circles", dict(mode="ruppert", off_centers=False)),
                         ("D", dict(switches="pcq30D"))):
        mesh = gpudelaunay.refine_2d(points, segments, holes, min_angle=30, backend="cpu",
                                     **kwargs)
        smallest, area = angles_and_areas(mesh.points, mesh.triangles)
        check(np.all(area > 0), "%s: counter-clockwise triangles" % name)
        check(smallest.min() >= 30 - 1e-9 and mesh.stats["BadTriangles"] == 0,
              "%s: minimum angle %.3f" % (name, smallest.min()))
        steiner[name] = mesh.stats["SteinerPoints"]
    # 281, 313 and 294 on one run (D: circles with off-centres)
    check(steiner["default"] < steiner["circles"] and steiner["default"] <= steiner["D"],
          "Steiner points %s" % steiner)


def test_warnings_and_errors():
    cross = np.array([[0, 0], [2, 2], [0, 2], [2, 0]], dtype=float)
    lines = [[0, 1], [2, 3]]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mesh = gpudelaunay.refine_2d(cross, lines, backend="cpu")
    check(any(issubclass(w.category, gpudelaunay.MeshingWarning) and
              "split 2 segment(s) into 4 pieces" in str(w.message) for w in caught),
          "crossing segments split with a warning: %s" % [str(w.message) for w in caught])
    check(len(mesh.points) >= 5, "the crossing point is a mesh point")

    try:
        gpudelaunay.refine_2d(cross, lines, strict=True, backend="cpu")
        check(False, "strict accepted crossing segments")
    except gpudelaunay.MeshingError as e:
        check(e.status == "SelfIntersectingInput", "status: %r" % e.status)
        check("segment 0 and segment 1 cross" in e.message, "message: %s" % e.message)

    try:
        gpudelaunay.refine_2d(cross, lines, switches="pqV", backend="cpu")
        check(False, "switch V accepted")
    except gpudelaunay.MeshingError as e:
        check(e.status == "InvalidInput" and "'V'" in e.message, "switches: %s" % e)

    for bad in (dict(points=np.zeros((3, 4))), dict(points=cross, segments=[[0, 9]])):
        try:
            gpudelaunay.refine_2d(**bad)
            check(False, "accepted %r" % bad)
        except ValueError:
            pass


def main():
    test_arrays_in_and_out()
    test_triangle_style()
    test_regions()
    test_markers_and_attributes()
    test_rules()
    test_warnings_and_errors()
    print("NumPy API: all checks passed")


if __name__ == "__main__":
    main()
