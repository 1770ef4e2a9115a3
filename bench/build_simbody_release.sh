#!/usr/bin/env bash
# Builds Simbody 3.7 from Debian's *source package* with upstream's Release configuration, for a fair
# peer comparison (scripts/peer_comparison.sh with SIMBODY_RELEASE=1).
#
# Why: Debian's binary package (libsimbody-dev 3.7+dfsg-3) is configured by debhelper with
# CMAKE_BUILD_TYPE=None, so it gets only dpkg-buildflags (-g -O2 -fstack-protector-strong ...
# -D_FORTIFY_SOURCE=2) and *no* -DNDEBUG: every SimTK_ASSERT/SimTK_ERRCHK/range/stage check in
# SimTKcommon/internal/ExceptionMacros.h stays on. Its three patches (visualizer path, BSD/Hurd CPU count,
# tests skipped on i386/mips) change neither flags nor assertions (the first one only turns
# SIMBODY_VISUALIZER_INSTALL_DIR into a -D argument, given below with upstream's value).
# Upstream's CMakeLists.txt sets, for GCC and Clang, CMAKE_CXX_FLAGS_RELEASE = CMAKE_C_FLAGS_RELEASE =
# "-DNDEBUG -O2" (plus an optional -m<BUILD_INST_SET>, empty by default); this script builds with exactly
# that (-DCMAKE_BUILD_TYPE=Release; CFLAGS/CXXFLAGS from the environment are ignored).
#
# What it does (idempotent; a second run with the install present only says so, unless --force):
#   1. makes sure a deb-src entry exists for Debian's mirror (adds /etc/apt/sources.list.d/mbsopt-deb-src.sources,
#      deb822, same URIs/Suites/Components/Signed-By as debian.sources, only when there is no deb-src yet);
#   2. installs the build dependencies needed for the libraries alone, from the source package's
#      Build-Depends (cmake, liblapack-dev; g++/make/dpkg-dev to compile and unpack). Not `apt-get build-dep`:
#      it would also pull doxygen/doxygen-latex (texlive) and the visualizer's freeglut/Xi/Xmu, ~60 packages;
#   3. `apt-get source simbody` into build/simbody-src/ (skipped when already there);
#   4. configures in build/simbody-build/ (Release, libraries only: no examples, tests, visualizer or docs),
#      builds with -j$(nproc) and installs into build/simbody-release/ (paths relative to the repository root).
#      The config file lands in build/simbody-release/lib/cmake/simbody/SimbodyConfig.cmake.
# Takes ~10 minutes on a 2-core machine (9 min measured for the compile; the download is ~36 MB, the
# source, build and install trees ~200 MB). Needs root, or sudo.
# Usage: bench/build_simbody_release.sh [--force]
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

force=0
for arg in "$@"; do
  case "$arg" in
    --force) force=1 ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "build_simbody_release: unknown argument $arg (only --force)" >&2; exit 2 ;;
  esac
done

src_parent=$root/build/simbody-src
build=$root/build/simbody-build
prefix=$root/build/simbody-release
config_dir=$prefix/lib/cmake/simbody

print_usage() {
  echo "build_simbody_release: Simbody (Release, -O2 -DNDEBUG) is installed in $prefix"
  echo "  use it with:  cmake -S $root -B $root/build/peer-release -DCMAKE_BUILD_TYPE=Release \\"
  echo "                  -DMBSOPT_BUILD_TESTS=OFF -DSimbody_DIR=$config_dir"
  echo "  or:           SIMBODY_RELEASE=1 scripts/peer_comparison.sh"
}

if [ "$force" -eq 0 ] && [ -f "$config_dir/SimbodyConfig.cmake" ] && [ -f "$prefix/lib/libSimTKsimbody.so" ]; then
  echo "build_simbody_release: already installed (--force rebuilds)"
  print_usage
  exit 0
fi

as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
apt_get() { DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get -o DPkg::Lock::Timeout=600 "$@"; }

# 1. deb-src for Debian's mirror (only if none is configured; apt reads *.list and *.sources).
need_update=0
if ! grep -Eqs '^[[:space:]]*(deb-src[[:space:]]|Types:.*deb-src)' \
    /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; then
  echo "build_simbody_release: adding /etc/apt/sources.list.d/mbsopt-deb-src.sources"
  "${as_root[@]}" tee /etc/apt/sources.list.d/mbsopt-deb-src.sources > /dev/null << 'EOF'
