#!/usr/bin/env bash
# Installs every Debian 12 package the project needs to build, test and run.
# Safe to run again: apt-get skips what is already installed.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config libgtest-dev
  time                   # /usr/bin/time: peak memory in the benchmarks
  libvtk9-dev            # VTK 9.1: modules, pipeline, OpenGL2 rendering, vtkTesting
  libvtk9-qt-dev qtbase5-dev libqt5opengl5-dev   # atp-view: VTK's Qt widget, Qt 5 Widgets/Test
  libcgal-dev            # minimum enclosing balls (Min_sphere_of_spheres_d)
  libtet1.5-dev          # TetGen: conformity checks in tests
  libmeshoptimizer-dev   # vertex-cache order, index/vertex codecs
  libxxhash-dev          # patch and section checksums (XXH3)
  zlib1g-dev             # reading the header of a .nii.gz before VTK does (VTK::zlib)
  libopenmpi-dev openmpi-bin   # VTK 9.1 on Debian links MPI; distributed build
  xvfb xauth             # headless rendering for tests
  clang libclang-rt-14-dev   # libFuzzer for scripts/fuzz.sh
  libx11-dev             # XOpenDisplay: no X display is a clear error, not VTK's abort
  libegl-dev libglew-dev # without a display, atp draws on an EGL device (a headless GPU)
  mricron-data           # real MRI volumes for the brain isosurface benchmark
)

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps.sh: run as root (apt-get needs it)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
