"""Mesh a closed surface into tetrahedra with the ParaView plugin and picture the result.

    xvfb-run -a pvbatch scripts/render_example3d.py INPUT OUTPUT.png [options]

INPUT is a closed surface: any file ParaView reads as polydata or an unstructured grid
(.vtp, .vtk, .stl, .obj, .ply, .vtu), or an .off file. The script meshes it with the
GPUQualityTetMesh filter of the GPUDelaunayRefinement plugin, writes the tetrahedra as .vtu
(OUTPUT with the extension .vtu unless --vtu says otherwise) and saves OUTPUT.png: the mesh
cut open by a crinkle clip (whole tetrahedra, as ParaView users look inside tet meshes)
colored by MinDihedralAngle, beside the histogram of all dihedral angles.

The plugin is found through PV_PLUGIN_PATH, --plugin, or the build tree
(build*/lib/paraview-*/plugins/GPUDelaunayRefinement). Rendering needs a display: use
xvfb-run on machines without one.
"""
import argparse
import os
import shutil
import sys
import tempfile

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from render_example import color_cells, load_plugin, reader_for, side_by_side  # noqa: E402


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("input", help="closed surface: .vtp, .vtk, .stl, .obj, .ply, .vtu or .off")
    p.add_argument("output", help="PNG picture to write")
    p.add_argument("--vtu", help="mesh file to write (default: OUTPUT with .vtu)")
    p.add_argument("--radius-edge", type=float, default=2.0,
                   help="largest radius-edge ratio, at least 1; 0 = off (default 2)")
    p.add_argument("--min-dihedral", type=float, default=0.0,
                   help="smallest dihedral angle in degrees; 0 = off (default)")
    p.add_argument("--max-volume", type=float, default=0.0, help="0 = off (default)")
    p.add_argument("--sliver-angle", type=float, default=0.0,
                   help="sliver removal after refinement (smoothing and flips), degrees; 0 = off (default)")
    p.add_argument("--backend", choices=["Auto", "GPU", "CPU"], default="Auto")
    p.add_argument("--plugin", help="path of GPUDelaunayRefinement.so")
    p.add_argument("--size", default="1400x560", help="picture size WxH (default 1400x560)")
    return p.parse_args()


