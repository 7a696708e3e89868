#!/usr/bin/env bash
# Runs a short r-ITR scene (a ball landing on spikes), opens every output in ParaView
# (check_outputs.py: frame counts, arrays, ranges) and draws it with scripts/render.py.
# Usage: paraview_outputs.sh SOURCE_DIR RITR_BINARY. Exits 77 (skipped) without ParaView.
set -euo pipefail
source_dir="$1"
ritr="$2"
pvbatch="$source_dir/scripts/pvbatch.sh"
if ! reason="$("$pvbatch" --available 2>&1)"; then
  echo "SKIPPED: $reason"
  exit 77
fi

run="$PWD/output/paraview_outputs"
rm -rf "$run"
mkdir -p "$run"
cat > "$run.prm" <<PRM
set dimension        = 2
set time step        = 0.01
set end time         = 0.1
set output directory = $run
set output every     = 2
subsection Body 0
  set shape             = disk
  set center            = 0, 0.75
  set radius            = 0.5
  set shape refinements = 1
  set initial velocity  = 0; -1
end
subsection Material 0
  set youngs modulus = 1e5
  set poisson ratio  = 0.4
end
subsection Obstacle 0
  set type         = spikes
  set point        = 0, 0
  set size         = 2.0
  set count        = 5
  set spike height = 0.2
end
subsection Adaptivity
  set enabled = true
end
PRM
"$ritr" "$run.prm" > "$run.log" || { cat "$run.log"; exit 1; }

frames=6  # t = 0, 0.02, ..., 0.1
"$pvbatch" "$source_dir/tests/paraview/check_outputs.py" "$run" "$frames"

"$pvbatch" "$source_dir/scripts/render.py" "$run" --frames 0 -1 --size 600 300
for picture in figure-00000.png figure-00005.png animation/frame-00003.png animation.gif; do
  [ -s "$run/pictures/$picture" ] || { echo "render.py wrote no $picture"; exit 1; }
done
echo "render.py wrote the figures, $frames animation frames and the GIF"
