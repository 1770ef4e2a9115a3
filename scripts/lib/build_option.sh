# Options of the scripts that build one target and then run it (tsan.sh, count_instructions.sh),
# sourced with the script's arguments: sets build=1, or 0 with --no-build (run what is built);
# --help prints the script's own header (its comment lines after the first).
build=1
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) build=0; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ { print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "$(basename "$0"): unknown option $1 (try --help)" >&2; exit 2 ;;
  esac
done
