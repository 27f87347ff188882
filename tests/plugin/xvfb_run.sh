#!/bin/bash
# Runs a command under `xvfb-run -a` (never a fixed display number), starting the search for
# a free display at a number of its own so that concurrent runs do not all race for :99, with
# its X authority file in a folder of its own beside the test (not in /tmp), and Xvfb started
# with -noreset. XVFB_SCREEN sets the screen (default 1280x1024x24; make bench-peers:
# 1920x1080x24).
#
# -noreset: an X server by default resets when its last client disconnects, and a client that
# connects just then is accepted, then dropped before the reply to its connection setup
# (XOpenDisplay returns NULL and prints nothing; VTK 9.1 reports "bad X server connection"
# and aborts). VTK closes a render window's display connection when the window is deleted, so
# a program that deletes its only window and opens the next within milliseconds loses that
# race now and then: bench/compare_vtk.py's windows one after another (the 20k sphere's second
# window connects 5 ms after the first closed: the failures at a round's start in `make
# bench-peers`), pvbatch (it opens the display to probe it, closes it and opens it again 5 ms
# later). Counted in bench/peers-runs.md ("bad X server connection"): 14 of 20 processes of
# 20 such windows aborted without -noreset, none of 40 with it. The retries on that message
# that this script used to make are gone with the cause.
set -u
screen=${XVFB_SCREEN:-1280x1024x24}
folder=$(mktemp -d "$PWD/xvfb.XXXXXX")
trap 'rm -rf "$folder"' EXIT
xvfb-run -a -n $((100 + $$ % 900)) -f "$folder/Xauthority" \
  -s "-noreset -screen 0 $screen" "$@"
