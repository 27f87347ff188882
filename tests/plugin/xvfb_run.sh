#!/bin/bash
# Runs a command under `xvfb-run -a` (never a fixed display number), starting the search for
# a free display at a number of its own so that concurrent runs do not all race for :99, with
# its X authority file in a folder of its own beside the test (not in /tmp).
#
# On this shared machine type, under heavy load, an X client sometimes cannot connect to its
# freshly started, still running Xvfb (VTK: "bad X server connection", nothing in Xvfb's
# log): about 1 run in 5 at a load average of 12, and pvbatch failed three times in a row at
# 15 (a fresh-clone make test beside four helpers' builds). Such a run is tried again, up to
# five times with a growing pause; any other failure is the command's own and is returned
# as it is. XVFB_SCREEN sets the screen (default 1280x1024x24; make bench-peers: 1920x1080x24).
set -u
screen=${XVFB_SCREEN:-1280x1024x24}
folder=$(mktemp -d "$PWD/xvfb.XXXXXX")
trap 'rm -rf "$folder"' EXIT
for attempt in 1 2 3 4 5; do
  xvfb-run -a -n $((100 + ($$ + 97 * attempt) % 900)) -f "$folder/Xauthority" \
    -s "-screen 0 $screen" "$@" 2>&1 | tee "$folder/log"
  status=${PIPESTATUS[0]}
  if [ "$status" -eq 0 ] || ! grep -q "bad X server connection" "$folder/log"; then
    exit "$status"
  fi
  echo "xvfb_run.sh: no connection to the X server (attempt $attempt of 5)" >&2
  sleep $((5 * attempt))
done
exit "$status"
