#!/bin/sh
# The ParaView GUI shows the meshing filter's progress in the status bar, its abort button
# stops the run, and an aborted run can be applied again (issue 15). Runs inside
# `xvfb-run -s "-screen 0 1600x1000x24"`:
#   gui_abort_test.sh PARAVIEW PLUGIN INPUT OUTDIR
# Drives the GUI with xdotool at the positions of ParaView 5.11's default window (paraview
# --dr, 1600x1000 screen): closes the welcome dialog, makes GPU Constrained Delaunay 2D on the
# input with the quick-launch box and presses Apply, so that the long refinement
# gui_abort.py has set as its defaults runs as a first Apply. It saves a screenshot once
# progress is reported (OUTDIR/gui_progress.png, used by docs/paraview.md), presses the
# status bar's abort button and checks, from the filter's events logged by gui_abort.py,
# that the run ended within 10 s with an empty output and was not started again, that the
# Apply button is lit again (OUTDIR/gui_aborted.png) and Output Messages says so. Apply
# without a change runs the filter again; that run is aborted too (an abort in a later
# Apply) and Apply is lit again, and stays lit after Reset (the outputs are still empty). A
# larger Maximum Area typed in the panel and Apply then give a mesh.
paraview=$1; plugin=$2; input=$3; out=$4
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
. "$here/gui_test_support.sh"
export GDR_PLUGIN=$plugin GDR_INPUT=$input
apply() { xdotool mousemove 47 424 click 1; }
abort() { # the status bar's abort button, found in a SCREENSHOT: it moves with the widths
  # of the texts beside it, so it is the grey-bordered button just left of the progress
  # bar's blue fill on row 745
  import -window root "$out/gui_abort_click.png"
  x=$(convert "$out/gui_abort_click.png" -crop 900x1+100+745 -depth 8 rgb:- | od -An -tu1 -v -w3 |
    awk '{ r[NR] = $1; b[NR] = $3 }
         END { for (i = 1; i <= NR && !(b[i] > r[i] + 80); i++);
               for (j = i - 1; j > 0 && !(r[j] > 140 && r[j] < 200 && b[j] - r[j] < 10 && r[j] - b[j] < 10); j--);
               if (i <= NR && j > 0) print 100 + j - 1 - 9 }')
  [ -n "$x" ] || fail "no abort button beside the progress bar (see $out/gui_abort_click.png)"
  xdotool mousemove "$x" 745 click 1
}
apply_lit() { # SCREENSHOT: the Apply button is green when enabled, grey when not
  import -window root "$1"
  [ "$(convert "$1" -format '%[fx:int(255*(p{15,424}.g-p{15,424}.r))]' info:)" -gt 20 ]
}
abort_run() { # N: abort run N once it reports progress; it must stop empty within 10 s
  wait_for "start $1" 10 || fail "Apply did not start run $1"
  wait_for "progress $1 0.0[2-9]\|progress $1 0.[1-9]" 60 || fail "no progress from run $1"
  sleep 2
  [ "$1" -eq 1 ] && import -window root "$out/gui_progress.png"
  abort
  clicked=$(date +%s)
  # the button moves with the length of the progress text, which can change between the
  # screenshot and the click: one more try if the run goes on
  wait_for "end $1 cells" 4 || { abort; wait_for "end $1 cells" 6; } ||
    fail "run $1 did not stop within 10 s of the abort"
  echo "run $1 stopped $(( $(date +%s) - clicked )) s after the abort"
  grep -q "end $1 cells=0" "$log" || fail "the aborted run $1 left cells"
  sleep 5
  grep -q "start $(($1 + 1))" "$log" && fail "the filter ran again after the abort of run $1"
  apply_lit "$out/gui_aborted.png" || fail "Apply is not lit after the abort of run $1"
}
start_paraview "$here/gui_abort.py" gui_abort
wait_for ready 120 || fail "the GUI did not start"
sleep 8                                   # the window and the welcome dialog
xdotool mousemove 893 576 click 1; sleep 1                         # close the dialog
xdotool mousemove 115 196 click 1; sleep 1                         # the reader, in the browser
xdotool key ctrl+space; sleep 1; xdotool type --delay 50 "GPU Constrained Delaunay 2D"
sleep 1; xdotool key Return
wait_for created 10 || fail "the filter was not made"
sleep 1
apply_lit "$out/gui_new_filter.png" || fail "Apply is not lit for the new filter"
apply                                                              # the first Apply
abort_run 1
grep -q "GPUConstrainedDelaunay2D1: run aborted" "$out/gui_abort_paraview.txt" ||
  fail "Output Messages does not say that the run was aborted"
apply                                                              # no property changed
abort_run 2
xdotool mousemove 129 424 click 1; sleep 2                         # Reset
apply_lit "$out/gui_reset.png" || fail "Reset after an abort put Apply out"
xdotool mousemove 191 667 click 1 key ctrl+a type "0.001"          # Maximum Area
xdotool key Tab; sleep 1
apply
wait_for "end 3 cells" 60 || fail "the third Apply gave no run"
grep -q "end 3 cells=0" "$log" && fail "the third run gave no mesh"
grep "end 3" "$log"
echo "$(grep -c progress "$log") progress events"
stop_paraview
echo "GUI progress, abort and apply again passed"
