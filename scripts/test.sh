#!/usr/bin/env bash
# Sets everything up, then runs every test not labelled 'benchmark'.
# Usage: scripts/test.sh [extra ctest arguments]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh" --with-paraview
cd "$root/build"
ctest --output-on-failure -LE benchmark -j "$(nproc)" "$@"
