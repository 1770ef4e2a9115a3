#!/usr/bin/env bash
# ctest: scripts/register-python-module.sh BUILD_DIR makes `python3 -c "import mbsopt"` load the
# build tree's module from any directory, for a user whose site-packages did not have it (a fresh
# HOME), with the python3 on PATH and with the interpreter the module was built for. Before the
# registration neither may load the build tree's module (a copy installed elsewhere may load), or
# the test would prove nothing.
# Usage: registered_import.sh SOURCE_DIR BUILD_DIR PYTHON3_EXECUTABLE
set -euo pipefail
source_dir=$1 build_dir=$(realpath "$2") built_for=$3
home=$(mktemp -d)
trap 'rm -rf "$home"' EXIT
export HOME=$home
unset PYTHONPATH
loads_the_build_trees() {  # PYTHON: whether it imports mbsopt from BUILD_DIR/python, from /
  (cd / && "$1" -c "
import sys
try:
    import mbsopt
except ImportError:
    sys.exit(1)
sys.exit(0 if mbsopt.__file__.startswith('$build_dir/python/') else 1)")
}
interpreters=(python3 "$built_for")
for python in "${interpreters[@]}"; do
  if loads_the_build_trees "$python"; then
    echo "FAIL: $python loads the build tree's module before the registration" >&2
    exit 1
  fi
done
"$source_dir/scripts/register-python-module.sh" "$build_dir"
for python in "${interpreters[@]}"; do
  if ! loads_the_build_trees "$python"; then
    echo "FAIL: $python does not load the build tree's module after the registration" >&2
    exit 1
  fi
  (cd / && "$python" -c "import mbsopt; print('$python imports mbsopt', mbsopt.__version__, 'from', mbsopt.__file__)")
done
