"""Mesh a planar straight-line graph with the ParaView plugin and picture the result.

    xvfb-run -a pvbatch scripts/render_example.py INPUT OUTPUT.png [options]

INPUT is a PSLG: Triangle's .poly (points, segments, hole seeds) or a VTK polydata file
(.vtp / .vtk: lines, polylines and polygon edges are segments). The script meshes it with
the GPUConstrainedDelaunay2D filter of the GPUDelaunayRefinement plugin, writes the mesh
as .vtu (OUTPUT with the extension .vtu unless --vtu says otherwise) and saves OUTPUT.png:
the mesh colored by its minimum angle beside the histogram of the minimum angles.

INPUT may also be a triangle mesh that already carries the cell array MinAngle (for
example a .vtu written by `gdr 2d`); it is then pictured as it is.

The plugin is found through PV_PLUGIN_PATH, --plugin, or the build tree
(build*/lib/paraview-*/plugins/GPUDelaunayRefinement). Rendering needs a display: use
xvfb-run on machines without one.
"""
import argparse
import glob
import os
import shutil
import sys
import tempfile

from paraview.simple import *  # noqa: F401,F403


def color_cells(display, view, array, top, title):
    """Surface With Edges, cells colored by `array` over [0, top] (Viridis), and its scalar
    bar titled `title` with whole-number labels, dark on a white background."""
    display.SetRepresentationType("Surface With Edges")
    display.EdgeColor = [0.15, 0.15, 0.15]
    ColorBy(display, ("CELLS", array))
    lut = GetColorTransferFunction(array)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lut.RescaleTransferFunction(0.0, top)
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = "%.0f"
    bar.RangeLabelFormat = "%.0f"


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("input", help=".poly, .vtp or .vtk PSLG (or a mesh with MinAngle)")
    p.add_argument("output", help="PNG picture to write")
    p.add_argument("--vtu", help="mesh file to write (default: OUTPUT with .vtu)")
    p.add_argument("--min-angle", type=float, default=25.0, help="degrees (default 25)")
    p.add_argument("--max-area", type=float, default=0.0, help="0 = off (default)")
    p.add_argument("--max-edge", type=float, default=0.0, help="0 = off (default)")
    p.add_argument("--mode", choices=["Ruppert", "Chew"], default="Ruppert")
    p.add_argument("--backend", choices=["Auto", "GPU", "CPU"], default="Auto")
    p.add_argument("--keep-exterior", action="store_true",
                   help="mesh the whole convex hull (default: remove the exterior when the "
                        "input has closed boundaries or hole seeds)")
    p.add_argument("--plugin", help="path of GPUDelaunayRefinement.so")
    p.add_argument("--size", default="1400x560", help="picture size WxH (default 1400x560)")
    return p.parse_args()


def read_poly(path):
    """Triangle .poly (or .node) -> (points, segments, holes), 0-based segments."""
    def rows(file_name):
        with open(file_name) as f:
            for line in f:
                line = line.split("#", 1)[0].split()
                if line:
                    yield line

    def read_vertices(it, count, file_name):
        ids, pts = [], []
        for _ in range(count):
            r = next(it)
            ids.append(int(r[0]))
            pts.append((float(r[1]), float(r[2])))
        return ids, pts

    it = rows(path)
    header = next(it)
    nvert = int(header[0])
    if nvert == 0 or path.endswith(".node"):
        node = path if path.endswith(".node") else os.path.splitext(path)[0] + ".node"
        node_it = rows(node)
        ids, points = read_vertices(node_it, int(next(node_it)[0]), node)
    else:
        ids, points = read_vertices(it, nvert, path)
    index = {vid: i for i, vid in enumerate(ids)}
    segments, holes = [], []
    if not path.endswith(".node"):
        nseg = int(next(it)[0])
        for _ in range(nseg):
            r = next(it)
            segments.append((index[int(r[1])], index[int(r[2])]))
        try:
            nholes = int(next(it)[0])
        except StopIteration:
            nholes = 0
        for _ in range(nholes):
            r = next(it)
            holes.append((float(r[1]), float(r[2])))
    return points, segments, holes


