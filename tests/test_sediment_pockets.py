"""The pocket search and the radius generator of fix saltdem/sediment alone (no LAMMPS): a
small C++ program (tests/unit/sediment_pockets_test.cpp) compiled against the package's
header-only saltdem_sediment_pockets.h and saltdem_sediment_random.h checks the generator's
stream and radius laws, the closed-form pocket of two discs, the window, the foreset, the
rate's area and maxper, and on a random bed that every new disc rests on two discs, below the
level, within the overlap tolerance, whatever order the discs were gathered in."""
import shutil
import subprocess

import pytest

from lmprun import ROOT

PKG = ROOT / "src" / "USER-SALTDEM"


def test_sediment_pockets_alone(tmp_path):
    cxx = shutil.which("g++") or shutil.which("c++")
    if cxx is None:
        pytest.skip("no C++ compiler")
    exe = tmp_path / "sediment_pockets_test"
    build = subprocess.run([cxx, "-std=c++17", "-O2", "-Wall", "-Werror", f"-I{PKG}",
                            str(ROOT / "tests" / "unit" / "sediment_pockets_test.cpp"),
                            "-o", str(exe)],
                           capture_output=True, text=True)
    assert build.returncode == 0, build.stderr[-3000:]
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stdout.strip() == "ok", run.stdout + run.stderr
