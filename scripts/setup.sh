#!/usr/bin/env bash
# Installs the Debian packages ritr needs (only those missing) and builds it (Release,
# incremental, ccache when available).
# Usage: scripts/setup.sh [--with-paraview] [--programs] [BUILD_DIR]
# --with-paraview also sets up ParaView's pvbatch for the pictures (scripts/render.py) and
# their test: about 550 MB and a few minutes more, so only on demand (scripts/test.sh asks).
# --programs builds only ritr and ritr-compare, not the tests (scripts/run.sh).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
with_paraview=false
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --with-paraview) with_paraview=true; shift ;;
    --programs) targets=(--target ritr ritr-compare); shift ;;
    *) break ;;
  esac
done
build="${1:-$root/build}"

# deal.II brings MPI and Trilinos (Amesos with MUMPS, ML); openmpi-bin is mpirun, for runs
# shared among processes and their test.
packages=(build-essential cmake libdeal.ii-dev openmpi-bin libeigen3-dev libsuitesparse-dev libtbb-dev
          libopenblas0-pthread libblas-dev libgtest-dev ccache libvtk9-dev libcgal-dev
          python3-numpy python3-matplotlib)  # ladder.py (frame metrics), ladder_report.py (plots)
$with_paraview && packages+=(paraview xvfb)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
sudo_cmd=""
[ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Debian's python3-paraview conflicts with python3-vtk9, which libvtk9-dev needs; its modules
# are unpacked into a folder of their own instead, which scripts/pvbatch.sh puts on the path.
paraview_python="${RITR_PARAVIEW_PYTHON:-${XDG_CACHE_HOME:-$HOME/.cache}/ritr/paraview-python}"
if $with_paraview && [ ! -d "$paraview_python/paraview" ]; then
  echo "setup: unpacking python3-paraview into $paraview_python"
  download="$(mktemp -d)"
  version="$(dpkg-query -W -f='${Version}' paraview)"
  (cd "$download" && { apt-get download -qq "python3-paraview=$version" 2>/dev/null ||
     { $sudo_cmd apt-get update -qq && apt-get download -qq "python3-paraview=$version"; }; })
  dpkg-deb -x "$download"/python3-paraview_*.deb "$download/unpacked"
  mkdir -p "$paraview_python"
  cp -r "$download/unpacked/usr/lib/python3/dist-packages/." "$paraview_python/"
  rm -rf "$download"
fi

mkdir -p "$build"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release > "$build/configure.log" 2>&1 ||
  { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j "$(nproc)" "${targets[@]}"
