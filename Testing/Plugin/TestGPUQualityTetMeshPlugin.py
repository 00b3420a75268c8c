"""ParaView test of the plugin's 3D filter GPUQualityTetMesh (pvbatch / pvpython).

    pvbatch TestGPUQualityTetMeshPlugin.py --plugin <GPUDelaunayRefinement.so>
            --input <closed surface .vtp> --outdir <dir>
            [--render --baseline <png>] [--update-baseline]

Loads the plugin, meshes the bundled hollow sphere, checks the proxy's defaults, ranges,
documentation and view hints, the counts, arrays, histogram and subfaces, and a region
seed made with ParaView's own sources. With --render (needs a display: run it under
`xvfb-run -a pvbatch`), renders the clipped domain in one color and compares it with the
baseline image, then saves the crinkle-clipped mesh colored by MinDihedralAngle, the
histogram chart as ParaView shows it by default, and both side by side
(docs/paraview.md uses the last one).
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plugin_test_support import check, check_documented, compare_images, parse_args  # noqa: E402


def check_proxy(mesh):
    """Defaults, documented ranges, panel layout and view hints."""
    check(mesh.RadiusEdgeRatio == 2.0, "RadiusEdgeRatio default")
    check(mesh.MinimumDihedralAngle == 0 and mesh.MaximumVolume == 0, "bounds off by default")
    check(mesh.MaximumSteinerPoints == -1, "MaximumSteinerPoints default")
    check(mesh.Backend == "Auto", "Backend default")
    check_documented(mesh, ("Input", "Seeds", "RadiusEdgeRatio", "MinimumDihedralAngle",
                            "MaximumVolume", "MaximumSteinerPoints", "Backend"))
    ratio = mesh.GetProperty("RadiusEdgeRatio").SMProperty.GetDomain("range")
    check(ratio.GetMinimum(0) == 0 and not ratio.GetMaximumExists(0), "RadiusEdgeRatio range")
    angle = mesh.GetProperty("MinimumDihedralAngle").SMProperty.GetDomain("range")
    check(angle.GetMinimum(0) == 0 and angle.GetMaximum(0) == 60, "MinimumDihedralAngle 0..60")
    for name in ("MaximumSteinerPoints", "Backend"):
        check(mesh.GetProperty(name).SMProperty.GetPanelVisibility() == "advanced",
              name + " is advanced")
    check(mesh.GetProperty("Seeds").SMProperty.GetMultipleInput() == 1, "Seeds take several")

    controller = servermanager.vtkSMParaViewPipelineControllerWithRendering()
    views = [controller.GetPreferredViewType(mesh.SMProxy, port) for port in range(3)]
    check(views == ["RenderView", "XYBarChartView", "None"], "preferred views %s" % views)


def check_outputs(mesh):
    info = mesh.GetDataInformation(0)
    ntets = info.GetNumberOfCells()
    print("mesh: %d tetrahedra, %d points" % (ntets, info.GetNumberOfPoints()))
    check(ntets > 1000, "too few tetrahedra: %d" % ntets)
    for name in ("RadiusEdgeRatio", "MinDihedralAngle", "MaxDihedralAngle", "Volume", "IsBad",
                 "Region"):
        check(name in mesh.CellData.keys(), "cell array " + name)
    check("PointType" in mesh.PointData.keys(), "point array PointType")
    check(mesh.CellData["RadiusEdgeRatio"].GetRange()[1] <= 1.4, "radius-edge bound")
    check(mesh.CellData["IsBad"].GetRange() == (0.0, 0.0), "no bad tetrahedra")
    lo, hi = mesh.CellData["MinDihedralAngle"].GetRange()
    check(0 < lo <= hi <= 70.6, "MinDihedralAngle range %g..%g" % (lo, hi))

    grid = servermanager.Fetch(mesh)
    check(grid.GetFieldData().GetAbstractArray("Backend").GetValue(0) in ("cpu", "gpu"),
          "Backend field")
    check(grid.GetFieldData().GetArray("BadTetrahedra").GetValue(0) == 0, "BadTetrahedra")

    table = servermanager.Fetch(mesh, idx=1)
    check(table.GetNumberOfRows() == 180, "histogram rows")
    check(table.GetColumnName(0) == "bin_extents", "histogram x column")
    counts = table.GetColumnByName("DihedralAngleCount")
    check(counts is not None, "histogram count column")
    check(sum(counts.GetValue(i) for i in range(180)) == 6 * ntets, "histogram total")
    check(all(counts.GetValue(i) == 0 for i in range(int(lo))), "no angle below the smallest")

    subfaces = servermanager.Fetch(mesh, idx=2)
    check(subfaces.GetNumberOfCells() >= 1600, "subfaces cover the 1600 input triangles")
    facet = subfaces.GetCellData().GetArray("FacetId")
    check(facet is not None and facet.GetRange() == (0.0, 1599.0), "FacetId")
    return ntets


def check_region_seed(reader):
    """A region seed in the cavity, made with ParaView's sources: it is filled, as region 5."""
    seed = PointSource(Center=[0.1, 0.0, 0.0], NumberOfPoints=1, Radius=0.0)
    attribute = Calculator(Input=seed, ResultArrayName="RegionAttribute", Function="5",
                           ResultArrayType="Int")
    mesh = GPUQualityTetMesh(Input=reader, Seeds=[attribute], Backend="CPU")
    mesh.UpdatePipeline()
    check(mesh.CellData["Region"].GetRange() == (0.0, 5.0), "Region from the seed")
    Delete(mesh)


