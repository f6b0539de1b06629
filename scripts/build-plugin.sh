#!/usr/bin/env bash
# SaltDEM as a LAMMPS plugin, and a stock lmp to load it into (for tests/test_plugin.py):
#
#   scripts/build-plugin.sh [LAMMPS_SOURCE_DIR]
#
# 1. a stock lmp of the LAMMPS source (default: the tree scripts/fetch-lammps.sh unpacks into the
#    cache) with GRANULAR, OPENMP, MPI and PLUGIN and without USER-SALTDEM, built with the main
#    build's options in the cache ($SALTDEM_CACHE or ~/.cache/saltdem, keyed like it: a second run
#    builds nothing);
# 2. the plugin (plugin/CMakeLists.txt) against that source: build-plugin/saltdemplugin.so.
# The last two lines of stdout: the stock lmp and the plugin.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cache=${SALTDEM_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/saltdem}
src=${1:-}
if [ -z "$src" ]; then src=$(bash "$root/scripts/fetch-lammps.sh" "$cache" | tail -n1); fi
[ -f "$src/src/lammpsplugin.h" ] || { echo "build-plugin: $src is not a LAMMPS source tree" >&2; exit 1; }
cxx=$(command -v "${CXX:-g++}")
gen=()
command -v ninja >/dev/null && gen=(-G Ninja)
opts=(-DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_COMPILER=$cxx" -DBUILD_MPI=ON -DBUILD_OMP=ON
      -DPKG_OPENMP=ON -DPKG_GRANULAR=ON -DPKG_PLUGIN=ON -DPKG_KSPACE=OFF -DFFT=KISS
      -DBUILD_SHARED_LIBS=OFF -DBUILD_TOOLS=OFF -DDOWNLOAD_POTENTIALS=OFF -DWITH_JPEG=OFF
      -DWITH_PNG=OFF -DWITH_FFMPEG=OFF -DWITH_GZIP=ON -DCMAKE_DISABLE_FIND_PACKAGE_FFTW3=ON)
key=$(printf '%s|' "$src" "${opts[@]}" "${gen[@]}" "$("$cxx" --version | head -n1)" v1 | sha256sum | cut -c1-12)
stock="$cache/stock-$key"
if [ ! -x "$stock/lmp" ]; then
  cmake -S "$src/cmake" -B "$stock" "${gen[@]}" "${opts[@]}" > "$stock.configure.log" 2>&1 ||
    { tail -n 30 "$stock.configure.log" >&2; exit 1; }
fi
cmake --build "$stock"
cmake -S "$root/plugin" -B "$root/build-plugin" "${gen[@]}" -DLAMMPS_SOURCE_DIR="$src" \
      -DCMAKE_CXX_COMPILER="$cxx" -DBUILD_MPI=ON
cmake --build "$root/build-plugin"
echo "$stock/lmp"
echo "$root/build-plugin/saltdemplugin.so"
