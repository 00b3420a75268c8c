"""ParaView test of the plugin's restricted Delaunay filter GPURestrictedDelaunay3D (pvbatch /
pvpython).

    pvbatch TestGPURestrictedDelaunay3DPlugin.py --plugin <GPUDelaunayRefinement.so>
            --input <closed surface .vtp> --outdir <dir> [--render]

Loads the plugin, checks the proxy's defaults, ranges, documentation and view hints, meshes
the bundled hollow sphere (tetrahedra, surface, histograms, statistics, the facet angle
bound), the same with SliverAngle (fewer slivers), an open hemisphere made by ParaView's
Sphere source (the surface alone), and a refused parameter (gpudelaunay.update_pipeline raises MeshingError). With --render (under
`xvfb-run -a pvbatch`), checks the default display and saves the crinkle-clipped mesh beside
the two angle histograms (restricted_delaunay.png, used by docs/paraview.md).
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plugin_test_support import check, check_documented, parse_args  # noqa: E402

PROPERTIES = ("Input", "FacetAngle", "FacetSize", "FacetDistance", "FeatureAngle",
              "CellRadiusEdgeRatio", "CellSize", "MeshVolume", "SliverAngle",
              "MaximumSteinerPoints", "Backend")


def check_proxy(mesh):
    """Defaults, documented ranges, panel layout and view hints."""
    check(mesh.FacetAngle == 30 and mesh.CellRadiusEdgeRatio == 2, "angle and ratio defaults")
    check(mesh.FacetSize == -1 and mesh.FacetDistance == -1 and mesh.CellSize == -1,
          "automatic sizes by default")
    check(mesh.MeshVolume == 1 and mesh.MaximumSteinerPoints == -1, "MeshVolume, cap defaults")
    check(mesh.FeatureAngle == 0, "no features by default")
    check(mesh.SliverAngle == 0, "no sliver pass by default")
    check(mesh.Backend == "Auto", "Backend default")
    check_documented(mesh, PROPERTIES)
    angle = mesh.GetProperty("FacetAngle").SMProperty.GetDomain("range")
    check(angle.GetMinimum(0) == 0 and angle.GetMaximum(0) == 30, "FacetAngle 0..30")
    sliver = mesh.GetProperty("SliverAngle").SMProperty
    check(sliver.GetDomain("range").GetMinimum(0) == 0 and sliver.GetDomain("range").GetMaximum(0) == 30,
          "SliverAngle 0..30")
    check(sliver.GetPanelVisibility() == "default", "SliverAngle is not advanced")
    for name in ("MaximumSteinerPoints", "Backend"):
        check(mesh.GetProperty(name).SMProperty.GetPanelVisibility() == "advanced",
              name + " is advanced")
    controller = servermanager.vtkSMParaViewPipelineControllerWithRendering()
    views = [controller.GetPreferredViewType(mesh.SMProxy, port) for port in range(3)]
    check(views == ["RenderView", "None", "XYBarChartView"], "preferred views %s" % views)


def field(data, name):
    array = data.GetFieldData().GetArray(name)
    check(array is not None, "field data " + name)
    return array.GetValue(0)


def check_histogram(table, column, total):
    check(table.GetNumberOfRows() == 180, "histogram rows")
    check(table.GetColumnName(0) == "bin_extents", "histogram x column")
    counts = table.GetColumnByName(column)
    check(counts is not None, "histogram column " + column)
    check(sum(counts.GetValue(i) for i in range(180)) == total,
          "%s total %d" % (column, total))
    return counts


def check_closed(mesh):
    info = mesh.GetDataInformation(0)
    ntets = info.GetNumberOfCells()
    print("hollow sphere: %d tetrahedra, %d points" % (ntets, info.GetNumberOfPoints()))
    check(ntets > 500, "too few tetrahedra: %d" % ntets)
    for name in ("RadiusEdgeRatio", "MinDihedralAngle", "MaxDihedralAngle", "Volume", "IsBad"):
        check(name in mesh.CellData.keys(), "cell array " + name)
    check("PointType" in mesh.PointData.keys(), "point array PointType")
    check(mesh.CellData["RadiusEdgeRatio"].GetRange()[1] <= 2.0 + 1e-6, "radius-edge bound")
    check(mesh.CellData["IsBad"].GetRange() == (0.0, 0.0), "no bad tetrahedra")

    grid = servermanager.Fetch(mesh)
    check(field(grid, "VolumeMeshed") == 1 and field(grid, "BadFacets") == 0, "statistics")
    check(field(grid, "FacetSize") == 0.25 and field(grid, "CellSize") == 0.25, "sizes in effect")
    # The polyhedron's volume (the ball less the cavity, 4.19 - 0.52 for round spheres).
    check(abs(field(grid, "Volume") - 3.6) < 0.1, "volume %g" % field(grid, "Volume"))

    surface = servermanager.Fetch(mesh, idx=1)
    ntris = surface.GetNumberOfCells()
    check(ntris > 200, "surface triangles %d" % ntris)
    cd = surface.GetCellData()
    for name in ("MinAngle", "Size", "Distance", "IsBad"):
        check(cd.GetArray(name) is not None, "surface cell array " + name)
    check(cd.GetArray("MinAngle").GetRange()[0] >= 30 - 1e-4, "facet angle bound")
    check(cd.GetArray("Size").GetRange()[1] <= 0.25 * (1 + 1e-9), "facet size bound")

    table = servermanager.Fetch(mesh, idx=2)
    check_histogram(table, "DihedralAngleCount", 6 * ntets)
    facets = check_histogram(table, "FacetAngleCount", ntris)
    check(all(facets.GetValue(i) == 0 for i in range(29)), "no facet angle below 29")


def check_slivers(reader):
    """SliverAngle: fewer tetrahedra with an angle beyond it, the volume and the surface
    criteria as before."""
    mesh = GPURestrictedDelaunay3D(Input=reader, FacetSize=0.25, FacetDistance=0.01,
                                   SliverAngle=15, Backend="CPU")
    mesh.UpdatePipeline()
    grid = servermanager.Fetch(mesh)
    before, after = field(grid, "SliversBefore"), field(grid, "SliversAfter")
    print("SliverAngle 15: %d -> %d slivers" % (before, after))
    check(before > 0 and after < before, "slivers %d -> %d" % (before, after))
    check(abs(field(grid, "Volume") - 3.6) < 0.1, "volume %g" % field(grid, "Volume"))
    check(field(grid, "BadTetrahedra") == 0 and field(grid, "BadFacets") == 0, "criteria met")
    check(mesh.CellData["RadiusEdgeRatio"].GetRange()[1] <= 2.0 + 1e-6, "radius-edge bound")
    Delete(mesh)


def check_open():
    """An open hemisphere from ParaView's Sphere source: the surface alone."""
    cap = Sphere(ThetaResolution=32, PhiResolution=32, EndPhi=90)
    mesh = GPURestrictedDelaunay3D(Input=cap, FacetSize=0.2, Backend="CPU")
    mesh.UpdatePipeline()
    check(mesh.GetDataInformation(0).GetNumberOfCells() == 0, "no tetrahedra")
    check(mesh.GetDataInformation(1).GetNumberOfCells() > 50, "the surface")
    check(field(servermanager.Fetch(mesh), "ClosedInput") == 0, "ClosedInput")
    Delete(mesh)
    Delete(cap)


