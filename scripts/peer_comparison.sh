#!/usr/bin/env bash
# Side by side with a peer (issue 11): builds bench/peer/peer_comparison against Debian's Simbody and
# writes results/peer-comparison/ (peer_comparison.json, peer_comparison.md, work_precision_<mechanism>.png).
# Not part of the test suite: ~5-10 minutes on the 2-core VM. Extra arguments go to the program, e.g.
#   scripts/peer_comparison.sh --mechanisms four_bar,chain8        # a subset
#   scripts/peer_comparison.sh --mechanisms nfourbar16             # opt-in, ~10 minutes more
#   scripts/peer_comparison.sh --quick --out /tmp/peer             # a smoke run
# Note: Debian's libsimbody is built with assertions on, roughly 2x slower than upstream's Release build.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
build=${PEER_BUILD_DIR:-build/peer}  # the build directory (PEER_BUILD_DIR overrides)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DMBSOPT_BUILD_TESTS=OFF > /dev/null
cmake --build "$build" -j"$(nproc)" --target peer_comparison

out=results/peer-comparison
args=("$@")
for ((i = 0; i < ${#args[@]}; ++i)); do [ "${args[i]}" = "--out" ] && out=${args[i + 1]}; done
mkdir -p "$out"
# Simbody's CPodes prints its own warnings on stderr: they go to the log with the progress lines.
"$build"/bench/peer/peer_comparison --out "$out" "$@" 2> "$out/run.log" || { tail -20 "$out/run.log"; exit 1; }
grep -v '^$' "$out/run.log" | grep -E '^(==|   (simbody|mbsopt|agreement|Simbody))|^wrote' || true

{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//') ($(nproc) cores)"
  echo "simbody package: $(dpkg-query -W -f='${Package} ${Version}' libsimbody-dev 2>/dev/null || echo unknown)"
  echo "compiler: $(c++ --version | head -1)"
  echo "note: Debian's Simbody is built with assertions on, roughly 2x slower than upstream's Release build"
} > "$out/environment.txt"

(cd "$out" && for plot in work_precision_*.gp; do gnuplot "$plot"; done)
echo "peer_comparison: wrote $out/ ($(cd "$out" && ls *.png | tr '\n' ' '))"
