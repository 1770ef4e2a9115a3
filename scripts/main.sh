#!/usr/bin/env bash
# The main job: install what is missing, build (Release), simulate the tramway of
# docs/tramway.md at the initial design b0 (tramway.csv), then optimise its yaw suspension
# with the default optimizer, the paper's SDCC, on the paper's formulation ∫⟨φ⟩dt with adjoint
# gradients (tramway-optimum/: result.json, history.png, response.png).
# It also registers the Python module of the build tree with python3 for this user (a .pth file in
# the user's site-packages naming build/release/python), so `python3 -c "import mbsopt"` works from
# anywhere and follows every rebuild; `rm "$(python3 -m site --user-site)/mbsopt.pth"` undoes it.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
# A first configuration leaves the tests and benchmarks out; a tree already configured keeps its
# choices (turning them off would leave ctest running the stale test list of scripts/test.sh's build).
options=()
[ -f build/release/CMakeCache.txt ] || options=(-DMBSOPT_BUILD_TESTS=OFF -DMBSOPT_BUILD_BENCH=OFF)
cmake --preset release "${options[@]}" > /dev/null
cmake --build --preset release -j "$(nproc)"
scripts/register-python-module.sh || echo "main.sh: the Python module is not registered (above); the main job goes on" >&2
build/release/app/mbsopt simulate tramway --out tramway.csv
build/release/app/mbsopt optimize tramway --out tramway-optimum
