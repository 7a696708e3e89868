#!/usr/bin/env bash
# Sets everything up, then runs the benchmark suite (ctest label 'benchmark').
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
cd "$root/build"
ctest --output-on-failure -L benchmark "$@"
