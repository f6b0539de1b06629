#!/usr/bin/env bash
# The README's first command: install what is missing, build lmp with USER-SALTDEM, and run the
# quick preset of Experiment 1 to the paper's 1000 m twice, side by side (one core each, about
# 10 min on a 2-core machine):
#   stated  the salt the paper states (Newtonian, 5e8 Pa s): -var saltmodel stated
#   paper   the salt whose structures the paper's figures show (a frictional-viscous fluid with
#           the strength the paper's kind of salt has under load): -var saltmodel paper
# Then each run's paper-style figure and outcomes, one side-by-side figure, and per stage what
# the paper says against what each run measured (printed, and written to comparison.md).
#   scripts/quickstart.sh [extra lmp arguments, e.g. -sf omp -pk omp 2]
# SALTMODELS="paper" (or "stated") runs one of the two only.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash scripts/setup.sh
bash scripts/build.sh
out="$root/out/expt1_quick"
py=${SALTDEM_PYTHON:-/usr/bin/python3}
models=${SALTMODELS:-stated paper}
preset=${SALTDEM_QUICKSTART_PRESET:-quick}    # (tiny: a smoke test of this script)
pids=()
for m in $models; do
  case $m in stated|paper) ;; *) echo "quickstart: SALTMODELS '$m' must be stated or paper" >&2; exit 2 ;; esac
  mkdir -p "$out/$m"
  echo "quickstart: running examples/expt1.in -var preset $preset -var saltmodel $m to 1000 m in $out/$m"
  (cd "$out/$m" && OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} "$root/build/lmp" -in "$root/examples/expt1.in" \
     -var preset "$preset" -var saltmodel "$m" -var root "$root" -log log.lammps "$@" > stdout.txt) &
  pids+=($!)
done
fail=0
for p in "${pids[@]}"; do wait "$p" || fail=1; done
[ "$fail" = 0 ] || { echo "quickstart: a run failed: see $out/*/stdout.txt" >&2; exit 1; }
figs=(); outs=()
for m in $models; do
  (cd "$out/$m"
   "$py" "$root/python/saltdem-post" figure 'dump.expt1.*.txt' --fault-x 3125 \
     --at 100 250 500 750 1000 --increment 50 -o figures --name "expt1_quick_$m.png" \
     --title "Expt 1 (quick preset), salt model $m" -q
   "$py" "$root/python/saltdem-post" outcomes 'dump.expt1.*.txt' --fault-x 3125 --scene fault \
     -o figures -q > /dev/null)
  figs+=("$out/$m/figures/expt1_quick_$m.png"); outs+=("$out/$m/figures/outcomes.json")
done
# shellcheck disable=SC2086
"$py" "$root/python/saltdem-post" compare "${outs[@]}" --labels $models --scene expt1 \
  --figures "${figs[@]}" -o "$out"
echo "quickstart: figures $out/*/figures/expt1_quick_*.png, side by side $out/comparison.png," \
  "per stage against the paper $out/comparison.md"
