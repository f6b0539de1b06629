"""Helpers shared by the test modules: find the built `lmp`, run decks, read thermo output."""
import os
import pathlib
import re
import shutil
import subprocess

import pytest

import mpistart
from saltdem_post import checkout

ROOT = pathlib.Path(__file__).resolve().parent.parent


def lmp_path():
    exe = checkout.lmp_path(ROOT)
    if not os.path.isfile(exe):
        pytest.fail(f"no LAMMPS executable at {exe}: build it first (see README) or set SALTDEM_LMP")
    return exe


class Run:
    """Outcome of one lmp invocation: return code, output, thermo tables."""

    def __init__(self, proc, workdir):
        self.rc = proc.returncode
        self.out = proc.stdout + proc.stderr
        self.workdir = pathlib.Path(workdir)

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


def run_lmp(deck, workdir, np=1, omp=0, timeout=600, args=(), **variables):
    """Run a deck text in workdir with -var NAME VALUE for each variable, on np MPI ranks
    and omp OpenMP threads (-sf omp); returns a Run."""
    workdir = pathlib.Path(workdir)
    (workdir / "in.deck").write_text(deck)
    cmd = [lmp_path(), "-in", "in.deck", "-log", "log.lammps", "-echo", "none"]
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
    # passive waiting: threads on a busy 2-core machine otherwise spin
    env = dict(os.environ, OMP_NUM_THREADS=str(omp or 1), OMP_WAIT_POLICY="passive")
    proc = run_cmd(cmd, cwd=workdir, capture_output=True, text=True, timeout=timeout, env=env)
    return Run(proc, workdir)


def run_cmd(cmd, **kwargs):
    """subprocess.run for a command that starts lmp (directly, by mpirun or through a script),
    retried while Open MPI fails to start (mpistart); a failure that persists fails the test as
    an infrastructure failure, never as a result of lmp."""
    proc, tries, failed = mpistart.run(cmd, **kwargs)
    if failed:
        pytest.fail(mpistart.describe(proc, tries), pytrace=False)
    return proc


def check_ok(run):
    assert run.rc == 0, f"lmp failed (rc={run.rc}): {run.error()}\n{run.out[-2000:]}"


def assert_error(r, *words):
    """A clean LAMMPS error (no crash) whose ERROR line holds every word; returns the line."""
    assert r.rc > 0, f"expected a clean error exit, got rc={r.rc}\n{r.out[-1500:]}"
    assert "Segmentation" not in r.out and "signal" not in r.out.lower()
    line = r.error()
    assert line is not None and line.startswith("ERROR"), r.out[-1500:]
    for w in words:
        assert w in line, f"'{w}' not in: {line}"
    return line


def run_unit(name, tmp_path, sources=()):
    """Compile tests/unit/NAME.cpp (with the package's headers and the package SOURCES it
    needs, -Wall -Werror) and run it: it prints "ok" and exits 0, or FAIL lines and exits 1.
    Skips without a C++ compiler."""
    cxx = shutil.which("g++") or shutil.which("c++")
    if cxx is None:
        pytest.skip("no C++ compiler")
    pkg = ROOT / "src" / "USER-SALTDEM"
    exe = tmp_path / name
    build = subprocess.run([cxx, "-std=c++17", "-O2", "-Wall", "-Werror", f"-I{pkg}",
                            str(ROOT / "tests" / "unit" / f"{name}.cpp"),
                            *[str(pkg / s) for s in sources], "-o", str(exe)],
                           capture_output=True, text=True)
    assert build.returncode == 0, build.stderr[-3000:]
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stdout.strip() == "ok", run.stdout + run.stderr