def check_refused(reader):
    """A facet angle above 30 degrees is refused, not clamped; scripts see it."""
    import gpudelaunay
    mesh = GPURestrictedDelaunay3D(Input=reader, FacetAngle=40, Backend="CPU")
    try:
        gpudelaunay.update_pipeline(mesh)
        check(False, "FacetAngle 40 accepted")
    except gpudelaunay.MeshingError as e:
        check(e.status == "InvalidInput" and "facet angle" in e.message, "error %s" % e)
    check(mesh.GetDataInformation(1).GetNumberOfCells() == 0, "empty output after the error")
    Delete(mesh)


def chart_of(mesh, series, title, left, top, view_size):
    """A bar chart of one histogram column, titled for the docs."""
    chart = CreateView("XYBarChartView")
    bars = Show(OutputPort(mesh, 2), chart)
    check(bars.XArrayName == "bin_extents", "the chart takes the bin centers as x")
    visible = list(bars.SeriesVisibility)
    check(visible == ["DihedralAngleCount", "FacetAngleCount"], "visible series %s" % visible)
    bars.SeriesVisibility = [series]
    chart.ChartTitle = title
    chart.BottomAxisTitle = "degrees"
    chart.LeftAxisTitle = left
    chart.LeftAxisUseCustomRange = 0
    chart.BottomAxisUseCustomRange = 1
    chart.BottomAxisRangeMinimum, chart.BottomAxisRangeMaximum = 0.0, top
    chart.ViewSize = view_size
    Render(chart)
    return chart


