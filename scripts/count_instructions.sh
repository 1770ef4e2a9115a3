#!/usr/bin/env bash
# Counts the instructions of one tramway simulation (12 s at h = 1 ms, default settings), of one
# design evaluation of the tramway problem (the simulation with its sensors, then the functionals)
# and of one adjoint and one direct gradient of that problem (all 7 functionals, the paper's 4
# design variables, with its simulation, one thread) under valgrind's callgrind: figures that do not
# move with the load of a shared machine, for comparing two versions where timings spread by ±30 %.
# Valgrind cannot run the default -march=native build (AVX-512), so this configures a portable one
# in build/portable (-DMBSOPT_NATIVE=OFF, Release, no tests) and builds bench_dynamics and
# bench_gradients there. Only NewmarkIntegrator::simulate, evaluateDesign, adjointGradient or
# directGradient, and what they call, are counted: callgrind's --toggle-collect switches counting at
# every entry to and exit from a function its pattern matches, so each pattern names the one
# overload that does the work (the convenience overloads call it, and a pattern matching both would
# switch counting off inside it). The four runs take about 5 minutes.
#
#   scripts/count_instructions.sh              # configure, build (-j2), count
#   scripts/count_instructions.sh --no-build   # count with the binary already built
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/build_option.sh "$@"
command -v valgrind > /dev/null || { echo "count_instructions.sh: valgrind is not installed (apt-get install valgrind)" >&2; exit 1; }
if [ "$build" -eq 1 ]; then
  cmake -S . -B build/portable -DCMAKE_BUILD_TYPE=Release -DMBSOPT_NATIVE=OFF -DMBSOPT_BUILD_TESTS=OFF > /dev/null
  cmake --build build/portable --target bench_dynamics bench_gradients -j2
fi
out=build/portable/callgrind.tramway.out
valgrind --tool=callgrind --callgrind-out-file="$out" \
  --toggle-collect='mbsopt::NewmarkIntegrator::simulate(*mbsopt::Trajectory&, std::function<void (long)> const&)' \
  build/portable/bench/bench_dynamics --benchmark_filter='TramwaySimulation/accept_by_rate:0/kept_buffers:1' \
  --benchmark_min_time=0.01 2> build/portable/callgrind.log > build/portable/callgrind.bench.txt
# Under valgrind one simulation takes seconds, far above the minimum time: one iteration is run.
iterations=$(awk '/^BM_TramwaySimulation/ {print $6}' build/portable/callgrind.bench.txt)
[ "$iterations" = "1" ] || { echo "count_instructions.sh: expected one benchmark iteration, got '$iterations'" >&2; exit 1; }
count=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' build/portable/callgrind.log)
[ -n "$count" ] || { echo "count_instructions.sh: callgrind reported no count (build/portable/callgrind.log)" >&2; exit 1; }
echo "instructions in one tramway simulation (12000 steps): $count ($((count / 12000)) per step)"
echo "per function: callgrind_annotate --inclusive=yes $out"

# The design evaluations: bench_gradients' TramwaySimulation times evaluateDesign, and its set-up
# evaluates the point a few times more; the total is divided by the calls of simulate() that
# callgrind recorded (one per evaluation).
out=build/portable/callgrind.evaluation.out
valgrind --tool=callgrind --callgrind-out-file="$out" \
  --toggle-collect='mbsopt::evaluateDesign(*mbsopt::DesignResponse&, std::function<void (long)> const&, bool)' \
  build/portable/bench/bench_gradients --benchmark_filter='TramwaySimulation' \
  --benchmark_min_time=0.01 2> build/portable/callgrind.evaluation.log > /dev/null
count=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' build/portable/callgrind.evaluation.log)
calls=$(awk '/^c?fn=\([0-9]+\) mbsopt::NewmarkIntegrator::simulate\([^{]*\)$/ { split($1, p, /[()]/); id = p[2] }
             /^cfn=/ { cur = $1; sub(/^cfn=\(/, "", cur); sub(/\).*/, "", cur); want = (id != "" && cur == id); next }
             /^calls=/ { if (want) { split($1, c, "="); n += c[2] }; want = 0 }
             END { print n + 0 }' "$out")
[ -n "$count" ] && [ "$calls" -gt 0 ] || { echo "count_instructions.sh: no design evaluation counted (build/portable/callgrind.evaluation.log)" >&2; exit 1; }
echo "instructions in one tramway design evaluation: $((count / calls)) (over $calls evaluations)"
echo "per function: callgrind_annotate --inclusive=yes $out"

# The exact gradients: bench_gradients' GradientAdjoint/jobs:1/variables:4 (GradientDirect/...)
# times adjointGradient (directGradient) once per iteration, and under valgrind runs one iteration.
count_gradient() {  # method, benchmark, function
  local method=$1 benchmark=$2 function=$3
  local out=build/portable/callgrind.$method.out log=build/portable/callgrind.$method.log
  valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect="mbsopt::$function*" \
    build/portable/bench/bench_gradients --benchmark_filter="$benchmark/jobs:1/variables:4" \
    --benchmark_min_time=0.01 2> "$log" > "build/portable/callgrind.$method.txt"
  local iterations count
  iterations=$(awk -v name="^BM_Tramway$benchmark/" '$0 ~ name {print $6}' "build/portable/callgrind.$method.txt")
  [ "$iterations" = "1" ] || { echo "count_instructions.sh: expected one $method iteration, got '$iterations'" >&2; exit 1; }
  count=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$log")
  [ -n "$count" ] || { echo "count_instructions.sh: callgrind reported no count ($log)" >&2; exit 1; }
  echo "instructions in one tramway $method gradient, 4 design variables (with its simulation): $count"
  echo "per function: callgrind_annotate --inclusive=yes $out"
}
count_gradient adjoint GradientAdjoint adjointGradient
count_gradient direct GradientDirect directGradient
