"""GUI side of gui_abort_test.sh: run by `paraview --script` with GDR_PLUGIN, GDR_INPUT and
GDR_GUI_LOG set. Loads the plugin, opens the input with the plugin's reader, shows a quick
constrained Delaunay triangulation of it (Minimum Angle 0), then sets a long refinement
(Minimum Angle 30, Maximum Area 2e-7) that runs at the GUI's next render, once the driver
has closed the welcome dialog. The filter's start, progress and end are logged to
GDR_GUI_LOG for the driver to check."""
import os
import time

from paraview.simple import *  # noqa: F401,F403

LoadPlugin(os.environ["GDR_PLUGIN"], remote=False, ns=globals())
log = open(os.environ["GDR_GUI_LOG"], "w", buffering=1)
t0 = time.time()


def note(text):
    log.write("%.2f %s\n" % (time.time() - t0, text))


reader = OpenDataFile(os.environ["GDR_INPUT"])
mesh = GPUConstrainedDelaunay2D(Input=reader)
mesh.MinimumAngle = 0
mesh.Backend = "CPU"
Show(mesh)
Render()
SetActiveSource(mesh)

mesh.MinimumAngle = 30
mesh.MaximumArea = 2e-7  # ~20M triangles: a minute or more, whatever the machine
algorithm = mesh.GetClientSideObject()
algorithm.AddObserver("StartEvent", lambda o, e: note("start"))
algorithm.AddObserver("ProgressEvent", lambda o, e: note("progress %.3f" % o.GetProgress()))
algorithm.AddObserver("EndEvent", lambda o, e: note(
    "end cells=%d abort=%d" % (o.GetOutput().GetNumberOfCells(), o.GetAbortExecute())))
note("ready")
