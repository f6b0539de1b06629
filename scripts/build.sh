#!/usr/bin/env bash
# Configure and build LAMMPS with USER-SALTDEM into build/lmp (LAMMPS itself is cached outside
# the clone, see README).  Extra arguments go to the cmake configure, e.g.
#   scripts/build.sh -DLAMMPS_SOURCE_DIR=/path/to/lammps
set -euo pipefail
cd "$(dirname "$0")/.."
gen=()
if [ ! -f build/CMakeCache.txt ] && command -v ninja >/dev/null; then gen=(-G Ninja); fi
cmake -S . -B build "${gen[@]}" "$@"
cmake --build build
# grep -c reads all of the output: grep -q would stop early and lmp die of SIGPIPE (pipefail)
build/lmp -h | grep -c "USER-SALTDEM" > /dev/null || { echo "build: lmp lacks USER-SALTDEM" >&2; exit 1; }
echo "build: $(pwd)/build/lmp"
