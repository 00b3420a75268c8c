"""ParaView test of the GPUDelaunayRefinement plugin (pvbatch / pvpython).

    pvbatch TestGPUDelaunayPlugin.py --plugin <GPUDelaunayRefinement.so> --input <.vtp>
            --outdir <dir> [--render --baseline <png>] [--update-baseline]

Loads the plugin, applies GPUConstrainedDelaunay2D to the bundled plate, checks counts,
arrays, histogram and proxy metadata. With --render (needs a display: run it under
`xvfb-run -a pvbatch`), renders the meshed domain and compares it with the baseline
image, and saves the mesh, the histogram chart and both side by side
(docs/paraview.md uses the last one).
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plugin_test_support import check, check_documented, compare_images, parse_args  # noqa: E402


def main():
    args = parse_args()
    os.makedirs(args.outdir, exist_ok=True)

    LoadPlugin(args.plugin, remote=False, ns=globals())
    check("GPUConstrainedDelaunay2D" in globals(), "proxy GPUConstrainedDelaunay2D not defined")

    reader = XMLPolyDataReader(FileName=[args.input])
    seed = PointSource(Center=[2.0, 3.0, 0.0], NumberOfPoints=1, Radius=0.0)
    mesh = GPUConstrainedDelaunay2D(Input=reader, HoleSeeds=seed)

    # Defaults and documented ranges.
    check(mesh.MinimumAngle == 20, "MinimumAngle default")
    check(mesh.MaximumEdgeLength == 0 and mesh.MaximumArea == 0, "size bounds off by default")
    check(mesh.MaximumSteinerPoints == -1, "MaximumSteinerPoints default")
    check(mesh.Mode == "Chew" and mesh.Backend == "Auto", "Mode/Backend defaults")
    check(mesh.OffCenters == 1, "OffCenters default (Triangle's rules)")
    check(mesh.RemoveExterior == 0 and mesh.StrictInput == 0, "boolean defaults")
    check_documented(mesh, ("MinimumAngle", "MaximumEdgeLength", "MaximumArea",
                            "MaximumSteinerPoints", "Mode", "Backend", "RemoveExterior",
                            "StrictInput", "HoleSeeds"))
    angle_domain = mesh.GetProperty("MinimumAngle").SMProperty.GetDomain("range")
    check(angle_domain.GetMinimum(0) == 0 and angle_domain.GetMaximum(0) == 34,
          "MinimumAngle range 0..34")
    for name in ("Mode", "Backend", "MaximumSteinerPoints", "StrictInput"):
        check(mesh.GetProperty(name).SMProperty.GetPanelVisibility() == "advanced",
              name + " is advanced")

    mesh.MinimumAngle = 25.0
    mesh.RemoveExterior = 1
    mesh.Backend = "CPU"
    mesh.UpdatePipeline()

    info = mesh.GetDataInformation(0)
    ncells = info.GetNumberOfCells()
    npoints = info.GetNumberOfPoints()
    print("mesh: %d triangles, %d points" % (ncells, npoints))
    check(ncells >= 40, "too few triangles: %d" % ncells)
    check(npoints >= 29, "input points missing: %d" % npoints)
    for name in ("MinAngle", "MaxAngle", "RadiusEdgeRatio", "Area", "IsBad"):
        check(name in mesh.CellData.keys(), "cell array " + name)
    check("PointType" in mesh.PointData.keys(), "point array PointType")
    lo, hi = mesh.CellData["MinAngle"].GetRange()
    check(lo >= 25.0 - 1e-9 and hi <= 60.0 + 1e-9, "MinAngle range %g..%g" % (lo, hi))
    check(mesh.CellData["IsBad"].GetRange() == (0.0, 0.0), "no bad triangles")
    area = sum(servermanager.Fetch(mesh).GetCellData().GetArray("Area").GetValue(i)
               for i in range(ncells))
    check(abs(area - (36.0 + 54.0 * 0.25881904510252074 - 3.0)) < 1e-6,
          "meshed area %.9f (plate minus hole)" % area)

    table = servermanager.Fetch(mesh, idx=1)
    check(table.GetNumberOfRows() == 60, "histogram rows")
    counts = table.GetColumnByName("bin_values")
    check(sum(counts.GetValue(i) for i in range(60)) == ncells, "histogram total")
    check(all(counts.GetValue(i) == 0 for i in range(25)), "no triangle below 25 degrees")

    # Triangle's switch string overrides the properties: -q30 asks for 30 degrees.
    check(mesh.TriangleSwitches == "", "TriangleSwitches default (empty)")
    check(mesh.GetProperty("TriangleSwitches").SMProperty.GetPanelVisibility() == "advanced",
          "TriangleSwitches is advanced")
    check_documented(mesh, ("TriangleSwitches",))
    mesh.TriangleSwitches = "pq30"
    mesh.UpdatePipeline()
    lo30 = mesh.CellData["MinAngle"].GetRange()[0]
    check(lo30 >= 30.0 - 1e-9, "MinAngle %g with switches pq30" % lo30)
    n30 = mesh.GetDataInformation(0).GetNumberOfCells()
    print("switches pq30: %d triangles" % n30)
    check(n30 > 1.2 * ncells, "pq30 refines further: %d against %d triangles" % (n30, ncells))
    mesh.TriangleSwitches = ""
    mesh.UpdatePipeline()
    again = mesh.GetDataInformation(0).GetNumberOfCells()
    # (Counts of the CPU path may differ a little between runs: threads.)
    check(abs(again - ncells) <= 0.05 * ncells, "switches cleared: %d triangles, as before" % again)

    controller = servermanager.vtkSMParaViewPipelineControllerWithRendering()
    check(controller.GetPreferredViewType(mesh.SMProxy, 1) == "XYBarChartView",
          "histogram port prefers the bar chart view")

    SaveData(os.path.join(args.outdir, "plate_mesh.vtp"), proxy=mesh)

    if not args.render:
        print("plugin test passed (no rendering)")
        return

    # Regression image: the meshed domain in one color (independent of the mesh details).
    view = CreateView("RenderView")
    view.ViewSize = [300, 200]
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    display = Show(mesh, view)
    # The domain in one colour, without the edges the plugin shows by default.
    display.SetRepresentationType("Surface")
    ColorBy(display, None)
    display.AmbientColor = display.DiffuseColor = [0.2, 0.3, 0.6]
    view.CameraPosition = [4.5, 3.0, 20.0]
    view.CameraFocalPoint = [4.5, 3.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 3.6
    Render(view)
    test_png = os.path.join(args.outdir, "plate_domain.png")
    SaveScreenshot(test_png, view, ImageResolution=[300, 200])
    if args.update_baseline:
        import shutil
        shutil.copyfile(test_png, args.baseline)
        print("baseline updated:", args.baseline)
    elif args.baseline:
        compare_images(test_png, args.baseline)

    # Pictures for the docs: a finer mesh colored by MinAngle with the input segments on
    # top, its histogram, and both side by side.
    mesh.MinimumAngle = 30.0
    mesh.MaximumArea = 0.05
    mesh.UpdatePipeline()
    display.SetRepresentationType("Surface With Edges")
    display.EdgeColor = [0.15, 0.15, 0.15]
    ColorBy(display, ("CELLS", "MinAngle"))
    lut = GetColorTransferFunction("MinAngle")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lut.RescaleTransferFunction(0.0, 60.0)
    display.SetScalarBarVisibility(view, True)
    scalar_bar = GetScalarBar(lut, view)
    scalar_bar.Title = "MinAngle (deg)"
    scalar_bar.ComponentTitle = ""
    scalar_bar.TitleColor = scalar_bar.LabelColor = [0.1, 0.1, 0.1]
    scalar_bar.AutomaticLabelFormat = 0
    scalar_bar.LabelFormat = scalar_bar.RangeLabelFormat = "%.0f"
    segments = Show(reader, view)
    segments.SetRepresentationType("Wireframe")
    segments.ColorArrayName = ["POINTS", ""]
    segments.AmbientColor = segments.DiffuseColor = [0.9, 0.1, 0.1]
    segments.LineWidth = 3.0
    view.ViewSize = [800, 500]
    view.CameraParallelScale = 3.8
    Render(view)
    SaveScreenshot(os.path.join(args.outdir, "plate_mesh.png"), view, ImageResolution=[800, 500])

    chart = CreateView("XYBarChartView")
    chart.ViewSize = [600, 500]
    bars = Show(OutputPort(mesh, 1), chart)
    bars.UseIndexForXAxis = 0
    bars.XArrayName = "bin_extents"
    bars.SeriesVisibility = ["bin_values"]
    bars.SeriesLabel = ["bin_values", "triangles"]
    chart.ChartTitle = "Minimum angle per triangle"
    chart.BottomAxisTitle = "degrees"
    chart.LeftAxisTitle = "triangles"
    Render(chart)
    SaveScreenshot(os.path.join(args.outdir, "plate_histogram.png"), chart,
                   ImageResolution=[600, 500])

    layout = CreateLayout("GPU Delaunay")
    layout.SplitHorizontal(0, 0.57)
    AssignViewToLayout(view=view, layout=layout, hint=1)
    AssignViewToLayout(view=chart, layout=layout, hint=2)
    SaveScreenshot(os.path.join(args.outdir, "paraview_plate.png"), layout,
                   ImageResolution=[1400, 500])
    print("plugin test passed (rendered into %s)" % args.outdir)


if __name__ == "__main__":
    main()
