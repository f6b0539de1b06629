#!/usr/bin/env bash
# The README's first command: install what is missing, build lmp with USER-SALTDEM, run the
# quick preset of Experiment 1 at the paper's physics (its rate and salt viscosity) to the
# paper's 1000 m (about 5 min on one core), and render its paper-style figure at the paper's
# stages and its outcomes (what the paper describes at each stage, measured).
#   scripts/quickstart.sh [extra lmp arguments, e.g. -sf omp -pk omp 2]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash scripts/setup.sh
bash scripts/build.sh
out="$root/out/expt1_quick"
mkdir -p "$out"
cd "$out"
echo "quickstart: running examples/expt1.in -var preset quick to 1000 m in $out"
"$root/build/lmp" -in "$root/examples/expt1.in" -var preset quick -var root "$root" \
  -log log.lammps "$@"
py=${SALTDEM_PYTHON:-/usr/bin/python3}
"$py" "$root/python/saltdem-post" figure 'dump.expt1.*.txt' --fault-x 3125 \
  --at 100 250 500 750 1000 --increment 50 -o figures --name expt1_quick.png \
  --title "Expt 1 (quick preset)"
"$py" "$root/python/saltdem-post" outcomes 'dump.expt1.*.txt' --fault-x 3125 --scene fault -o figures
echo "quickstart: figure at $out/figures/expt1_quick.png, outcomes at $out/figures/outcomes.md"
