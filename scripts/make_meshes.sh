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
gmsh -3 chicken.geo -o chicken.msh > /dev/null
gmsh -3 spike_bed.geo -o spike_bed.msh > /dev/null
gmsh -2 jelly_mold.geo -o jelly_mold.msh > /dev/null
gmsh -2 fork.geo -o fork.msh > /dev/null
python3 "$root/scripts/extrude_stamps.py" --depth 0.3 stamps/qi.obj stamps/tian.obj stamps/da.obj stamps/sheng.obj
for stamp in qi tian da sheng; do
  gmsh -2 "stamps/${stamp}_3d.geo" -o "stamps/${stamp}_3d.msh" > /dev/null
done
echo "meshes regenerated: $(ls *.msh stamps/*.msh | tr '\n' ' ')"
