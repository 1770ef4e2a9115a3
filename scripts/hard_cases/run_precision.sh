#!/usr/bin/env bash
# Work-precision of the integrator on the hard cases (problems/scenes/hard/), each against its
# independent reference (reference/<scene>.csv), written to results/hard-cases/<scene>/
# (precision.json, work_precision.png). Not part of the test suite: about 15 minutes on the 2-core VM,
# most of it the N = 40 four-bar (81 coordinates) at h = 2e-3 and 1e-3 over its whole 20 s.
# Needs a Release build: cmake --preset release && cmake --build --preset release.
set -euo pipefail
cd "$(dirname "$0")/../.."
mbsopt=build/release/app/mbsopt
hard=problems/scenes/hard
out=results/hard-cases

study() {  # scene, steps, then extra arguments
  local scene=$1 steps=$2
  shift 2
  echo "== $scene"
  "$mbsopt" precision "$hard/$scene.yaml" --reference "$hard/reference/$scene.csv" --steps "$steps" \
    --repeat 1 --target-error 1e-3 --out "$out/$scene" "$@"
}

# IFToMM A02, N = 40, 20 s: the steps from 2e-2 down to 1e-3.
study n_four_bar_a02 2e-2,1e-2,5e-3,2e-3,1e-3 --variants newmark
study n_four_bar_a02_flat 2e-2,1e-2,5e-3,2e-3,1e-3 --variants newmark
# N = 2 released flat: a step of h = 1e-2 lands 5e-6 rad from the singular position.
study n_four_bar_2_flat 1e-2,5e-3,2e-3,1e-3
# IFToMM A01, 2000 s: the benchmark's high precision (1e-3 m) is reached at h = 4e-4 (5 million steps).
study pendulum_a01 1e-2,5e-3,2.5e-3,1e-3,5e-4,4e-4 --variants newmark,fast-newton
# Andrews' squeezer, 30 ms, against the published values of the IVP test set.
study andrews_squeezer 1e-4,5e-5,2e-5,1e-5,5e-6
