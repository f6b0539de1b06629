#!/usr/bin/env bash
# Resume the full-preset Expt 1 run of issue 16 from the checkpoint kept in this folder (its
# newest restart file, the frames written so far and the first segments' logs, gzipped): unpack
# them into out/expts_full/expt1/ (files already there are kept) and continue the run with the
# series runner, which resumes from the restart file and, at 1000 m, makes the figure and the
# outcomes table.  MPIRUN (default "mpirun -np 2") chooses the ranks; as root Open MPI also needs
# --allow-run-as-root.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=$root/out/expts_full/expt1
mkdir -p "$out"
for f in "$here"/*.gz; do
  b=$(basename "$f" .gz)
  [ -e "$out/$b" ] || gunzip -c "$f" > "$out/$b"
done
for f in wall_segments.txt cmd.txt; do
  [ -e "$out/$f" ] || cp "$here/$f" "$out/$f"
done
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
exec env ONLY=expt1 MPIRUN="${MPIRUN:-mpirun -np 2}" bash "$root/examples/run-series.sh" expts full
