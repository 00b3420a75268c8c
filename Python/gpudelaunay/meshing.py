"""NumPy API of the gpudelaunay meshers, in the style of the `triangle` package and
pyvista-tetgen: arrays in, a result of arrays out, failures as Python exceptions.

    import numpy as np, gpudelaunay
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    mesh = gpudelaunay.refine_2d(square, [[0, 1], [1, 2], [2, 3], [3, 0]], max_area=0.01)
    mesh.points, mesh.triangles, mesh.min_angle          # also mesh["points"], ...

Each mesher runs its VTK filter (vtkGPUConstrainedDelaunay2D for refine_2d); the 3D meshers
follow the same shape: keyword options named as the CLI names them, a MeshResult, and
MeshingError carrying the core's status and message.
"""
import warnings

import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

__all__ = ["MeshingError", "MeshingWarning", "MeshResult", "refine_2d", "update",
           "update_pipeline"]

# The core's status names (gdr/error.h), as the filters prefix their error messages.
_STATUSES = ("InvalidInput", "SelfIntersectingInput", "OutOfDeviceMemory", "NoDevice",
             "Aborted", "IoError", "InternalError")


class MeshingError(RuntimeError):
    """A mesher refused its input or failed. `status` is the core's status name
    ("InvalidInput", "SelfIntersectingInput", "NoDevice", ...), `message` its message."""

    def __init__(self, status, message):
        super().__init__(f"{status}: {message}" if status else message)
        self.status = status
        self.message = message


class MeshingWarning(UserWarning):
    """What the mesher reported and went on (segments split at crossings, a Steiner cap)."""


class MeshResult(dict):
    """The mesh as NumPy arrays: a dict whose keys are also attributes."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __dir__(self):
        return list(super().__dir__()) + list(self.keys())


def _message_text(text):
    """The message of a VTK error or warning event, without VTK's file, line and object."""
    text = text.strip()
    # "ERROR: In FILE, line N\nvtkClass (0x...): MESSAGE"
    first = text.find("): ")
    if text.startswith(("ERROR:", "Warning:", "Generic Warning:")) and first >= 0:
        text = text[first + 3:]
    return text.strip()


def _run(algorithm, work=None):
    """Updates `algorithm` (or runs `work`, which updates it), turning its errors into a
    MeshingError and its warnings into MeshingWarning (VTK prints neither while they are
    observed). The filters and readers also set the error code on failure."""
    errors = []

    @calldata_type(VTK_STRING)
    def on_error(_obj, _event, text):
        errors.append(_message_text(text))

    @calldata_type(VTK_STRING)
    def on_warning(_obj, _event, text):
        warnings.warn(_message_text(text), MeshingWarning, stacklevel=3)

    @calldata_type(VTK_STRING)
    def on_executive_error(_obj, _event, text):
        pass  # "Algorithm ... returned failure": the filter's own error says why

    executive = algorithm.GetExecutive()
    tags = [(algorithm, algorithm.AddObserver(vtkCommand.ErrorEvent, on_error)),
            (algorithm, algorithm.AddObserver(vtkCommand.WarningEvent, on_warning)),
            (executive, executive.AddObserver(vtkCommand.ErrorEvent, on_executive_error))]
    try:
        (work or algorithm.Update)()
    finally:
        for obj, tag in tags:
            obj.RemoveObserver(tag)
    if not errors and algorithm.GetErrorCode() != 0:
        # Not run again (nothing changed since it failed): its error was reported then.
        errors.append("%s failed (error code %d) when it last ran" % (
            algorithm.GetClassName(), algorithm.GetErrorCode()))
    if errors:
        message = errors[0]
        status, _, rest = message.partition(": ")
        if status in _STATUSES:
            raise MeshingError(status, rest)
        raise MeshingError(None, message)


def _array(values, name, columns, dtype):
    a = np.asarray(values, dtype=dtype)
    if a.ndim != 2 or a.shape[1] not in columns:
        raise ValueError(f"{name} must be an array of shape (n, {' or '.join(map(str, columns))}), "
                         f"got shape {a.shape}")
    return a


