#!/usr/bin/env bash
# Side by side with peers: builds bench/peer/peer_comparison against Debian's Simbody and MuJoCo and
# writes results/peer-comparison/ (peer_comparison.json, peer_comparison.md, work_precision_<mechanism>.png).
# By default: four_bar, chain8, nfourbar4, andrews (Andrews' squeezer, problems/scenes/hard/), humanoid
# (MuJoCo's sample, mbsopt and MuJoCo only) and the a02_singular survey. Not part of the test suite: ~5-10 minutes on the 2-core VM. Extra arguments go to
# the program, e.g.
#   scripts/peer_comparison.sh --mechanisms four_bar,andrews       # a subset
#   scripts/peer_comparison.sh --mechanisms nfourbar16             # opt-in, ~10 minutes more
#   scripts/peer_comparison.sh --quick --out /tmp/peer             # a smoke run
# Note: Debian's libsimbody is built with assertions on (CMAKE_BUILD_TYPE=None, no -DNDEBUG), roughly 2x
# slower than upstream's Release build. Environment:
#   SIMBODY_RELEASE=1   compare with Simbody at its best instead: runs bench/build_simbody_release.sh first
#                       (Debian's source package built with upstream's Release flags, -O2 -DNDEBUG, into
#                       build/simbody-release/; ~10 minutes once on 2 cores) and builds against it
#                       (-DSimbody_DIR=build/simbody-release/lib/cmake/simbody) in build/peer-release.
#   PEER_BUILD_DIR=DIR  the build directory (default build/peer, or build/peer-release with SIMBODY_RELEASE=1)
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
simbody_args=()
if [ "${SIMBODY_RELEASE:-0}" = 1 ]; then
  bench/build_simbody_release.sh
  simbody_dir=$PWD/build/simbody-release/lib/cmake/simbody
  simbody_args=(-DSimbody_DIR="$simbody_dir")
  build=${PEER_BUILD_DIR:-build/peer-release}
else
  build=${PEER_BUILD_DIR:-build/peer}  # the build directory (PEER_BUILD_DIR overrides)
fi
configure=$(cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DMBSOPT_BUILD_TESTS=OFF "${simbody_args[@]}")
grep '^-- peer_comparison: Simbody' <<< "$configure" || true  # which Simbody (bench/peer/CMakeLists.txt)
cmake --build "$build" -j"$(nproc)" --target peer_comparison
simbody_lib=$(ldd "$build"/bench/peer/peer_comparison | awk '/libSimTKsimbody/ {print $3}')
if [ "${SIMBODY_RELEASE:-0}" = 1 ] && [ "$(dirname "$(realpath "$simbody_lib")")" != "$(realpath "$PWD/build/simbody-release/lib")" ]; then
  echo "peer_comparison: $build/bench/peer/peer_comparison loads $simbody_lib, not the Release build" >&2
  exit 1
fi

out=results/peer-comparison
args=("$@")
for ((i = 0; i < ${#args[@]}; ++i)); do [ "${args[i]}" = "--out" ] && out=${args[i + 1]}; done
mkdir -p "$out"
# Simbody's CPodes prints its own warnings on stderr: they go to the log with the progress lines.
"$build"/bench/peer/peer_comparison --out "$out" "$@" 2> "$out/run.log" || { tail -20 "$out/run.log"; exit 1; }
grep -v '^$' "$out/run.log" | grep -E '^(==|   (simbody|mujoco|mbsopt|agreement|Simbody))|^wrote' || true

{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//') ($(nproc) cores)"
  echo "mujoco package: $(dpkg-query -W -f='${Package} ${Version}' libmujoco-dev 2>/dev/null || echo unknown)"
  if [ "${SIMBODY_RELEASE:-0}" = 1 ]; then
    source_version=$(cd build/simbody-src && ls simbody_*.dsc 2>/dev/null | sed 's/^simbody_//; s/\.dsc$//' || true)
    echo "simbody: Release build of Debian's source package simbody ${source_version:-unknown} (bench/build_simbody_release.sh)"
    echo "simbody flags: $(sed -n "s/^CMAKE_CXX_FLAGS_RELEASE:STRING=//p" build/simbody-build/CMakeCache.txt 2>/dev/null | tr -d "'" | xargs)"
    echo "simbody config: $(realpath --relative-to="$PWD" "$simbody_dir") (in the repository)"
    echo "simbody library: $(realpath --relative-to="$PWD" "$simbody_lib") (in the repository)"
    echo "compiler: $(c++ --version | head -1)"
  else
    echo "simbody package: $(dpkg-query -W -f='${Package} ${Version}' libsimbody-dev 2>/dev/null || echo unknown)"
    echo "compiler: $(c++ --version | head -1)"
    echo "note: Debian's Simbody is built with assertions on, roughly 2x slower than upstream's Release build"
  fi
} > "$out/environment.txt"

(cd "$out" && for plot in work_precision_*.gp; do gnuplot "$plot"; done)
echo "peer_comparison: wrote $out/ ($(cd "$out" && ls *.png | tr '\n' ' '))"
