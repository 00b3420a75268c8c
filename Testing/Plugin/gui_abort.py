"""GUI side of gui_abort_test.sh: run by `paraview --script` with GDR_PLUGIN, GDR_INPUT and
GDR_GUI_LOG set. Loads the plugin and opens the input with the plugin's reader. The driver
then makes GPU Constrained Delaunay 2D in the GUI, as a user does, so that its first run is
a first Apply (a filter made by a script counts as applied already). Its defaults are set
here to a long refinement (Minimum Angle 30, Maximum Area 2e-7, CPU). The filter's runs
(start N, progress N P, end N cells=C) are logged to GDR_GUI_LOG for the driver to check."""
import os
import time

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403

LoadPlugin(os.environ["GDR_PLUGIN"], remote=False, ns=globals())
log = open(os.environ["GDR_GUI_LOG"], "w", buffering=1)
t0 = time.time()


def note(text):
    log.write("%.2f %s\n" % (time.time() - t0, text))


reader = OpenDataFile(os.environ["GDR_INPUT"])
Show(reader)
Render()
SetActiveSource(reader)

# ~20M triangles: a minute or more, whatever the machine. Settings at a priority above the
# XML defaults are the defaults of a filter made in the GUI.
servermanager.vtkSMSettings.GetInstance().AddCollectionFromString(
    '{ "filters": { "GPUConstrainedDelaunay2D": '
    '{ "MinimumAngle": 30, "MaximumArea": 2e-7, "Backend": 2 } } }', 2.0)

watched = []
runs = []


def on_start(*_):
    runs.append(1)
    note("start %d" % len(runs))


def on_register(*_):
    # The filter made in the GUI: observe its VTK object.
    for proxy in GetSources().values():
        if proxy.GetXMLName() != "GPUConstrainedDelaunay2D" or proxy in watched:
            continue
        algorithm = proxy.GetClientSideObject()
        if algorithm is None:
            continue
        watched.append(proxy)
        algorithm.AddObserver("StartEvent", on_start)
        algorithm.AddObserver("ProgressEvent", lambda o, e: note(
            "progress %d %.3f" % (len(runs), o.GetProgress())))
        algorithm.AddObserver("EndEvent", lambda o, e: note(
            "end %d cells=%d" % (len(runs), o.GetOutput().GetNumberOfCells())))
        note("created")


servermanager.ProxyManager().SMProxyManager.AddObserver("RegisterEvent", on_register)
note("ready")
