#!/usr/bin/env bash
# Runs the concurrency test (tests/5-sensitivity/test_parallel_runs.cpp: design evaluations, finite differences,
# exact gradients and whole SDCC, SLSQP and Ipopt optimisations on the thread pool of
# 5-sensitivity/parallel_runs.hpp) under ThreadSanitizer (docs/thread-sanitizer.md). Configures the
# tsan preset (clang, -fsanitize=thread, -O1 -g, build/tsan), builds only test_parallel_runs and
# what it links, runs it; any ThreadSanitizer report, any failed test, exits non-zero. The run's
# output is kept in build/tsan/tsan.log.
#
#   scripts/tsan.sh                 # configure, build (-j2), run
#   scripts/tsan.sh --no-build      # run the binary already built
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/build_option.sh "$@"
if [ "$build" -eq 1 ]; then
  cmake --preset tsan > /dev/null
  cmake --build --preset tsan --target test_parallel_runs -j2
fi
binary=build/tsan/tests/test_parallel_runs
log=build/tsan/tsan.log

# halt_on_error: the first report ends the run with a failure; second_deadlock_stack: a lock-order
# report shows where both locks were taken. Suppressions, each one explained, only for races inside
# the uninstrumented system libraries (tests/tsan.supp, read when it exists).
options="halt_on_error=1 second_deadlock_stack=1"
[ -f tests/tsan.supp ] && options="$options suppressions=$(pwd)/tests/tsan.supp print_suppressions=1"
export TSAN_OPTIONS="$options${TSAN_OPTIONS:+ $TSAN_OPTIONS}"

status=0
start=$SECONDS
"$binary" 2>&1 | tee "$log" || status=$?
elapsed=$((SECONDS - start))
if [ "$status" -ne 0 ] || grep -q "WARNING: ThreadSanitizer" "$log"; then
  echo "tsan.sh: FAILED (exit $status, $(grep -c "WARNING: ThreadSanitizer" "$log" || true) report(s), ${elapsed} s; log: $log)" >&2
  exit 1
fi
echo "tsan.sh: no ThreadSanitizer report, all tests passed (${elapsed} s; log: $log)"
