"""SaltDEM::SphFields, the SPH field passes of pair saltdem/viscous, alone (no LAMMPS): a small
C++ program (tests/unit/sph_fields_test.cpp) compiled against the package's
saltdem_sph_fields.cpp checks the kernel density of a square lattice against the lattice sum
and its continuum value m / a^2, the full-kernel flag, and the Bonet-Lok corrected pressure
matrix (S A = a rho I)."""
import shutil
import subprocess

import pytest

from lmprun import ROOT

PKG = ROOT / "src" / "USER-SALTDEM"


def test_sph_fields_on_a_lattice(tmp_path):
    cxx = shutil.which("g++") or shutil.which("c++")
    if cxx is None:
        pytest.skip("no C++ compiler")
    exe = tmp_path / "sph_fields_test"
    build = subprocess.run([cxx, "-std=c++17", "-O2", "-Wall", "-Werror", f"-I{PKG}",
                            str(ROOT / "tests" / "unit" / "sph_fields_test.cpp"),
                            str(PKG / "saltdem_sph_fields.cpp"), "-o", str(exe)],
                           capture_output=True, text=True)
    assert build.returncode == 0, build.stderr[-3000:]
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stdout.strip() == "ok", run.stdout + run.stderr