def _cells(connectivity, size):
    """Cells of `size` points each, from their flat point ids, as a vtkCellArray."""
    cells = vtkCellArray()
    offsets = np.arange(0, len(connectivity) + 1, size, dtype=np.int64)
    cells.SetData(numpy_support.numpy_to_vtkIdTypeArray(offsets, deep=1),
                  numpy_support.numpy_to_vtkIdTypeArray(
                      np.ascontiguousarray(connectivity, dtype=np.int64), deep=1))
    return cells


def _polydata(points, segments):
    """Points (n, 2) and segments (k, 2) as vtkPolyData with z = 0: with segments, one
    polyvertex of all points (so that points on no segment are kept, in their order, as
    cell 0) and the segments as lines (cells 1 to k)."""
    xyz = np.zeros((len(points), 3))
    xyz[:, :points.shape[1]] = points
    vtk_points = vtkPoints()
    vtk_points.SetDataTypeToDouble()
    vtk_points.SetData(numpy_support.numpy_to_vtk(xyz, deep=1))
    pd = vtkPolyData()
    pd.SetPoints(vtk_points)
    if segments is not None and len(segments):
        pd.SetVerts(_cells(np.arange(len(points)), len(points)))
        pd.SetLines(_cells(segments.ravel(), 2))
    return pd


def _add_array(data, name, values):
    array = numpy_support.numpy_to_vtk(np.ascontiguousarray(values), deep=1)
    array.SetName(name)
    data.AddArray(array)


def _per_item(values, name, count, dtype, columns=False):
    """`values` with one value per item (count items), (count,) or (count, 1) as the
    `triangle` package gives markers, as a (count,) array; with `columns`, (count,) or
    (count, a) as a (count, a) array. None stays None."""
    if values is None:
        return None
    a = np.asarray(values, dtype=dtype)
    if columns and a.ndim == 1:
        a = a.reshape(-1, 1)
    elif not columns and a.ndim == 2 and a.shape[1] == 1:
        a = a[:, 0]
    if a.ndim != (2 if columns else 1) or len(a) != count:
        raise ValueError(f"{name} must have one {'row' if columns else 'value'} per item "
                         f"({count}), got shape {a.shape}")
    return a


def _field_values(fd):
    """Single-valued field data arrays (the run's statistics) as a dict of Python values."""
    stats = {}
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        if a is None or a.GetNumberOfValues() != 1:
            continue
        stats[a.GetName()] = a.GetValue(0)
    return stats


_CELL_ARRAYS = {"MinAngle": "min_angle", "MaxAngle": "max_angle",
                "RadiusEdgeRatio": "radius_edge_ratio", "Area": "area", "IsBad": "is_bad",
                "Region": "region"}
_POINT_ARRAYS = {"PointType": "point_type", "BoundaryMarker": "point_markers",
                 "PointAttributes": "point_attributes"}


def _connectivity(cells, size):
    """The point ids of cells of `size` points each as an (c, size) int64 array."""
    conn = numpy_support.vtk_to_numpy(cells.GetConnectivityArray()) if cells else np.zeros(0)
    return np.array(conn, dtype=np.int64).reshape(-1, size)


def _copy_arrays(data, names, result):
    """The arrays of `data` named in `names` (VTK name: result key) into `result`."""
    for vtk_name, key in names.items():
        array = data.GetArray(vtk_name)
        if array is not None:
            result[key] = numpy_support.vtk_to_numpy(array).copy()


