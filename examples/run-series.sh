#!/usr/bin/env bash
# Run a series of the paper's scenes, each in its own directory, and render its figure.
#
#   examples/run-series.sh SERIES [PRESET] [-- extra lmp arguments, e.g. -sf omp -pk omp 4]
#
#   expts   Expts 1-3 at the standard rate (paper Figs. 3-5)
#   fig6    Expts 1-3 at the 5x lower rate (paper Fig. 6): 0.00002 m per 0.002 s step
#   fig7    Expt 1 geometry with a 65 degree fault and salt 1000, 500, 250 m (paper Fig. 7;
#           the cover keeps its 1750 m)
# PRESET: full (default: the paper's resolution, days of CPU per run), quick (minutes), tiny.
# Output: out/SERIES_PRESET/NAME/ with the frames, log and figures/NAME.png.
# LMP (default build/lmp) and MPIRUN (e.g. "mpirun -np 8") choose how lmp runs.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
series=${1:?usage: examples/run-series.sh expts|fig6|fig7 [full|quick|tiny] [-- lmp args]}
preset=${2:-full}
shift $(( $# >= 2 ? 2 : 1 ))
[ "${1:-}" = "--" ] && shift
lmp=${LMP:-$root/build/lmp}
py=${SALTDEM_PYTHON:-/usr/bin/python3}

# the low rate of Fig. 6 is 1/5 of the preset's standard displacement per step
case $preset in
  full) dstep=0.0001 ;; quick) dstep=0.00125 ;; tiny) dstep=0.01 ;;
  *) echo "run-series: preset '$preset' must be full, quick or tiny" >&2; exit 2 ;;
esac
slow=$(awk "BEGIN{print $dstep/5}")

runs=()
case $series in
  expts) runs=("expt1 expt1" "expt2 expt2" "expt3 expt3") ;;
  fig6)  runs=("expt1_slow expt1 -var dstep $slow" "expt2_slow expt2 -var dstep $slow"
               "expt3_slow expt3 -var dstep $slow") ;;
  fig7)  runs=("fig7_salt1000 expt1 -var dip 65 -var salt 1000"
               "fig7_salt500 expt1 -var dip 65 -var salt 500"
               "fig7_salt250 expt1 -var dip 65 -var salt 250") ;;
  *) echo "run-series: series '$series' must be expts, fig6 or fig7" >&2; exit 2 ;;
esac

for r in "${runs[@]}"; do
  read -r name deck vars <<< "$r"
  out="$root/out/${series}_${preset}/$name"
  mkdir -p "$out"
  echo "run-series: $name ($deck.in $vars) in $out"
  # shellcheck disable=SC2086
  (cd "$out" && ${MPIRUN:-} "$lmp" -in "$root/examples/$deck.in" -var root "$root" \
      -var preset "$preset" $vars -log log.lammps "$@" > stdout.txt)
  dstep_run=$(grep -o 'dstep [0-9.e-]*' <<< "$vars" | awk '{print $2}' || true)
  "$py" "$root/python/saltdem-post" figure "$out/dump.$deck.*.txt" -o "$out/figures" \
      --name "$name.png" --title "$name ($preset)" --disp-per-step "${dstep_run:-$dstep}" -q \
      $( [ "$preset" = full ] || echo --at $(grep -o 'frame at displacement [0-9.]*' "$out/stdout.txt" | awk '{printf "%s ", $4}') )
  echo "run-series: figure $out/figures/$name.png"
done