def off_to_vtp(path, workdir):
    """An OFF surface (faces of any number of corners) as a .vtp, for ParaView to read."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

    with open(path) as f:
        words = [w for line in f for w in line.split("#", 1)[0].split()]
    if not words or not words[0].endswith("OFF"):
        sys.exit("render_example3d.py: %s is not an OFF file" % path)
    npoints, nfaces = int(words[1]), int(words[2])
    at = 4
    points = vtkPoints()
    points.SetDataTypeToDouble()
    for _ in range(npoints):
        points.InsertNextPoint(*(float(w) for w in words[at:at + 3]))
        at += 3
    faces = vtkCellArray()
    for _ in range(nfaces):
        n = int(words[at])
        faces.InsertNextCell(n, [int(w) for w in words[at + 1:at + 1 + n]])
        at += 1 + n
    surface = vtkPolyData()
    surface.SetPoints(points)
    surface.SetPolys(faces)
    out = os.path.join(workdir, "surface.vtp")
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(out)
    writer.SetInputData(surface)
    writer.Write()
    return out


def field(data, name):
    array = data.GetFieldData().GetAbstractArray(name)
    return array.GetValue(0) if array is not None else None


def main():
    args = parse()
    width, height = (int(v) for v in args.size.lower().split("x"))
    vtu = args.vtu or os.path.splitext(args.output)[0] + ".vtu"
    for f in (args.output, vtu):
        if os.path.dirname(f):
            os.makedirs(os.path.dirname(f), exist_ok=True)

    workdir = tempfile.mkdtemp(prefix="gdr_render3d_")
    if args.input.lower().endswith(".off"):
        source = XMLPolyDataReader(FileName=[off_to_vtp(args.input, workdir)])
    else:
        source = reader_for(args.input)

    load_plugin(args.plugin, globals())
    mesh = GPUQualityTetMesh(Input=source)
    mesh.RadiusEdgeRatio = args.radius_edge
    mesh.MinimumDihedralAngle = args.min_dihedral
    mesh.MaximumVolume = args.max_volume
    mesh.SliverAngle = args.sliver_angle
    mesh.Backend = args.backend
    mesh.UpdatePipeline()
    info = mesh.GetDataInformation(0)
    if info.GetNumberOfCells() == 0:
        sys.exit("render_example3d.py: the filter produced no tetrahedra (see the errors above)")
    SaveData(vtu, proxy=mesh)
    print("mesh written to", vtu)

    fetched = servermanager.Fetch(mesh)
    bad = field(fetched, "BadTetrahedra")
    title = "%s: %d tetrahedra, dihedral angles %.1f to %.1f deg, %s backend, %.2f s" % (
        os.path.basename(args.input), info.GetNumberOfCells(),
        field(fetched, "MinimumDihedralAngleReached"),
        field(fetched, "MaximumDihedralAngleReached"), field(fetched, "Backend"),
        field(fetched, "TotalSeconds"))
    if args.sliver_angle > 0:
        title += "\nsliver pass at %g deg: %d -> %d tetrahedra beyond it, %d flips" % (
            args.sliver_angle, field(fetched, "SliversBefore"), field(fetched, "SliversAfter"),
            field(fetched, "SliverFlips"))
    if bad:
        title += "\n%d tetrahedra left above the bounds (IsBad)%s" % (
            bad, ", refinement stalled" if field(fetched, "Stalled") else "")

    left_w = int(0.55 * width)
    left_png = os.path.join(workdir, "mesh.png")
    right_png = os.path.join(workdir, "histogram.png")

    # Right: the histogram of all six dihedral angles of every tetrahedron. Saved before
    # the render view shows its title: a text source shown first leaves ghost copies of
    # the chart's axis labels in its screenshot (ParaView 5.11 under Xvfb).
    chart = CreateView("XYBarChartView")
    bars = Show(OutputPort(mesh, 1), chart)
    bars.SeriesVisibility = ["DihedralAngleCount"]
    bars.SeriesLabel = ["DihedralAngleCount", "dihedral angles"]
    chart.ChartTitle = "Dihedral angles (all six of every tetrahedron)"
    chart.BottomAxisTitle = "degrees"
    chart.LeftAxisTitle = "angles per 1-degree bin"
    chart.ViewSize = [width - left_w, height]
    Render(chart)
    SaveScreenshot(right_png, chart, ImageResolution=[width - left_w, height])

    # Left: the mesh cut open through its center, seen from the side of the cut.
    view = CreateView("RenderView")
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    bounds = info.GetBounds()
    center = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
    cut = Clip(Input=mesh, ClipType="Plane", Crinkleclip=1)
    cut.ClipType.Origin = center
    cut.ClipType.Normal = [0.0, -1.0, 0.0]  # keeps the half beyond the plane
    display = Show(cut, view)
    color_cells(display, view, "MinDihedralAngle", 70.0, "MinDihedralAngle (deg)")
    text = Text(Text=title)
    text_display = Show(text, view)
    text_display.Color = [0.1, 0.1, 0.1]
    text_display.FontSize = 13
    text_display.WindowLocation = "Upper Center"
    view.ViewSize = [left_w, height]
    Render(view)  # paraview.simple resets the camera on the first render only
    view.CameraFocalPoint = center
    view.CameraPosition = [center[0] + 0.55, center[1] - 0.7, center[2] + 0.45]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    ResetCamera(view)
    Render(view)
    SaveScreenshot(left_png, view, ImageResolution=[left_w, height])
    side_by_side(left_png, right_png, args.output)
    shutil.rmtree(workdir, ignore_errors=True)
    print("picture written to", args.output)


if __name__ == "__main__":
    main()
