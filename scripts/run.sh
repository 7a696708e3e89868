#!/usr/bin/env bash
# Sets everything up, then runs ritr on the given scene. Without one it shows the method: r-ITR
# on a coarse soft ball dropped on spikes (prm/ritr_ball_on_spikes_2d.prm), the fixed mesh of
# the same size for contrast and a finer fixed mesh as the yardstick, and prints one line
# comparing them (scripts/ladder.py; results in output/showcase/).
# Usage: scripts/run.sh [SCENE.prm]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
cd "$root"
if [ $# -gt 0 ]; then
  exec "$root/build/ritr" "$1"
fi
rm -rf output/showcase
exec /usr/bin/python3 scripts/ladder.py prm/ritr_ball_on_spikes_2d.prm --fixed 0 1 --work output/showcase \
  --out output/showcase/comparison.json --summary
