#!/usr/bin/env bash
# ctest: scripts/register-python-module.sh BUILD_DIR makes `python3 -c "import mbsopt"` work from any
# directory, loading the build tree's module, for a user whose site-packages did not have it (a
# fresh HOME; before the registration the import must fail, or the test would prove nothing).
# Usage: registered_import.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1 build_dir=$(realpath "$2")
home=$(mktemp -d)
trap 'rm -rf "$home"' EXIT
export HOME=$home
unset PYTHONPATH
if (cd / && python3 -c "import mbsopt" 2> /dev/null); then
  echo "FAIL: python3 imports mbsopt before the registration" >&2
  exit 1
fi
"$source_dir/scripts/register-python-module.sh" "$build_dir"
(cd / && python3 -c "
import mbsopt
assert mbsopt.__file__.startswith('$build_dir/python/'), mbsopt.__file__
assert 'sdcc' in mbsopt.optimizers()
print('python3 imports mbsopt', mbsopt.__version__, 'from', mbsopt.__file__)")
