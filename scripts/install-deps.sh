#!/usr/bin/env bash
# Installs the Debian packages mbsopt needs, and only those missing (idempotent).
# Uses sudo only when not already root.
set -euo pipefail

packages=(
  g++ cmake make            # toolchain
  clang libclang-rt-14-dev  # the sanitizer build and the libFuzzer target (docs/fuzzing.md)
  libeigen3-dev             # dense linear algebra, AutoDiff
  libcli11-dev              # command line
  libgtest-dev              # tests
  libbenchmark-dev          # benchmarks
  libyaml-dev               # scene files (libyaml, the C reference parser)
  nlohmann-json3-dev        # machine-readable outputs
  libnlopt-cxx-dev          # SLSQP, MMA, CCSAQ
  coinor-libipopt-dev       # Ipopt 3.11
  gnuplot-nox               # plots
  pkg-config                # finds Ipopt
  libopenmpi-dev openmpi-bin  # `mpirun -n N mbsopt benchmark` (the sweep over MPI ranks)
  pybind11-dev python3-dev python3-numpy  # the Python module (python/)
  python3-matplotlib        # its example, python/examples/tramway_comparison.py
  libsimbody-dev            # the peer engine of bench/peer (scripts/peer_comparison.sh); optional for the build
  python3-scipy python3-mpmath  # hard-case references (scripts/hard_cases/make_references.py)
  libmujoco-dev             # MJCF and URDF model files, compiled by MuJoCo (7-io/model_file.hpp)
  libqhull-dev              # the include folder that libmujoco-dev's CMake target names (Debian 12 omits the dependency)
  libmujoco-samples         # the sample models the MuJoCo comparison reads (tests/7-io/test_model_file.cpp)
  mkdocs doxygen            # the documentation site and its C++ API reference (scripts/build-docs.sh)
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages are installed"
  exit 0
fi

as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
echo "install-deps: installing ${missing[*]}"
"${as_root[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