def refine_2d(points, segments=None, holes=None, min_angle=20.0, max_area=None,
              max_edge=None, switches=None, backend="auto", remove_exterior=False,
              strict=False, max_steiner=None, mode="chew", off_centers=True,
              cdt_only=False, regions=None, point_markers=None, segment_markers=None,
              point_attributes=None):
    """Quality constrained Delaunay refinement of a planar straight-line graph.

    points: (n, 2) coordinates (an (n, 3) array is read in its x, y). A dict in the style
        of the `triangle` package ({"vertices", "segments", "holes", "regions",
        "vertex_markers", "segment_markers", "vertex_attributes"}) is accepted too.
    segments: (k, 2) point indices (0-based), or None. Crossing segments and points lying
        on segments are split there (a MeshingWarning counts them) unless strict=True.
    holes: (h, 2) seeds of regions to leave empty.
    regions: (r, 4) rows x, y, attribute, max_area, as Triangle's region list: the region
        enclosed by segments around (x, y) gets the attribute (result "region") and, when
        max_area > 0, that area bound.
    point_markers: (n,) integer boundary markers of the points; segment_markers: (k,) of
        the segments ((n, 1) and (k, 1) too); point_attributes: (n,) or (n, a) values per
        point. They are carried
        to the result as Triangle carries them (Triangle's .node and .poly).
    min_angle: smallest angle in degrees, at most 34 (0: no angle bound).
    max_area, max_edge, max_steiner: size bounds and the Steiner point cap (None: off).
    switches: Triangle's switch string ("pq30a0.1"); it overrides the options it names,
        as gdr 2d reads it, and an unsupported switch raises MeshingError.
    backend: "auto", "gpu" or "cpu".
    mode, off_centers: Triangle's rules by default: "chew" (a point encroaches a segment
        inside its diametral lens) and off-centres; "ruppert" (diametral circles, Triangle's
        -D) and off_centers=False (circumcentres) insert more points.

    Returns a MeshResult with points (m, 2), triangles (t, 3), point_type (m,), the cell
    arrays min_angle, max_angle, radius_edge_ratio, area and is_bad (t,), region (t,) when
    regions were given, segments (s, 2): the subsegments (mesh edges on input segments and,
    unless the exterior is removed, on the convex hull) with segment_markers (s,) (the
    segment's marker; 1 where that is 0 or not given on the mesh boundary, 0 inside),
    point_markers (m,) (a point's own marker, else that of a marked subsegment through it,
    else 0), point_attributes (m, a) when given (interpolated linearly at new points), and
    stats.
    Raises MeshingError (with the core's status and message) when the input is refused or
    the run fails, ValueError for arrays of the wrong shape or indices out of range.
    """
    from .GPUDelaunayFilters import vtkGPUConstrainedDelaunay2D

    if isinstance(points, dict):
        # A `triangle`-style dict; arguments given explicitly take precedence over its keys.
        given = points

        def pick(value, key):
            return given.get(key) if value is None else value

        segments = pick(segments, "segments")
        holes = pick(holes, "holes")
        regions = pick(regions, "regions")
        point_markers = pick(point_markers, "vertex_markers")
        segment_markers = pick(segment_markers, "segment_markers")
        point_attributes = pick(point_attributes, "vertex_attributes")
        points = given["vertices"]
    points = _array(points, "points", (2, 3), np.float64)
    if segments is not None:
        segments = _array(segments, "segments", (2,), np.int64)
        if len(segments) and (segments.min() < 0 or segments.max() >= len(points)):
            raise ValueError(f"segments refer to points outside [0, {len(points) - 1}]")
    if backend not in ("auto", "gpu", "cpu"):
        raise ValueError(f"backend must be 'auto', 'gpu' or 'cpu', got {backend!r}")
    if mode not in ("ruppert", "chew"):
        raise ValueError(f"mode must be 'ruppert' or 'chew', got {mode!r}")

    point_markers = _per_item(point_markers, "point_markers", len(points), np.int32)
    point_attributes = _per_item(point_attributes, "point_attributes", len(points), np.float64,
                                 columns=True)
    segment_markers = _per_item(segment_markers, "segment_markers",
                                0 if segments is None else len(segments), np.int32)

    pslg = _polydata(points, segments)
    # The arrays the filter reads Triangle's data from (docs/paraview.md).
    if point_markers is not None:
        _add_array(pslg.GetPointData(), "BoundaryMarker", point_markers)
    if point_attributes is not None:
        _add_array(pslg.GetPointData(), "PointAttributes", point_attributes)
    if segment_markers is not None and len(segment_markers):
        # on every cell: the polyvertex of the points first (no marker), then the lines
        _add_array(pslg.GetCellData(), "BoundaryMarker",
                   np.concatenate([[0], segment_markers]).astype(np.int32))
    if regions is not None and len(regions):
        regions = _array(regions, "regions", (4,), np.float64)
        seeds = np.zeros((len(regions), 3))
        seeds[:, :2] = regions[:, :2]
        for name, values in (("RegionSeeds", seeds), ("RegionAttribute", regions[:, 2]),
                             ("RegionMaximumArea", regions[:, 3])):
            _add_array(pslg.GetFieldData(), name, values)
    mesher = vtkGPUConstrainedDelaunay2D()
    mesher.SetInputData(pslg)
    if holes is not None and len(holes):
        holes = _array(holes, "holes", (2, 3), np.float64)
        mesher.SetHoleSeedsData(_polydata(holes, None))
    mesher.SetMinimumAngle(float(min_angle))
    mesher.SetMaximumArea(float(max_area or 0.0))
    mesher.SetMaximumEdgeLength(float(max_edge or 0.0))
    mesher.SetMaximumSteinerPoints(-1 if max_steiner is None else int(max_steiner))
    mesher.SetRemoveExterior(bool(remove_exterior))
    mesher.SetStrictInput(bool(strict))
    mesher.SetMode(mesher.CHEW if mode == "chew" else mesher.RUPPERT)
    mesher.SetOffCenters(bool(off_centers))
    if cdt_only:
        mesher.SetCDTOnly(True)
    mesher.SetBackend({"auto": mesher.AUTO, "gpu": mesher.GPU, "cpu": mesher.CPU}[backend])
    if switches:
        mesher.SetTriangleSwitches(str(switches))
    _run(mesher)

    out = mesher.GetOutput()
    subsegments = mesher.GetOutput(2)
    result = MeshResult()
    xyz = numpy_support.vtk_to_numpy(out.GetPoints().GetData()) if out.GetPoints() else np.zeros((0, 3))
    result["points"] = np.array(xyz[:, :2], dtype=np.float64)
    result["triangles"] = _connectivity(out.GetPolys(), 3)
    result["segments"] = _connectivity(subsegments.GetLines(), 2)
    result["segment_markers"] = np.zeros(0, dtype=np.int32)
    _copy_arrays(out.GetPointData(), _POINT_ARRAYS, result)
    _copy_arrays(out.GetCellData(), _CELL_ARRAYS, result)
    _copy_arrays(subsegments.GetCellData(), {"BoundaryMarker": "segment_markers"}, result)
    if "point_attributes" in result:
        result["point_attributes"] = result["point_attributes"].reshape(len(result.points), -1)
    result["stats"] = _field_values(out.GetFieldData())
    return result


def update(algorithm):
    """algorithm.Update() for the VTK filters and readers of this package; raises
    MeshingError (the core's status and message) when the run failed: bad input or
    parameters, Backend GPU without a usable GPU, an unreadable file. A successful run
    with an empty result (empty input), or an aborted run, does not raise."""
    _run(algorithm)


def update_pipeline(proxy, time=None):
    """paraview.simple: proxy.UpdatePipeline(time), raising MeshingError when the filter
    or reader failed, so that a pvpython script tells a failure from an empty result.
    Needs a builtin session (pvpython or pvbatch without a server: the filter runs in
    this process)."""
    algorithm = proxy.GetClientSideObject()
    if algorithm is None:
        raise RuntimeError("update_pipeline needs a builtin session (the filter in this process)")
    if time is None:
        # With a time the proxy always asks its pipeline to update (without one it skips
        # the request when nothing changed since an earlier, failed UpdatePipeline).
        from paraview.simple import GetTimeKeeper
        time = GetTimeKeeper().Time
    _run(algorithm, lambda: proxy.UpdatePipeline(time))
