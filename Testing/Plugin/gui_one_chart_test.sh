#!/bin/sh
# Two meshing filters share one histogram chart in the ParaView GUI. Runs inside
# `xvfb-run -s "-screen 0 1600x1000x24"`:
#   gui_one_chart_test.sh PARAVIEW PLUGIN PLATE OUTDIR
# gui_one_chart.py shows each filter's histogram in a new bar chart view, as Apply does; this
# driver checks, from what it logs, that the second view was closed and both histograms shown
# in the first chart, each named by its filter in the legend, and saves a screenshot
# (OUTDIR/gui_one_chart.png).
paraview=$1; plugin=$2; plate=$3; out=$4
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
. "$here/gui_test_support.sh"
export GDR_PLUGIN=$plugin GDR_PLATE=$plate
start_paraview "$here/gui_one_chart.py" gui_one_chart
wait_for ready 120 || fail "the GUI did not start"
wait_for "charts=1 representations=2 shown=2 prefixes=GPUConstrainedDelaunay2D1: ,GPUConstrainedDelaunay2D2: " 30 ||
  fail "the second histogram was not moved into the first chart"
screenshot_and_stop gui_one_chart
echo "GUI one chart passed"
