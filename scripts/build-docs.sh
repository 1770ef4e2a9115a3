#!/usr/bin/env bash
# Builds the documentation site into build/docs/site (MkDocs, Debian's package; mkdocs.yml names the
# pages): gathers docs/, the folders' READMEs, the reference pages generated from the code
# (scripts/docs_reference.py, from the built program and Python module) and the C++ API reference
# (Doxygen, Doxyfile) into build/docs/pages, then builds them with --strict, so that a warning or a
# link to a page that does not exist fails (and Doxygen fails on any warning of its own).
#   scripts/build-docs.sh [BUILD_DIR]   (default build/release, which must be built)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/release}"
pages=build/docs/pages
rm -rf "$pages" build/docs/site
mkdir -p "$pages"
cp -r docs/. "$pages/"
cp problems/scenes/README.md "$pages/scene-files.md"
cp problems/suite/README.md "$pages/problem-suite.md"
cp 5-sensitivity/README.md "$pages/sensitivity.md"
cp 6-optimizers/README.md "$pages/optimizers.md"
find results -name '*.png' -exec cp --parents {} "$pages/" \;  # the figures the pages show
python="$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")"  # the module's interpreter
"${python:-python3}" scripts/docs_reference.py --mbsopt "$build/app/mbsopt" --python-path "$build/python" \
  --out "$pages/reference"
doxygen Doxyfile
mkdocs build --strict --quiet
echo "build-docs: build/docs/site/index.html"
