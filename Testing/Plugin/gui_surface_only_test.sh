#!/bin/sh
# The ParaView GUI shows a restricted Delaunay run without tetrahedra (an open surface) by
# its surface and its facet-angle histogram. Runs inside `xvfb-run -s "-screen 0 1600x1000x24"`:
#   gui_surface_only_test.sh PARAVIEW PLUGIN OUTDIR
# gui_surface_only.py meshes an open hemisphere and shows the outputs; this driver checks,
# from the display properties it logs, that the plugin's GUI component hid the empty
# tetrahedra, showed the surface with its edges and the facet angles in the chart, and saves
# a screenshot (OUTDIR/gui_surface_only.png).
paraview=$1; plugin=$2; out=$3
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
. "$here/gui_test_support.sh"
export GDR_PLUGIN=$plugin
start_paraview "$here/gui_surface_only.py" gui_surface_only
wait_for ready 120 || fail "the GUI did not start"
grep -q "ready cells=0 surface=[1-9]" "$log" || fail "expected a surface and no tetrahedra"
wait_for "tets visible=0 surface visible=1 representation=Surface With Edges" 30 ||
  fail "the surface was not shown instead of the empty tetrahedra"
wait_for "series shown=FacetAngleCount label=smallest angle per surface triangle title=Angle histograms" 30 ||
  fail "the chart does not show the facet angles alone"
screenshot_and_stop gui_surface_only
echo "GUI surface-only display passed"