def render(mesh, args):
    # Regression image: the domain cut in half, in one color. A plane cut of the tetrahedra
    # is the cut of the domain, whatever the tetrahedra are.
    view = CreateView("RenderView")
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    half = Clip(Input=mesh, ClipType="Plane")
    half.ClipType.Normal = [0.0, -1.0, 0.0]
    display = Show(half, view)
    display.SetRepresentationType("Surface")
    ColorBy(display, None)
    display.AmbientColor = display.DiffuseColor = [0.2, 0.3, 0.6]
    Render(view)  # paraview.simple resets the camera on the first render only
    # Looking at the kept half (y > 0) from the side of the cut.
    view.CameraFocalPoint = [0.0, 0.3, 0.0]
    view.CameraPosition = [2.6, -3.2, 2.2]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30
    view.ViewSize = [300, 300]
    Render(view)
    test_png = os.path.join(args.outdir, "hollow_sphere_domain.png")
    SaveScreenshot(test_png, view, ImageResolution=[300, 300])
    if args.update_baseline:
        import shutil
        shutil.copyfile(test_png, args.baseline)
        print("baseline updated:", args.baseline)
    elif args.baseline:
        compare_images(test_png, args.baseline)
    Hide(half, view)

    # Pictures for the docs: the crinkle clip (whole tetrahedra), colored by
    # MinDihedralAngle as ParaView colors it by default, and the histogram in a bar chart
    # with ParaView's default series.
    shown = Show(mesh, view)
    check(shown.Representation == "Surface With Edges", "default representation")
    check(shown.ColorArrayName == ["CELLS", "MinDihedralAngle"], "default coloring")
    Hide(mesh, view)
    crinkle = Clip(Input=mesh, ClipType="Plane", Crinkleclip=1)
    crinkle.ClipType.Normal = [0.0, -1.0, 0.0]
    tets = Show(crinkle, view)
    check(tets.ColorArrayName == ["CELLS", "MinDihedralAngle"], "crinkle clip coloring")
    tets.SetRepresentationType("Surface With Edges")
    tets.EdgeColor = [0.15, 0.15, 0.15]
    lut = GetColorTransferFunction("MinDihedralAngle")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lut.RescaleTransferFunction(0.0, 70.0)
    tets.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = "MinDihedralAngle (deg)"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = bar.RangeLabelFormat = "%.0f"
    view.ViewSize = [760, 560]
    Render(view)
    SaveScreenshot(os.path.join(args.outdir, "hollow_sphere_mesh.png"), view,
                   ImageResolution=[760, 560])

    chart = CreateView("XYBarChartView")
    bars = Show(OutputPort(mesh, 1), chart)
    check(bars.XArrayName == "bin_extents" and bars.UseIndexForXAxis == 0,
          "the chart takes the bin centers as x")
    visible = list(bars.SeriesVisibility)
    check(visible == ["DihedralAngleCount"], "visible series %s" % visible)
    chart.ChartTitle = "Dihedral angles (all six of every tetrahedron)"
    chart.BottomAxisTitle = "dihedral angle (degrees)"
    chart.LeftAxisTitle = "angles per 1-degree bin"
    chart.ViewSize = [640, 560]
    Render(chart)
    SaveScreenshot(os.path.join(args.outdir, "hollow_sphere_histogram.png"), chart,
                   ImageResolution=[640, 560])

    layout = CreateLayout("GPU Quality Tet Mesh")
    layout.SplitHorizontal(0, 0.54)
    AssignViewToLayout(view=view, layout=layout, hint=1)
    AssignViewToLayout(view=chart, layout=layout, hint=2)
    SaveScreenshot(os.path.join(args.outdir, "paraview_hollow_sphere.png"), layout,
                   ImageResolution=[1400, 560])


def main():
    args = parse_args()
    os.makedirs(args.outdir, exist_ok=True)

    LoadPlugin(args.plugin, remote=False, ns=globals())
    check("GPUQualityTetMesh" in globals(), "proxy GPUQualityTetMesh not defined")

    reader = XMLPolyDataReader(FileName=[args.input])
    mesh = GPUQualityTetMesh(Input=reader)
    check_proxy(mesh)
    mesh.RadiusEdgeRatio = 1.4
    mesh.Backend = "CPU"
    mesh.UpdatePipeline()
    check_outputs(mesh)
    check_region_seed(reader)
    SaveData(os.path.join(args.outdir, "hollow_sphere.vtu"), proxy=mesh)

    if not args.render:
        print("plugin test passed (no rendering)")
        return
    render(mesh, args)
    print("plugin test passed (rendered into %s)" % args.outdir)


if __name__ == "__main__":
    main()
