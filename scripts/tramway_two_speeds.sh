#!/usr/bin/env bash
# The tramway's design problem under two load cases: the paper's speed (3.7 m/s for 12 s) and a
# faster pass (4.5 m/s for 10 s, which ends before the track does). The scene is
# problems/scenes/tramway.yaml with a `load_cases:` section added to its design (written to
# results/tramway-two-speeds/tramway_two_speeds.yaml, beside the results); every optimizer runs on
# it with adjoint gradients, `mbsopt compare … --jobs 1`, into results/tramway-two-speeds (about
# 20 s). The cost is the worst case's max |a_lat| and each
# yaw limit holds in both cases. It uses the Release build (scripts/main.sh or the README's build
# commands build it).
#
#   scripts/tramway_two_speeds.sh
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
  -h|--help) awk 'NR > 1 && /^#/ { print; next } NR > 1 { exit }' "$0"; exit 0 ;;
  "") ;;
  *) echo "$(basename "$0"): unknown option $1 (try --help)" >&2; exit 2 ;;
esac
mbsopt=build/release/app/mbsopt
[ -x "$mbsopt" ] || { echo "tramway_two_speeds.sh: $mbsopt is not built (cmake --build --preset release)" >&2; exit 1; }
out=results/tramway-two-speeds
mkdir -p "$out"
scene=$out/tramway_two_speeds.yaml  # kept beside the results it produced
cat problems/scenes/tramway.yaml - > "$scene" <<'CASES'
  load_cases:
    - {name: nominal}
    - {name: fast, set: {bogie1_track.motion.polynomial.1: 4.5, bogie2_track.v0: 4.5, settings.end_time: 10}}
CASES
"$mbsopt" compare "$scene" --max-iter 100 --jobs 1 --out "$out"
