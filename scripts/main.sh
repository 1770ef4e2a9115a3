#!/usr/bin/env bash
# The main job: install what is missing, build (Release), simulate the tramway of
# shared/specs/tramway.md at the initial design b0 and write tramway.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release -DMBSOPT_BUILD_TESTS=OFF -DMBSOPT_BUILD_BENCH=OFF > /dev/null
cmake --build --preset release -j "$(nproc)"
build/release/app/mbsopt simulate tramway --out tramway.csv
