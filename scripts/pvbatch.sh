#!/usr/bin/env bash
# Runs a ParaView Python script with pvbatch, off screen: scripts/pvbatch.sh SCRIPT.py [ARGS].
# Debian's python3-paraview cannot be installed beside libvtk9-dev (it conflicts with
# python3-vtk9), so `scripts/setup.sh --with-paraview` unpacks its modules into a folder of
# their own; this puts them on PYTHONPATH and starts a virtual X server when there is no
# display. Exits 127 with one line when ParaView is not set up; `--available` only checks.
set -euo pipefail
modules="${RITR_PARAVIEW_PYTHON:-${XDG_CACHE_HOME:-$HOME/.cache}/ritr/paraview-python}"
if [ -d "$modules/paraview" ]; then
  export PYTHONPATH="$modules${PYTHONPATH:+:$PYTHONPATH}"
fi
if ! command -v pvbatch > /dev/null || { [ ! -d "$modules/paraview" ] &&
     [ ! -d /usr/lib/python3/dist-packages/paraview ]; }; then
  echo "ParaView (pvbatch and its Python modules) is not set up: run scripts/setup.sh --with-paraview" >&2
  exit 127
fi
if [ "${1:-}" = "--available" ]; then
  [ -n "${DISPLAY:-}" ] || command -v Xvfb > /dev/null ||
    { echo "no display and no Xvfb: run scripts/setup.sh --with-paraview" >&2; exit 127; }
  exit 0
fi
if [ -z "${DISPLAY:-}" ]; then
  # A private virtual X server (24-bit colour for OpenGL); -displayfd picks a free display
  # and tells it once the server is ready.
  ready="$(mktemp)"
  Xvfb -displayfd 3 -screen 0 1920x1200x24 -nolisten tcp 3> "$ready" 2> /dev/null &
  server=$!
  trap 'kill $server 2> /dev/null; rm -f "$ready"' EXIT
  for _ in $(seq 300); do
    [ -s "$ready" ] && break
    sleep 0.1
  done
  [ -s "$ready" ] || { echo "the virtual X server (Xvfb) did not start" >&2; exit 127; }
  export DISPLAY=":$(head -n 1 "$ready")"
fi
# Connecting to the X server fails now and then on some machines (pvbatch then aborts with
# "bad X server connection", SIGABRT; a bare XOpenDisplay fails too, so it is the server
# under load): such a run is tried again, up to ten times.
for attempt in $(seq 10); do
  status=0
  pvbatch "$@" || status=$?
  [ "$status" -ne 134 ] && exit "$status"
  echo "pvbatch aborted (attempt $attempt of 10)" >&2
done
exit 134
