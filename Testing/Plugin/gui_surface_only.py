"""GUI side of gui_surface_only_test.sh: run by `paraview --script` with GDR_PLUGIN and
GDR_GUI_LOG set. Meshes an open hemisphere (ParaView's Sphere source) with the restricted
Delaunay filter, which gives no tetrahedra, and shows its tetrahedra and its histograms as
the Apply button would. The plugin's GUI component then hides the empty tetrahedra, shows
the surface with its edges and, in the chart, the facet angles instead of the (empty)
dihedral angles; the display properties it sets are logged to GDR_GUI_LOG for the driver
to check."""
import os

from paraview.simple import *  # noqa: F401,F403

LoadPlugin(os.environ["GDR_PLUGIN"], remote=False, ns=globals())
log = open(os.environ["GDR_GUI_LOG"], "w", buffering=1)

cap = Sphere(ThetaResolution=32, PhiResolution=32, EndPhi=90)
mesh = GPURestrictedDelaunay3D(Input=cap, FacetSize=0.2, Backend="CPU")
view = GetActiveViewOrCreate("RenderView")
tets = Show(mesh, view)
chart = CreateView("XYBarChartView")
bars = Show(OutputPort(mesh, 2), chart)


def surface_display():
    for representation in view.Representations:
        connection = representation.GetProperty("Input").SMProperty
        if connection.GetNumberOfProxies() and connection.GetOutputPortForConnection(0) == 1:
            return representation
    return None


def on_tets_visibility(*_):
    surface = surface_display()
    log.write("tets visible=%d surface %s\n" % (
        tets.Visibility, "none" if surface is None else
        "visible=%d representation=%s" % (surface.Visibility,
                                          surface.SMProxy.GetProperty("Representation").GetElement(0))))


def on_chart_title(*_):  # set after the series
    shown = list(bars.SeriesVisibility)
    labels = dict(zip(bars.SeriesLabel[::2], bars.SeriesLabel[1::2]))
    log.write("series shown=%s label=%s title=%s\n" % (
        ",".join(shown), labels.get("FacetAngleCount"), chart.ChartTitle))


tets.GetProperty("Visibility").SMProperty.AddObserver("ModifiedEvent", on_tets_visibility)
chart.GetProperty("ChartTitle").SMProperty.AddObserver("ModifiedEvent", on_chart_title)
log.write("ready cells=%d surface=%d\n" % (mesh.GetDataInformation(0).GetNumberOfCells(),
                                           mesh.GetDataInformation(1).GetNumberOfCells()))
