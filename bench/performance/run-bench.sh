#!/usr/bin/env bash
# SaltDEM scene benchmark: the Expt 1 scene with the SaltDEM styles against the same packing with
# stock gran/hooke/history, on 1 and 2 MPI ranks and 1 and 2 OpenMP threads.  Results in
# out/bench/results.json and results.txt (see docs/performance.md).  Options: --help.
#
#   bash bench/performance/run-bench.sh                         # ~30,000 discs, 1,000 steps per run
#   bash bench/performance/run-bench.sh --nsteps 200 --configs serial
set -euo pipefail
cd "$(dirname "$0")/../.."
# the checkout's saltdem_post (saltdem_post.checkout finds lmp), installed or not
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"
exec "${SALTDEM_PYTHON:-/usr/bin/python3}" bench/performance/run_bench.py "$@"
