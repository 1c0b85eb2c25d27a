#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine (run as root):
#   bash cmake/setup.sh example   install what is missing, build, install sizemesh (/usr/local), mesh the bundled example
#   bash cmake/setup.sh test      install what is missing, build, run the whole test suite
#   bash cmake/setup.sh build     install what is missing and build
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(cmake ninja-build g++ pkg-config
  libocct-data-exchange-dev libocct-modeling-algorithms-dev libocct-modeling-data-dev libocct-foundation-dev
  libvtk9-dev liblpsolve55-dev libeigen3-dev libtbb-dev catch2 libcli11-dev nlohmann-json3-dev libmuparser-dev
  libboost-dev libcgal-dev libcgns-dev cgns-convert tetgen python3-meshio gmsh
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-tqdm python3-distributed
  # paraview and xvfb (a virtual X server: Debian's ParaView renders through X only) for
  # examples/paraview_view.py; its Python package is unpacked by paraview_python below.
  paraview xvfb)

install_missing() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "installing: ${missing[*]}"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
}

# ParaView's Python package (pvpython), unpacked into build/paraview-python:
# Debian's python3-paraview conflicts with python3-vtk9, which libvtk9-dev
# needs, so it cannot be installed beside it; unpacked, it runs on the
# installed paraview's libraries (examples/paraview_view.py puts it first on
# its path through SIZEMESH_PARAVIEW_PYTHON).
paraview_python() {
  local dir=build/paraview-python
  ls "$dir"/usr/bin/pvpython* >/dev/null 2>&1 && return 0
  local tmp
  tmp=$(mktemp -d)
  (cd "$tmp" && { apt-get download python3-paraview >/dev/null 2>&1 ||
                  { apt-get update -qq && apt-get download python3-paraview >/dev/null 2>&1; }; }) ||
    { echo "setup: python3-paraview could not be downloaded; the ParaView test will be skipped" >&2; rm -rf "$tmp"; return 0; }
  mkdir -p "$dir"
  dpkg -x "$tmp"/python3-paraview_*.deb "$dir"
  rm -rf "$tmp"
}

build() {
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build build -j "$(nproc)"
}

case "${1:-example}" in
  build) install_missing; paraview_python; build ;;
  test)
    install_missing; paraview_python; build
    cd build && ctest --output-on-failure -j "$(nproc)" ;;
  example)
    install_missing; paraview_python; build
    cmake --install build >/dev/null  # sizemesh on the PATH, `import sizemesh` in python3
    sizemesh examples/onera_m6_wing.stp -o onera_m6_wing.vtu --background onera_m6_wing_background.vtu ;;
  *) echo "usage: bash cmake/setup.sh [example|test|build]" >&2; exit 2 ;;
esac
