"""GUI side of gui_one_chart_test.sh: run by `paraview --script` with GDR_PLUGIN, GDR_PLATE
and GDR_GUI_LOG set. Meshes the plate twice with GPU Constrained Delaunay 2D and shows each
histogram in a bar chart view of its own, as the Apply button does (the proxy's view hint).
The plugin's GUI component moves the second histogram into the first chart, names each run
in the legend and closes the second view; the chart views left and the first chart's
series are logged to GDR_GUI_LOG for the driver to check."""
import os

from paraview.simple import *  # noqa: F401,F403

LoadPlugin(os.environ["GDR_PLUGIN"], remote=False, ns=globals())
log = open(os.environ["GDR_GUI_LOG"], "w", buffering=1)

plate = XMLPolyDataReader(FileName=[os.environ["GDR_PLATE"]])
first = GPUConstrainedDelaunay2D(Input=plate, Backend="CPU")
second = GPUConstrainedDelaunay2D(Input=plate, Backend="CPU", MinimumAngle=30)
chart = CreateView("XYBarChartView")
Show(OutputPort(first, 1), chart)


watched = set()


def on_representations(*_):
    charts = [v for v in GetViews() if v.GetXMLName() == "XYBarChartView"]
    shown = [r for r in chart.Representations if r.Visibility]
    prefixes = ",".join(r.SeriesLabelPrefix for r in chart.Representations)
    log.write("charts=%d representations=%d shown=%d prefixes=%s\n" % (
        len(charts), len(chart.Representations), len(shown), prefixes))
    # The legend is named after a representation is added: log again when it is.
    for r in chart.Representations:
        if r.GetGlobalIDAsString() not in watched:
            watched.add(r.GetGlobalIDAsString())
            r.GetProperty("SeriesLabelPrefix").SMProperty.AddObserver("ModifiedEvent", on_representations)


chart.GetProperty("Representations").SMProperty.AddObserver("ModifiedEvent", on_representations)
other = CreateView("XYBarChartView")
Show(OutputPort(second, 1), other)
log.write("ready\n")
