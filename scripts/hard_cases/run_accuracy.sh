#!/usr/bin/env bash
# Runs driven by accuracy on every hard case, whole, each against its independent reference
# `mbsopt simulate SCENE --accuracy TOL` for TOL = 1e-3 … 1e-8, the true error beside the
# error the run estimated. Writes results/hard-cases/accuracy.md (the table) and accuracy.json.
# Not part of the test suite (the N = 40 four-bars take minutes); the tests run the short scenes and
# A01's first 20 s. Needs a Release build: cmake --preset release && cmake --build --preset release.
# INTEGRATOR=adaptive runs the adaptive Newmark instead of the extrapolation, into accuracy-adaptive.md
# and .json; extra arguments go to check_accuracy.py (e.g. --tolerances 1e-3,1e-4,1e-5,1e-6).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=results/hard-cases
mkdir -p "$out"
integrator=${INTEGRATOR:-extrapolation}
name=accuracy
[ "$integrator" = extrapolation ] || name=accuracy-$integrator
{
  echo "# Runs driven by accuracy on the hard cases ($integrator)"
  echo
  echo "\`scripts/hard_cases/run_accuracy.sh\`, $(date -u +%Y-%m-%d), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//') ($(nproc) cores)."
  echo "True error: the largest over the reference's sensors and times; estimated: the run's own estimate for that sensor."
  echo
  python3 scripts/hard_cases/check_accuracy.py --integrator "$integrator" --out "$out/$name.json" "$@"
} | tee "$out/$name.md"
