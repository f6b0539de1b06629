"""Helpers shared by the test modules: find the built `lmp`, run decks, read thermo output."""
import os
import pathlib
import re

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
