#!/usr/bin/env bash
# Sets everything up (the programs only; scripts/test.sh builds the tests), then runs ritr on
# the given scene. Without one it shows the method: r-ITR on a coarse soft ball dropped on
# spikes (prm/ritr_ball_on_spikes_2d.prm), the fixed mesh of the same size and one refined once
# for contrast and one refined twice as the yardstick, and prints how they compare: accuracy,
# time, and the sentence of time to accuracy (scripts/ladder.py; results in output/showcase/).
# Usage: scripts/run.sh [SCENE.prm]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh" --programs
cd "$root"
if [ $# -gt 0 ]; then
  exec "$root/build/ritr" "$1"
fi
rm -rf output/showcase
exec /usr/bin/python3 scripts/ladder.py prm/ritr_ball_on_spikes_2d.prm --fixed 0 1 2 --work output/showcase \
  --out output/showcase/comparison.json --summary
