#!/usr/bin/env bash
# The test suite: installs what is missing (scripts/setup.sh), builds build/lmp, then runs
# pytest (Debian's python3) over tests/.  Extra arguments go to pytest, e.g. -k viscous.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
py=${SALTDEM_PYTHON:-/usr/bin/python3}
exec "$py" -m pytest -q tests "$@"
