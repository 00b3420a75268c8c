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


def _polydata(points, segments):
    """Points (n, 2) and segments (k, 2) as vtkPolyData with z = 0 and lines."""
    xyz = np.zeros((len(points), 3))
    xyz[:, :points.shape[1]] = points
    vtk_points = vtkPoints()
    vtk_points.SetDataTypeToDouble()
    vtk_points.SetData(numpy_support.numpy_to_vtk(xyz, deep=1))
    pd = vtkPolyData()
    pd.SetPoints(vtk_points)
    if segments is not None and len(segments):
        lines = vtkCellArray()
        offsets = np.arange(0, 2 * len(segments) + 1, 2, dtype=np.int64)
        lines.SetData(numpy_support.numpy_to_vtkIdTypeArray(offsets, deep=1),
                      numpy_support.numpy_to_vtkIdTypeArray(
                          np.ascontiguousarray(segments, dtype=np.int64).ravel(), deep=1))
        pd.SetLines(lines)
    return pd


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


def refine_2d(points, segments=None, holes=None, min_angle=20.0, max_area=None,
              max_edge=None, switches=None, backend="auto", remove_exterior=False,
              strict=False, max_steiner=None, mode="chew", off_centers=True,
              cdt_only=False, regions=None):
    """Quality constrained Delaunay refinement of a planar straight-line graph.

    points: (n, 2) coordinates (an (n, 3) array is read in its x, y). A dict in the style
        of the `triangle` package ({"vertices", "segments", "holes"}) is accepted too.
    segments: (k, 2) point indices (0-based), or None. Crossing segments and points lying
        on segments are split there (a MeshingWarning counts them) unless strict=True.
    holes: (h, 2) seeds of regions to leave empty.
    regions: (r, 4) rows x, y, attribute, max_area, as Triangle's region list: the region
        enclosed by segments around (x, y) gets the attribute (result "region") and, when
        max_area > 0, that area bound.
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
    regions were given, and stats.
    Raises MeshingError (with the core's status and message) when the input is refused or
    the run fails, ValueError for arrays of the wrong shape or indices out of range.
    """
    from .GPUDelaunayFilters import vtkGPUConstrainedDelaunay2D

    if isinstance(points, dict):
        if segments is None:
            segments = points.get("segments")
        if holes is None:
            holes = points.get("holes")
        if regions is None:
            regions = points.get("regions")
        points = points["vertices"]
    points = _array(points, "points", (2, 3), np.float64)
    if segments is not None:
        segments = _array(segments, "segments", (2,), np.int64)
        if len(segments) and (segments.min() < 0 or segments.max() >= len(points)):
            raise ValueError(f"segments refer to points outside [0, {len(points) - 1}]")
    if backend not in ("auto", "gpu", "cpu"):
        raise ValueError(f"backend must be 'auto', 'gpu' or 'cpu', got {backend!r}")
    if mode not in ("ruppert", "chew"):
        raise ValueError(f"mode must be 'ruppert' or 'chew', got {mode!r}")

    pslg = _polydata(points, segments)
    if regions is not None and len(regions):
        regions = _array(regions, "regions", (4,), np.float64)
        seeds = np.zeros((len(regions), 3))
        seeds[:, :2] = regions[:, :2]
        for name, values, components in (("RegionSeeds", seeds, 3),
                                          ("RegionAttribute", regions[:, 2], 1),
                                          ("RegionMaximumArea", regions[:, 3], 1)):
            array = numpy_support.numpy_to_vtk(np.ascontiguousarray(values), deep=1)
            array.SetName(name)
            pslg.GetFieldData().AddArray(array)
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
    result = MeshResult()
    xyz = numpy_support.vtk_to_numpy(out.GetPoints().GetData()) if out.GetPoints() else np.zeros((0, 3))
    result["points"] = np.array(xyz[:, :2], dtype=np.float64)
    polys = out.GetPolys()
    conn = numpy_support.vtk_to_numpy(polys.GetConnectivityArray()) if polys else np.zeros(0)
    result["triangles"] = np.array(conn, dtype=np.int64).reshape(-1, 3)
    point_type = out.GetPointData().GetArray("PointType")
    if point_type is not None:
        result["point_type"] = numpy_support.vtk_to_numpy(point_type).copy()
    cd = out.GetCellData()
    for vtk_name, key in _CELL_ARRAYS.items():
        array = cd.GetArray(vtk_name)
        if array is not None:
            result[key] = numpy_support.vtk_to_numpy(array).copy()
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