def poly_to_vtp(path, workdir):
    """Writes the .poly as a PSLG .vtp and its hole seeds as a point .vtp."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

    points, segments, holes = read_poly(path)

    def write(pd, name):
        out = os.path.join(workdir, name)
        w = vtkXMLPolyDataWriter()
        w.SetFileName(out)
        w.SetInputData(pd)
        w.Write()
        return out

    pts = vtkPoints()
    pts.SetDataTypeToDouble()
    for x, y in points:
        pts.InsertNextPoint(x, y, 0.0)
    lines = vtkCellArray()
    for a, b in segments:
        lines.InsertNextCell(2, [a, b])
    verts = vtkCellArray()
    for i in range(len(points)):
        verts.InsertNextCell(1, [i])
    pslg = vtkPolyData()
    pslg.SetPoints(pts)
    pslg.SetLines(lines)
    pslg.SetVerts(verts)
    pslg_file = write(pslg, "pslg.vtp")

    holes_file = None
    if holes:
        hpts = vtkPoints()
        for x, y in holes:
            hpts.InsertNextPoint(x, y, 0.0)
        hpd = vtkPolyData()
        hpd.SetPoints(hpts)
        holes_file = write(hpd, "holes.vtp")
    return pslg_file, holes_file, len(segments) > 0


def load_plugin(explicit, ns=None):
    """Loads the GPUDelaunayRefinement plugin, its proxies into `ns` (default: this module)."""
    ns = globals() if ns is None else ns
    if "GPUConstrainedDelaunay2D" in ns:
        return  # auto-loaded through PV_PLUGIN_PATH
    candidates = [explicit] if explicit else []
    for d in os.environ.get("PV_PLUGIN_PATH", "").split(os.pathsep):
        if d:
            candidates.append(os.path.join(d, "GPUDelaunayRefinement.so"))
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    candidates += sorted(glob.glob(os.path.join(
        root, "build*", "lib", "paraview-*", "plugins", "GPUDelaunayRefinement",
        "GPUDelaunayRefinement.so")))
    for c in candidates:
        if c and os.path.isfile(c):
            LoadPlugin(c, remote=False, ns=ns)
            return
    sys.exit("%s: GPUDelaunayRefinement plugin not found (build it, or set PV_PLUGIN_PATH / "
             "--plugin)" % os.path.basename(sys.argv[0]))


def write_vtu(polydata, path):
    """The triangles with all their point, cell and field data as a .vtu file."""
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid, VTK_TRIANGLE
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

    grid = vtkUnstructuredGrid()
    grid.SetPoints(polydata.GetPoints())
    grid.SetCells(VTK_TRIANGLE, polydata.GetPolys())
    grid.GetPointData().ShallowCopy(polydata.GetPointData())
    grid.GetCellData().ShallowCopy(polydata.GetCellData())
    grid.GetFieldData().ShallowCopy(polydata.GetFieldData())
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(grid)
    if writer.Write() != 1:
        sys.exit("render_example.py: cannot write " + path)


def side_by_side(left_png, right_png, output_png):
    from vtkmodules.vtkFiltersCore import vtkImageAppend
    from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

    append = vtkImageAppend()
    append.SetAppendAxis(0)
    for f in (left_png, right_png):
        r = vtkPNGReader()
        r.SetFileName(f)
        r.Update()
        append.AddInputData(r.GetOutput())
    w = vtkPNGWriter()
    w.SetFileName(output_png)
    w.SetInputConnection(append.GetOutputPort())
    w.Write()


def reader_for(path):
    ext = os.path.splitext(path)[1].lower()
    if ext == ".vtp":
        return XMLPolyDataReader(FileName=[path])
    if ext == ".vtu":
        return XMLUnstructuredGridReader(FileName=[path])
    if ext == ".vtk":
        return LegacyVTKReader(FileNames=[path])
    return OpenDataFile(path)


def main():
    args = parse()
    width, height = (int(v) for v in args.size.lower().split("x"))
    vtu = args.vtu or os.path.splitext(args.output)[0] + ".vtu"
    for f in (args.output, vtu):
        if os.path.dirname(f):
            os.makedirs(os.path.dirname(f), exist_ok=True)

    workdir = tempfile.mkdtemp(prefix="gdr_render_")
    holes = None
    closed = True
    if args.input.lower().endswith((".poly", ".node")):
        source_file, holes_file, closed = poly_to_vtp(args.input, workdir)
        source = XMLPolyDataReader(FileName=[source_file])
        holes = XMLPolyDataReader(FileName=[holes_file]) if holes_file else None
    else:
        source = reader_for(args.input)
    source.UpdatePipeline()

    if "MinAngle" in source.CellData.keys():
        mesh = source  # already meshed (e.g. by gdr 2d)
        triangles = source.GetDataInformation().GetNumberOfCells()
        histogram = Histogram(Input=mesh, SelectInputArray=["CELLS", "MinAngle"],
                              BinCount=60, CustomBinRanges=[0.0, 60.0],
                              UseCustomBinRanges=1)
        title = "%s: %d triangles" % (os.path.basename(args.input), triangles)
    else:
        load_plugin(args.plugin)
        mesh = GPUConstrainedDelaunay2D(Input=source)
        if holes is not None:
            mesh.HoleSeeds = holes
        mesh.MinimumAngle = args.min_angle
        mesh.MaximumArea = args.max_area
        mesh.MaximumEdgeLength = args.max_edge
        mesh.Mode = args.mode
        mesh.Backend = args.backend
        mesh.RemoveExterior = 0 if args.keep_exterior or not closed else 1
        mesh.UpdatePipeline()
        info = mesh.GetDataInformation(0)
        if info.GetNumberOfCells() == 0:
            sys.exit("render_example.py: the filter produced no triangles (see the errors above)")
        histogram = OutputPort(mesh, 1)
        fetched = servermanager.Fetch(mesh)
        backend = fetched.GetFieldData().GetAbstractArray("Backend").GetValue(0)
        seconds = fetched.GetFieldData().GetArray("TotalSeconds").GetValue(0)
        title = "%s: %d triangles, min angle %.1f deg, %s backend, %.3f s" % (
            os.path.basename(args.input), info.GetNumberOfCells(),
            mesh.CellData["MinAngle"].GetRange()[0], backend, seconds)
        write_vtu(fetched, vtu)
        print("mesh written to", vtu)

    # Left: the mesh colored by MinAngle.
    view = CreateView("RenderView")
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    display = Show(mesh, view)
    color_cells(display, view, "MinAngle", 60.0, "MinAngle (deg)")
    view.InteractionMode = "2D"
    ResetCamera(view)

    # Right: the histogram of the minimum angles.
    chart = CreateView("XYBarChartView")
    bars = Show(histogram, chart)
    bars.UseIndexForXAxis = 0
    bars.XArrayName = "bin_extents"
    bars.SeriesVisibility = ["bin_values"]
    bars.SeriesLabel = ["bin_values", "triangles"]
    chart.ChartTitle = "Minimum angle per triangle"
    chart.BottomAxisTitle = "degrees"
    chart.LeftAxisTitle = "triangles"

    # Each view saved at its own size, then put side by side. The chart goes first, before
    # the render view gets its title: once a text source is shown, the chart's screenshot
    # gets ghost copies of its axis labels (ParaView 5.11 under Xvfb).
    left_w = int(0.6 * width)
    left_png = os.path.join(workdir, "mesh.png")
    right_png = os.path.join(workdir, "histogram.png")
    view.ViewSize = [left_w, height]
    chart.ViewSize = [width - left_w, height]
    Render(chart)
    SaveScreenshot(right_png, chart, ImageResolution=[width - left_w, height])
    text = Text(Text=title)
    text_display = Show(text, view)
    text_display.Color = [0.1, 0.1, 0.1]
    text_display.FontSize = 14
    text_display.WindowLocation = "Upper Center"
    Render(view)
    SaveScreenshot(left_png, view, ImageResolution=[left_w, height])
    side_by_side(left_png, right_png, args.output)
    shutil.rmtree(workdir, ignore_errors=True)
    print("picture written to", args.output)


if __name__ == "__main__":
    main()
