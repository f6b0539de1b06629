#!/usr/bin/env bash
# SaltDEM scene benchmark: the Expt 1 scene with the SaltDEM styles against the same packing with
# stock gran/hooke/history, on 1 and 2 MPI ranks and 1 and 2 OpenMP threads.  Results in
# out/bench/results.json and results.txt (see docs/performance.md).  Options: --help.
#
#   bash bench/run-bench.sh                         # ~30,000 discs, 1,000 steps per run
#   bash bench/run-bench.sh --nsteps 200 --configs serial
set -euo pipefail
cd "$(dirname "$0")/.."
exec "${SALTDEM_PYTHON:-/usr/bin/python3}" bench/run_bench.py "$@"
