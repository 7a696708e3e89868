#!/usr/bin/env bash
# Sets everything up, then runs ritr on the given scene (prm/default.prm when none is given).
# Usage: scripts/run.sh [SCENE.prm]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
scene="${1:-$root/prm/default.prm}"
cd "$root"
exec "$root/build/ritr" "$scene"
