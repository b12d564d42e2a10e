#!/usr/bin/env bash
# Runs a command under a private X server (Debian's ParaView is GLX-only: renders need one):
#   bash scripts/with-xvfb.sh pvbatch pvstates/render.py OUTDIR
# -noreset: pvbatch connects to the display more than once, and an X server resets when its
# last client leaves; a connection made during that reset fails ("bad X server connection",
# pvbatch aborts). xvfb-run starts Xvfb without -noreset: two renders at once failed 2 of 3
# times on this 2-core machine, 0 of 3 with it. -displayfd: Xvfb picks a free display itself
# and names it once it accepts connections (no race for a display number).
set -euo pipefail
tmp=$(mktemp -d -t dustlift-xvfb.XXXXXX)
xvfb=
cleanup() {
  if [ -n "$xvfb" ]; then kill "$xvfb" 2>/dev/null || true; wait "$xvfb" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
Xvfb -displayfd 3 -screen 0 1920x1200x24 -nolisten tcp -noreset 3>"$tmp/display" 2>"$tmp/xvfb.log" &
xvfb=$!
for _ in $(seq 1 600); do
  [ -s "$tmp/display" ] && break
  if ! kill -0 "$xvfb" 2>/dev/null; then
    echo "with-xvfb.sh: Xvfb ended before it was ready:" >&2
    cat "$tmp/xvfb.log" >&2
    exit 1
  fi
  sleep 0.1
done
if [ ! -s "$tmp/display" ]; then
  echo "with-xvfb.sh: Xvfb did not start within 60 s" >&2
  exit 1
fi
status=0
DISPLAY=":$(head -n1 "$tmp/display")" "$@" || status=$?
exit "$status"
