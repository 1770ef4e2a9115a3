#!/usr/bin/env bash
# Install what is missing, build everything (Release), run the whole test suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release -DMBSOPT_BUILD_TESTS=ON -DMBSOPT_BUILD_BENCH=ON > /dev/null
cmake --build --preset release -j "$(nproc)"
ctest --preset release -j "$(nproc)"
