#!/usr/bin/env bash
# Install what is missing, build everything, run the whole test suite with ctest: once in Release,
# once under AddressSanitizer + UndefinedBehaviorSanitizer (any report aborts the test); and build
# the documentation site from the Release build (warnings as errors, links checked).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs="$(nproc)"
cmake --preset release -DMBSOPT_BUILD_TESTS=ON -DMBSOPT_BUILD_BENCH=ON > /dev/null
cmake --build --preset release -j "$jobs"
ctest --preset release -j "$jobs"
scripts/build-docs.sh build/release
cmake --preset sanitize -DMBSOPT_BUILD_TESTS=ON > /dev/null
cmake --build --preset sanitize -j "$jobs"
ctest --preset sanitize -j "$jobs"