# Added by mbsopt's bench/build_simbody_release.sh: Debian's source packages (apt-get source simbody).
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
  need_update=1
fi

# 2. Build dependencies of the libraries (debian/control Build-Depends minus docs and visualizer).
packages=(g++ make cmake liblapack-dev libblas-dev dpkg-dev)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
srcdir=$(find "$src_parent" -mindepth 1 -maxdepth 1 -type d -name 'simbody-*' 2>/dev/null | sort | tail -1 || true)
if [ "$need_update" -eq 1 ] || [ ${#missing[@]} -gt 0 ] || [ -z "$srcdir" ]; then
  "${as_root[@]}" apt-get update -qq
fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "build_simbody_release: installing ${missing[*]}"
  apt_get install -y -qq --no-install-recommends "${missing[@]}"
fi

# 3. Debian's source package (upstream tarball + debian/ with its quilt patches applied by dpkg-source).
if [ -z "$srcdir" ]; then
  mkdir -p "$src_parent"
  echo "build_simbody_release: apt-get source simbody -> $src_parent"
  (cd "$src_parent" && apt-get source -qq simbody)
  srcdir=$(find "$src_parent" -mindepth 1 -maxdepth 1 -type d -name 'simbody-*' | sort | tail -1)
else
  echo "build_simbody_release: source already in $srcdir"
fi
[ -f "$srcdir/CMakeLists.txt" ] || { echo "build_simbody_release: no CMakeLists.txt in $srcdir" >&2; exit 1; }
# Guard: the Release flags this script promises are upstream's; stop if the source says otherwise.
grep -q 'BUILD_CXX_FLAGS_RELEASE' "$srcdir/CMakeLists.txt" && grep -q '"-DNDEBUG -O2 ' "$srcdir/CMakeLists.txt" ||
  { echo "build_simbody_release: $srcdir/CMakeLists.txt no longer sets -DNDEBUG -O2 for Release" >&2; exit 1; }

# 4. Configure, build, install. Environment flags (dpkg-buildflags style CFLAGS/CXXFLAGS) would be
# prepended to every compile line: drop them so the flags are upstream's Release ones only.
unset CFLAGS CXXFLAGS CPPFLAGS LDFLAGS
[ "$force" -eq 0 ] || rm -rf "$build" "$prefix"
start=$SECONDS
# CMAKE_INSTALL_RPATH=$ORIGIN: upstream sets no RPATH on Linux; this lets the installed libraries find
# each other (libSimTKsimbody -> libSimTKmath -> libSimTKcommon) instead of Debian's copies in /usr/lib.
# SIMBODY_VISUALIZER_INSTALL_DIR: Debian's 0001 patch deletes the line computing it (debian/rules passes it),
# and SimbodyConfig.cmake needs it even without the visualizer; this is upstream's value.
cmake -S "$srcdir" -B "$build" \
  -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_INSTALL_PREFIX="$prefix" \
  -DCMAKE_INSTALL_LIBDIR=lib \
  -DCMAKE_INSTALL_RPATH='$ORIGIN' \
  -DSIMBODY_VISUALIZER_INSTALL_DIR="$prefix/libexec/simbody" \
  -DBUILD_DYNAMIC_LIBRARIES=ON \
  -DBUILD_STATIC_LIBRARIES=OFF \
  -DBUILD_EXAMPLES=OFF \
  -DBUILD_TESTING=OFF \
  -DBUILD_VISUALIZER=OFF \
  -DINSTALL_DOCS=OFF
cmake --build "$build" -j"$(nproc)"
cmake --install "$build"
grep -q -- '-DNDEBUG -O2' "$build/CMakeCache.txt" || { echo "build_simbody_release: unexpected flags" >&2; exit 1; }
echo "build_simbody_release: built in $(( (SECONDS - start) / 60 )) min $(( (SECONDS - start) % 60 )) s" \
  "(CMAKE_CXX_FLAGS_RELEASE: $(sed -n "s/^CMAKE_CXX_FLAGS_RELEASE:STRING=//p" "$build/CMakeCache.txt" | tr -d "'" | xargs))"
print_usage
