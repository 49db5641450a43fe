#!/usr/bin/env bash
# Installs every Debian package HexDom needs to build, test and run the demo. Idempotent: packages that
# are already installed are skipped, so a second run costs a dpkg query and nothing else.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libeigen3-dev pybind11-dev libcli11-dev libgtest-dev zlib1g-dev
  libocct-data-exchange-dev libocct-modeling-algorithms-dev libocct-modeling-data-dev
  libocct-foundation-dev libocct-ocaf-dev libocct-visualization-dev libtbb-dev
  python3-dev python3-numpy python3-pytest python3-vtk9 python3-meshio
  freecad-python3 calculix-ccx xvfb xauth
  gmsh python3-gmsh
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
