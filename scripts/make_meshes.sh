#!/usr/bin/env bash
# Regenerates meshes/*.msh from their gmsh .geo sources (installs gmsh if missing). The .msh
# files are committed, so running ritr never needs gmsh.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if ! command -v gmsh > /dev/null; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq && $sudo_cmd apt-get install -y -qq --no-install-recommends gmsh
fi
cd "$root/meshes"
gmsh -2 wedge.geo -o wedge.msh > /dev/null
gmsh -1 funnel.geo -o funnel.msh > /dev/null
gmsh -1 angled_gap.geo -o angled_gap.msh > /dev/null
gmsh -3 wedge_3d.geo -o wedge_3d.msh > /dev/null
echo "meshes regenerated: $(ls *.msh | tr '\n' ' ')"
