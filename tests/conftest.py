"""Shared pytest fixtures: run small decks with the built `lmp` (helpers in lmprun.py)."""
import os
import shutil
import subprocess

import pytest

from lmprun import Run, lmp_path


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
