# Sourced by the GUI drivers (gui_*_test.sh): start_paraview SCRIPT NAME starts `paraview
# --dr --script=SCRIPT` in the background with GDR_GUI_LOG=$out/NAME.log (the events the
# script logs) and keeps its pid; wait_for PATTERN SECONDS waits for a line of that log;
# fail MESSAGE prints the log's tail, stops paraview and exits 1; screenshot_and_stop NAME
# closes the welcome dialog, saves $out/NAME.png and stops paraview (stop_paraview). Needs
# $paraview and $out.
start_paraview() {
  log="$out/$2.log"
  rm -f "$log"
  GDR_GUI_LOG=$log "$paraview" --dr --script="$1" > "$out/$2_paraview.txt" 2>&1 &
  pv=$!
}
# stop_paraview: SIGTERM, then SIGKILL after 5 s (ParaView's SIGTERM handler, which prints
# a stack trace, has been seen to hang when the signal came during GUI work).
stop_paraview() {
  kill "$pv" 2>/dev/null
  i=0
  while kill -0 "$pv" 2>/dev/null; do
    i=$((i + 1)); [ $i -gt 20 ] && { kill -9 "$pv" 2>/dev/null; break; }; sleep 0.25
  done
}
fail() { echo "FAILED: $*"; tail -20 "$log" 2>/dev/null; stop_paraview; exit 1; }
wait_for() { # PATTERN SECONDS
  i=0
  while ! grep -q "$1" "$log" 2>/dev/null; do
    i=$((i + 1)); [ $i -gt $(($2 * 4)) ] && return 1; sleep 0.25
  done
}
screenshot_and_stop() { # NAME
  sleep 8                                              # the window and the welcome dialog
  xdotool mousemove 893 576 click 1; sleep 2           # close the dialog
  import -window root "$out/$1.png"
  stop_paraview
}