def render(mesh, args):
    """The picture for the docs: the tetrahedra cut open (whole cells) and colored by
    MinDihedralAngle, beside the histograms of the dihedral angles and of the smallest
    angles of the surface triangles."""
    view = CreateView("RenderView")
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    shown = Show(mesh, view)
    check(shown.Representation == "Surface With Edges", "default representation")
    check(shown.ColorArrayName == ["CELLS", "MinDihedralAngle"], "default coloring")
    Hide(mesh, view)
    crinkle = Clip(Input=mesh, ClipType="Plane", Crinkleclip=1)
    crinkle.ClipType.Normal = [0.0, -1.0, 0.0]
    tets = Show(crinkle, view)
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
    Render(view)  # paraview.simple resets the camera on the first render only
    view.CameraFocalPoint = [0.0, 0.3, 0.0]
    view.CameraPosition = [2.6, -3.2, 2.2]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30
    view.ViewSize = [760, 560]
    Render(view)

    dihedral = chart_of(mesh, "DihedralAngleCount", "Dihedral angles (all six of every tetrahedron)",
                        "angles per bin", 180.0, [640, 280])
    facets = chart_of(mesh, "FacetAngleCount", "Smallest angle of every surface triangle",
                      "triangles per bin", 61.0, [640, 280])

    layout = CreateLayout("GPU Restricted Delaunay 3D")
    layout.SplitHorizontal(0, 0.54)
    layout.SplitVertical(2, 0.5)
    AssignViewToLayout(view=view, layout=layout, hint=1)
    AssignViewToLayout(view=dihedral, layout=layout, hint=5)
    AssignViewToLayout(view=facets, layout=layout, hint=6)
    SaveScreenshot(os.path.join(args.outdir, "restricted_delaunay.png"), layout,
                   ImageResolution=[1400, 560])


def main():
    args = parse_args()
    os.makedirs(args.outdir, exist_ok=True)

    LoadPlugin(args.plugin, remote=False, ns=globals())
    check("GPURestrictedDelaunay3D" in globals(), "proxy GPURestrictedDelaunay3D not defined")

    reader = XMLPolyDataReader(FileName=[args.input])
    mesh = GPURestrictedDelaunay3D(Input=reader)
    check_proxy(mesh)
    mesh.FacetSize = 0.25
    mesh.FacetDistance = 0.01
    mesh.Backend = "CPU"
    mesh.UpdatePipeline()
    check_closed(mesh)
    check_open()
    check_slivers(reader)
    check_refused(reader)
    SaveData(os.path.join(args.outdir, "hollow_sphere_rdt.vtu"), proxy=mesh)
    surface_file = os.path.join(args.outdir, "hollow_sphere_rdt_surface.vtp")
    SaveData(surface_file, proxy=OutputPort(mesh, 1))
    check(os.path.getsize(surface_file) > 0, "the surface saved")

    if not args.render:
        print("plugin test passed (no rendering)")
        return
    render(mesh, args)
    print("plugin test passed (rendered into %s)" % args.outdir)


if __name__ == "__main__":
    main()
