#!/usr/bin/env bash
# The README's first command: install what is missing, build lmp with USER-SALTDEM, run the
# quick preset of Experiment 1 at the paper's physics (its rate and salt viscosity), stopped at
# 250 m of the paper's 1000 m to stay within a few minutes, and render its paper-style figure.
# The whole run: build/lmp -in examples/expt1.in -var preset quick (about 12 min on one core).
#   scripts/quickstart.sh [extra lmp arguments, e.g. -sf omp -pk omp 2]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash scripts/setup.sh
bash scripts/build.sh
out="$root/out/expt1_quick"
mkdir -p "$out"
cd "$out"
echo "quickstart: running examples/expt1.in -var preset quick to 250 m in $out"
"$root/build/lmp" -in "$root/examples/expt1.in" -var preset quick -var target 250 \
  -var f 50 100 200 250 -var root "$root" -log log.lammps "$@"
py=${SALTDEM_PYTHON:-/usr/bin/python3}
"$py" "$root/python/saltdem-post" figure 'dump.expt1.*.txt' --fault-x 3125 --at 100 250 \
  --increment 50 -o figures --name expt1_quick.png --title "Expt 1 (quick preset)"
echo "quickstart: figure at $out/figures/expt1_quick.png"
