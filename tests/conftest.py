"""Shared pytest fixtures: find the built `lmp` and run small decks with it."""
import os
import pathlib
import re
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent


def lmp_path():
    exe = os.environ.get("SALTDEM_LMP", str(ROOT / "build" / "lmp"))
    if not os.path.isfile(exe):
        pytest.fail(f"no LAMMPS executable at {exe}: build it first (see README) or set SALTDEM_LMP")
    return exe


class Run:
    """Outcome of one lmp invocation: return code, output, thermo tables."""

    def __init__(self, proc, workdir):
        self.rc = proc.returncode
        self.out = proc.stdout + proc.stderr
        self.workdir = workdir

    def thermo(self, index=-1):
        """Thermo table number `index` (one per run command) as {column: [values]}."""
        tables, cols, rows = [], None, None
        for line in self.out.splitlines():
            s = line.split()
            if s and s[0] == "Step":
                cols, rows = s, []
            elif cols is not None and s and re.fullmatch(r"-?\d+", s[0]) and len(s) == len(cols):
                rows.append([float(v) for v in s])
            elif cols is not None and line.startswith("Loop time"):
                tables.append({c: [r[k] for r in rows] for k, c in enumerate(cols)})
                cols = None
        if not tables:
            raise AssertionError("no thermo output in:\n" + self.out[-3000:])
        return tables[index]

    def error(self):
        """The LAMMPS ERROR line, if any."""
        for line in self.out.splitlines():
            if "ERROR" in line:
                return line
        return None


@pytest.fixture
def lmp(tmp_path):
    """lmp(deck_text, np=1, omp=0, **vars) runs a deck in a temporary directory."""

    def run(deck, np=1, omp=0, timeout=600, args=(), **variables):
        deck_file = tmp_path / "in.deck"
        deck_file.write_text(deck)
        cmd = [lmp_path(), "-in", str(deck_file), "-log", "log.lammps", "-echo", "none"]
        for k, v in variables.items():
            cmd += ["-var", k, str(v)]
        if omp:
            cmd += ["-sf", "omp", "-pk", "omp", str(omp)]
        cmd += list(args)
        if np > 1:
            mpirun = shutil.which("mpirun")
            if mpirun is None:
                pytest.fail("mpirun not found: install openmpi-bin (scripts/setup.sh)")
            extra = ["--allow-run-as-root"] if os.geteuid() == 0 else []
            cmd = [mpirun, *extra, "--oversubscribe", "-np", str(np), *cmd]
        env = dict(os.environ, OMP_NUM_THREADS=str(omp or 1))
        proc = subprocess.run(cmd, cwd=tmp_path, capture_output=True, text=True,
                              timeout=timeout, env=env)
        return Run(proc, tmp_path)

    return run
