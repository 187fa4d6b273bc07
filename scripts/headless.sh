#!/usr/bin/env bash
# Runs a command on a virtual X display, so that rendering works headless.
# -noreset: by default Xvfb resets when its last client disconnects, and a client connecting
# during the reset cannot open the display ("bad X server connection"); the tests open and
# close displays all the time, in parallel.
exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$@"
