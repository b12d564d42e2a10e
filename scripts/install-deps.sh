#!/usr/bin/env bash
# Installs every Debian 12 package dustlift needs (build, tests, renders, figures).
# Debian 12: libvtk9-dev conflicts with python3-paraview,
# so C++ builds against ParaView's bundled VTK (paraview-dev + libglew-dev).
# The second group is what find_package(ParaView COMPONENTS Catalyst PythonCatalyst) needs
# for the Catalyst adaptor (cmake/catalyst.cmake): Debian's paraview-dev does not pull it in.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update
$SUDO apt-get install -y --no-install-recommends \
  build-essential cmake ninja-build ccache pkg-config git \
  paraview python3-paraview paraview-dev libglew-dev \
  libhdf5-dev libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev \
  libtomlplusplus-dev libcli11-dev libfmt-dev zlib1g-dev \
  xvfb xauth python3-numpy python3-matplotlib python3-h5py \
  libopenmpi-dev libutfcpp-dev liblz4-dev libdouble-conversion-dev libnetcdf-dev libboost-dev \
  libfreetype-dev libxml2-dev libx11-dev python3-dev
