#!/usr/bin/env bash
# Installs the Debian packages brdfbake needs; quick and silent when they are all present.
# Usage: scripts/setup.sh        (run as root, or with sudo available)
set -euo pipefail

packages=(
  cmake g++ make
  pocl-opencl-icd ocl-icd-opencl-dev opencl-clhpp-headers clinfo
  libopenexr-dev catch2 libcli11-dev nlohmann-json3-dev librandom123-dev
  libboost-math-dev libmgl-dev libyaml-cpp-dev
  pkg-config  # the install_consumer test checks brdfbake.pc
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module and its tests (Debian's /usr/bin/python3)
  libpng-dev  # 16-bit PNG tables (host/io/table_png.cpp)
  libjpeg-dev  # the ranges of glTF JPEG textures (host/scene/texture_image.cpp)
  libopenmpi-dev openmpi-bin  # MPI jobs (mpirun -np N brdfbake ...; docs/cluster.md) and their tests
  chromium  # the bake report rendered headless by its test (tests/test_bake_report_browser.cpp)
  mono-mcs  # the Unity HDRP .cs table compiled and read back by its test (tests/test_ltc_unity.cpp)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
