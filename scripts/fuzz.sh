#!/usr/bin/env bash
# Fuzzes mbsopt's user-text parsers with libFuzzer (docs/fuzzing.md).
#
#   scripts/fuzz.sh                      # build the target (sanitize preset), fuzz 60 s
#   scripts/fuzz.sh --seconds 1800 --jobs 2   # a long campaign, corpus kept in build/fuzz-corpus
#
# Every seed (the shipped scenes, the suite's design problems, the bad scenes of the tests,
# tests/fuzz/seeds) and every file of
# tests/fuzz/regressions/ runs first; then the fuzzer mutates. A finding (crash, sanitizer report,
# uncaught exception, an input slower than --timeout seconds or above 2 GB) is written to
# WORK/findings/ and the script exits 1: reduce it (the binary's -minimize_crash=1), add it to
# tests/fuzz/regressions/, fix the code.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
binary="" seconds=60 jobs=1 seed=0 timeout=10 work="$root/build/fuzz-corpus"
while [ $# -gt 0 ]; do
  case "$1" in
    --binary) binary="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --timeout) timeout="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    -h|--help) sed -n '2,11p' "$0"; echo "options: --binary PATH --seconds N (60) --jobs N (1) --seed N (0: random) --timeout S (10) --work DIR"; exit 0 ;;
    *) echo "fuzz.sh: unknown option $1 (try --help)" >&2; exit 2 ;;
  esac
done
if [ -z "$binary" ]; then
  cd "$root"
  cmake --preset sanitize -DMBSOPT_BUILD_TESTS=ON > /dev/null
  cmake --build --preset fuzz -j "$(nproc)"
  binary="$root/build/sanitize/tests/fuzz/fuzz_scene_input"
fi
binary="$(realpath "$binary")"
mkdir -p "$work/corpus" "$work/findings"
work="$(realpath "$work")"
rm -f "$work"/findings/* "$work"/fuzz-*.log

# The output corpus first (new inputs go there), then the read-only seed directories.
seeds=("$root/problems/scenes" "$root/problems/scenes/hard" "$root/problems/suite" "$root/tests/scenes/bad" "$root/tests/fuzz/seeds"
       "$root/tests/fuzz/regressions")
options=(-max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 -max_len=16384 -seed="$seed"
         -dict="$root/tests/fuzz/scene.dict" -artifact_prefix="$work/findings/" -print_final_stats=1)
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}" UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
if [ "$jobs" -gt 1 ]; then
  # -fork keeps going after a finding and writes every one to findings/.
  (cd "$work" && "$binary" -fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 "${options[@]}" \
      "$work/corpus" "${seeds[@]}") 2>&1 | tee "$work/fuzz.log" | grep -E "^#|INFO: fuzzed|DONE|stat::|ERROR|==ERROR" || true
else
  (cd "$work" && "$binary" "${options[@]}" "$work/corpus" "${seeds[@]}") > "$work/fuzz.log" 2>&1 || status=$?
  grep -E "INFO: seed corpus|INITED|DONE|stat::|ERROR|deadly|timeout|out-of-memory" "$work/fuzz.log" || true
fi
findings=$(find "$work/findings" -type f | wc -l)
if [ "$status" -ne 0 ] || [ "$findings" -gt 0 ]; then
  echo "fuzz.sh: $findings finding(s) in $work/findings (log: $work/fuzz.log)" >&2
  tail -n 40 "$work/fuzz.log" >&2
  exit 1
fi
echo "fuzz.sh: no finding in $seconds s (log: $work/fuzz.log)"
