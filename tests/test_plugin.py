"""SaltDEM as a LAMMPS plugin (plugin/CMakeLists.txt): scripts/build-plugin.sh builds a stock lmp
of the same LAMMPS source (GRANULAR, OPENMP, MPI, PLUGIN, without USER-SALTDEM; in the cache, like
the main build) and the plugin against that source.  The stock lmp loads the plugin with
'plugin load', has every style of the package, and runs a scene deck bit for bit as the main
build with the package built in (serial, and with the /omp variants on 2 threads).

The first run compiles LAMMPS once more (minutes).  Skipped with SALTDEM_SKIP_SECOND_BUILD=1 (or
-m "not long and not second_build"), or when the LAMMPS source cannot be had.
"""
import os
import re
import subprocess

import pytest

from lmprun import ROOT, check_ok, run_lmp, run_cmd

pytestmark = pytest.mark.second_build

SCENE = (ROOT / "tests" / "decks" / "small_scene.in").read_text()


@pytest.fixture(scope="module")
def plugin():
    if os.environ.get("SALTDEM_SKIP_SECOND_BUILD"):
        pytest.skip("SALTDEM_SKIP_SECOND_BUILD is set")
    p = subprocess.run(["bash", str(ROOT / "scripts" / "build-plugin.sh")], cwd=ROOT,
                       capture_output=True, text=True, timeout=4 * 3600)
    if p.returncode != 0 and "fetch-lammps: ERROR" in p.stderr:
        pytest.skip("no LAMMPS source: " + p.stderr.strip().splitlines()[-1])
    assert p.returncode == 0, (p.stdout + p.stderr)[-4000:]
    lmp, so = p.stdout.strip().splitlines()[-2:]
    assert os.access(lmp, os.X_OK) and os.path.exists(so), (lmp, so)
    return lmp, so


def read(path):
    return path.read_text().splitlines()[9:]


def test_stock_lmp_has_no_saltdem(plugin):
    lmp, so = plugin
    out = run_cmd([lmp, "-h"], capture_output=True, text=True).stdout
    packages = out.split("Installed packages:")[1].split("List of individual style options")[0]
    assert {"PLUGIN", "OPENMP", "GRANULAR"} <= set(packages.split())
    styles = out.split("List of individual style options")[1]
    assert "USER-SALTDEM" not in packages and "saltdem/" not in styles


def test_plugin_registers_every_style(plugin, tmp_path):
    lmp, so = plugin
    (tmp_path / "in.list").write_text(f"plugin load {so}\nplugin list\n")
    p = run_cmd([lmp, "-in", "in.list", "-log", "none"], capture_output=True, text=True,
                       cwd=tmp_path)
    assert p.returncode == 0, p.stdout[-2000:]
    listed = set(re.findall(r"(pair|fix|command) style plugin (\S+)", p.stdout))
    want = {("pair", "saltdem/cohesive"), ("pair", "saltdem/viscous"),
            ("pair", "saltdem/cohesive/omp"), ("pair", "saltdem/viscous/omp"),
            ("fix", "saltdem/nve"), ("fix", "saltdem/nve/omp"), ("fix", "saltdem/fault"),
            ("fix", "saltdem/keystone"), ("fix", "saltdem/tiltwall"),
            ("fix", "saltdem/viscosity"), ("fix", "SALTDEM_DENSITY"), ("fix", "SALTDEM_REBUILD"),
            ("command", "saltdem/timestep"), ("command", "saltdem/wall")}
    # every style macro of the package's headers is registered (the registration is generated)
    macros = set()
    for h in (ROOT / "src" / "USER-SALTDEM").glob("*.h"):
        for kind, name in re.findall(r"^(Pair|Fix|Command)Style\((\S+?),", h.read_text(), re.M):
            macros.add((kind.lower(), name))
    assert want <= macros and macros == listed, (macros ^ listed)
    assert want <= listed, (want - listed, p.stdout[-2000:])
    assert "WARNING" not in p.stdout and "ERROR" not in p.stdout


@pytest.mark.parametrize("omp", [0, 2])
def test_scene_bit_for_bit_as_built_in(plugin, tmp_path, monkeypatch, omp):
    lmp, so = plugin
    a, b = tmp_path / "builtin", tmp_path / "plugin"
    a.mkdir()
    b.mkdir()
    ra = run_lmp(SCENE, a, omp=omp)
    check_ok(ra)
    monkeypatch.setenv("SALTDEM_LMP", lmp)
    rb = run_lmp(f"plugin load {so}\n" + SCENE, b, omp=omp)
    check_ok(rb)
    assert "Loading plugin: SaltDEM" in rb.out or "saltdem" in rb.out.lower()
    if omp:    # the plugin's /omp variants run
        assert "Last active /omp style is pair_style saltdem/viscous" in rb.out
    da, db = read(a / "final.dump"), read(b / "final.dump")
    assert len(da) > 200
    assert da == db
