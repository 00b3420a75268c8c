#!/bin/sh
# The ParaView GUI shows the meshing filter's progress in the status bar and its abort
# button stops the run (issue 15). Runs inside `xvfb-run -s "-screen 0 1600x1000x24"`:
#   gui_abort_test.sh PARAVIEW PLUGIN INPUT OUTDIR
# Drives the GUI with xdotool at the positions of ParaView 5.11's default window (paraview
# --dr, 1600x1000 screen): closes the welcome dialog, clicks into the render view so that
# the refinement gui_abort.py has set up runs (tens of seconds), saves a screenshot once
# progress is reported (OUTDIR/gui_progress.png, used by docs/paraview.md), presses the
# status bar's abort button and checks, from the filter's events logged by gui_abort.py,
# that the run ended within 10 s with an empty output and was not started again.
paraview=$1; plugin=$2; input=$3; out=$4
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
. "$here/gui_test_support.sh"
export GDR_PLUGIN=$plugin GDR_INPUT=$input
start_paraview "$here/gui_abort.py" gui_abort
wait_for ready 120 || fail "the GUI did not start"
sleep 8                                   # the window and the welcome dialog
xdotool mousemove 893 576 click 1; sleep 1                         # close the dialog
wait_for start 3 || xdotool mousemove 1100 600 click 1             # render: the run starts
wait_for "progress 0.0[2-9]\|progress 0.[1-9]" 60 || fail "no progress from the run"
sleep 2
import -window root "$out/gui_progress.png"
xdotool mousemove 372 748 click 1                                  # abort button
clicked=$(date +%s)
wait_for "end cells" 10 || fail "the run did not stop within 10 s of the abort"
echo "stopped $(( $(date +%s) - clicked )) s after the abort; $(grep -c progress "$log") progress events"
grep "end cells" "$log" | tail -1 | grep -q "cells=0" || fail "the aborted run left cells"
sleep 5
[ "$(grep -c start "$log")" -eq 1 ] || fail "the filter ran again after the abort"
kill $pv
echo "GUI progress and abort passed"
