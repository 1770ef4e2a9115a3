#!/usr/bin/env bash
# Makes `python3 -c "import mbsopt"` find the module of a build tree (BUILD_DIR, default
# build/release): writes mbsopt.pth, naming BUILD_DIR/python, into the user's site-packages of the
# python3 the module was built for (the build's Python3_EXECUTABLE, Debian's /usr/bin/python3) and of
# the python3 on PATH when that is another interpreter of the same version. No copy: the module
# follows every rebuild. `cmake --install build/release --component python --prefix PREFIX` installs
# a copy instead.
#
#   scripts/register-python-module.sh [BUILD_DIR]
set -euo pipefail
case "${1:-}" in
  -h|--help) awk 'NR > 1 && /^#/ { print; next } NR > 1 { exit }' "$0"; exit 0 ;;
  -*) echo "$(basename "$0"): unknown option $1 (try --help)" >&2; exit 2 ;;
esac
build_dir=$(realpath -m "${1:-$(dirname "$0")/../build/release}")
module_dir="$build_dir/python"
cache="$build_dir/CMakeCache.txt"
built_for=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$cache" 2>/dev/null || true)
if [ -z "$built_for" ] || ! ls "$module_dir"/mbsopt.*.so > /dev/null 2>&1; then
  echo "register-python-module: no Python module in $module_dir (configure with -DMBSOPT_BUILD_PYTHON=ON and build)" >&2
  exit 1
fi
version() { "$1" -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")'; }
interpreters=("$built_for")
on_path=$(command -v python3 || true)
if [ -n "$on_path" ] && [ "$(realpath "$on_path")" != "$(realpath "$built_for")" ]; then
  if [ "$(version "$on_path")" = "$(version "$built_for")" ]; then
    interpreters+=("$on_path")
  else
    echo "register-python-module: $on_path is Python $(version "$on_path"), the module is built for" \
         "$built_for (Python $(version "$built_for")): use that one, or configure with" \
         "-DPython3_EXECUTABLE=$on_path and rebuild" >&2
  fi
fi
for python in "${interpreters[@]}"; do
  site=$("$python" -m site --user-site)
  mkdir -p "$site"
  echo "$module_dir" > "$site/mbsopt.pth"
  if ! (cd / && "$python" -c "import mbsopt" 2> /dev/null); then
    echo "register-python-module: $python cannot import mbsopt after writing $site/mbsopt.pth" \
         "(is its user site disabled? PYTHONPATH=$module_dir works too)" >&2
    exit 1
  fi
  echo "register-python-module: $python imports mbsopt from $module_dir ($site/mbsopt.pth)"
done
