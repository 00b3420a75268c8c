#!/bin/sh
# Runs a command under `xvfb-run -a`, retrying up to three times when the X server was not
# usable ("bad X server connection": seen about once in 15 CI runs, on a display that
# xvfb-run had just started). Any other failure is reported at once. Xvfb's own messages go to
# the output, for the record.
# Usage: xvfb_retry.sh XVFB_RUN COMMAND [ARGS...]
xvfb_run=$1
shift
log=$(mktemp)
attempt=1
while :; do
  "$xvfb_run" -a -e "$log" "$@" > "$log.out" 2>&1
  rc=$?
  cat "$log.out"
  if [ $rc -ne 0 ] && [ $attempt -lt 3 ] && grep -q "bad X server connection" "$log.out"; then
    echo "xvfb_retry: the X server was not usable (attempt $attempt); Xvfb said:"
    cat "$log"
    attempt=$((attempt + 1))
    continue
  fi
  rm -f "$log" "$log.out"
  exit $rc
done
