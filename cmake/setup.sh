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
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-tqdm python3-distributed)

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

build() {
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build build -j "$(nproc)"
}

case "${1:-example}" in
  build) install_missing; build ;;
  test)
    install_missing; build
    cd build && ctest --output-on-failure -j "$(nproc)" ;;
  example)
    install_missing; build
    cmake --install build >/dev/null  # sizemesh on the PATH, `import sizemesh` in python3
    sizemesh examples/onera_m6_wing.stp -o onera_m6_wing.vtu --background onera_m6_wing_background.vtu ;;
  *) echo "usage: bash cmake/setup.sh [example|test|build]" >&2; exit 2 ;;
esac
