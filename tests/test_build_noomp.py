"""The package without the OPENMP package: a second LAMMPS build (cmake -DSALTDEM_OPENMP=OFF,
into build-noomp/, its LAMMPS objects cached beside the main build's under their own key) has
the serial styles and none of the /omp ones, and a small scene (both pair styles under pair
hybrid, fix saltdem/nve, a fault, the salt's density fix) runs in it as in the main build.

The first run compiles LAMMPS once more (minutes; later runs only the package's files).  It
needs the LAMMPS source the main build used: skipped when the main build is not configured or
its source is gone, or with SALTDEM_SKIP_SECOND_BUILD=1 (or -m "not long and not second_build").
"""
import os
import pathlib
import re
import shutil
import subprocess

import pytest

from lmprun import ROOT, check_ok, lmp_path, run_lmp, run_cmd

pytestmark = pytest.mark.second_build

BUILD = ROOT / "build-noomp"


def cache_value(cache, name):
    m = re.search(rf"^{name}:\w+=(.*)$", cache, re.M)
    return m.group(1).strip() if m else ""


@pytest.fixture(scope="module")
def noomp_lmp():
    if os.environ.get("SALTDEM_SKIP_SECOND_BUILD"):
        pytest.skip("SALTDEM_SKIP_SECOND_BUILD is set")
    main = ROOT / "build" / "CMakeCache.txt"
    if not main.exists():
        pytest.skip("the main build is not configured (scripts/build.sh)")
    cache = main.read_text()
    src = cache_value(cache, "LAMMPS_SOURCE_DIR")
    store = cache_value(cache, "SALTDEM_CACHE_DIR")
    # the LAMMPS source: the user's tree, or the one fetch-lammps.sh unpacked into the cache
    have = (pathlib.Path(src) / "src" / "version.h").exists() if src else \
        any(pathlib.Path(store).glob("*/.saltdem-verified"))
    if not have:
        pytest.skip("no LAMMPS source for a second build")
    args = ["cmake", "-S", str(ROOT), "-B", str(BUILD), "-DSALTDEM_OPENMP=OFF",
            f"-DSALTDEM_CACHE_DIR={store}"]
    if src:
        args.append(f"-DLAMMPS_SOURCE_DIR={src}")
    if not (BUILD / "CMakeCache.txt").exists() and shutil.which("ninja"):
        args += ["-G", "Ninja"]
    for cmd in (args, ["cmake", "--build", str(BUILD)]):
        p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=3600)
        assert p.returncode == 0, f"{' '.join(cmd)} failed:\n{(p.stdout + p.stderr)[-4000:]}"
    exe = BUILD / "lmp"
    assert exe.exists()
    return str(exe)


def test_styles_without_openmp(noomp_lmp):
    out = run_cmd([noomp_lmp, "-h"], capture_output=True, text=True).stdout
    assert "USER-SALTDEM" in out and "OPENMP" not in out.split("Installed packages")[1][:400]
    styles = set(re.findall(r"saltdem/[a-z/]+", out))
    assert {"saltdem/cohesive", "saltdem/viscous", "saltdem/nve", "saltdem/fault",
            "saltdem/viscosity", "saltdem/timestep", "saltdem/wall"} <= styles
    assert not [s for s in styles if s.endswith("/omp")], styles
    main = run_cmd([lmp_path(), "-h"], capture_output=True, text=True).stdout
    assert "saltdem/cohesive/omp" in main and "saltdem/nve/omp" in main


SCENE = (ROOT / "tests" / "decks" / "small_scene.in").read_text()



def read(path):
    lines = path.read_text().splitlines()[9:]
    return {int(l.split()[0]): [float(v) for v in l.split()[1:]] for l in lines if l.strip()}


def test_scene_runs_as_in_the_main_build(noomp_lmp, tmp_path, monkeypatch):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    ra = run_lmp(SCENE, a)
    check_ok(ra)
    monkeypatch.setenv("SALTDEM_LMP", noomp_lmp)
    rb = run_lmp(SCENE, b)
    check_ok(rb)
    assert "reference density of fluid type 2" in rb.out
    da, db = read(a / "final.dump"), read(b / "final.dump")
    assert len(da) == len(db) > 200
    diff = max(abs(da[i][k] - db[i][k]) for i in da for k in range(5))
    assert diff < 1e-9, diff
