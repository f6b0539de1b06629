"""Each material its own density in the scene decks (issue 18 item 1): -var rho_salt, rho_cover
and compaction athy reach the discs' masses and the SPH salt's reference density, and the
defaults leave the paper's scene as it was (tiny Expt 1)."""
import math
import os
import re

import numpy as np
import pytest

from lmprun import ROOT, lmp_path, run_cmd


def run_expt1(wd, **var):
    cmd = [lmp_path(), "-in", str(ROOT / "examples" / "expt1.in"), "-log", "log.lammps",
           "-echo", "none", "-screen", "none", "-var", "root", str(ROOT), "-var", "preset", "tiny"]
    for k, v in var.items():
        cmd += ["-var", k, str(v)]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    proc = run_cmd(cmd, cwd=wd, capture_output=True, text=True, timeout=900, env=env)
    log = (wd / "log.lammps").read_text()
    assert proc.returncode == 0, log[-3000:]
    # the discs' masses from the last restart file, as a data file
    proc = run_cmd([lmp_path(), "-restart2data", "expt1.restart.b", "r.data"], cwd=wd,
                          capture_output=True, text=True, timeout=300, env=env)
    assert proc.returncode == 0, proc.stdout[-3000:]
    return log, read_atoms(wd / "r.data")


def read_atoms(path):
    """{id: (type, diameter, density)} of a data file of atom style sphere"""
    lines = path.read_text().splitlines()
    i = next(k for k, l in enumerate(lines) if l.startswith("Atoms"))
    out = {}
    for line in lines[i + 2:]:
        if not line.strip():
            break
        w = line.split()
        out[int(w[0])] = (int(w[1]), float(w[2]), float(w[3]))
    return out


def rho0(log, t=2):
    return float(re.findall(rf"reference density of fluid type {t} = (\S+)", log)[0])


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    out = {}
    for name, var in [("paper", {}),
                      ("light", {"rho_salt": 2160, "rho_cover": 2160}),
                      ("buoyant", {"rho_salt": 2160, "rho_cover": 2500}),
                      ("athy", {"rho_salt": 2160, "rho_cover": 2100, "compaction": "athy"})]:
        wd = tmp_path_factory.mktemp(name)
        out[name] = (wd,) + run_expt1(wd, **var)
    return out


def test_densities_reach_the_masses(runs):
    """every disc's density (mass over its size, as the data file writes it) is its material's:
    salt 2160/2200, cover 2500/2200 of the paper's, walls unchanged"""
    _, _, paper = runs["paper"]
    _, _, buoy = runs["buoyant"]
    assert paper.keys() == buoy.keys()
    want = {1: 2500 / 2200, 2: 2160 / 2200, 3: 1.0}
    for i, (t, d, rho) in paper.items():
        assert buoy[i][0] == t and buoy[i][1] == d
        assert buoy[i][2] / rho == pytest.approx(want[t], rel=1e-12), (i, t)


def test_compaction_follows_athy(runs):
    """compaction athy: cover density rho_grain - (rho_grain - rho_cover) exp(-z/zc), z the depth
    below the cover's top (2750 m) of the disc's centre at assembly (the pack file's position)"""
    wd, log, paper = runs["paper"]
    _, _, athy = runs["athy"]
    pack = pack_positions(next(wd.glob("pack_*.data")))
    for i, (t, d, rho) in paper.items():
        if t != 1:
            continue
        z = max(2750.0 - pack[d], 0.0)
        assert athy[i][2] / rho == pytest.approx(
            (2650 - 550 * math.exp(-z / 2000)) / 2200, rel=1e-9), i
    # the groups use the cover's mean density; the buoyancy group is printed
    _, alog, _ = runs["athy"]
    m = re.search(r"buoyancy / viscous stress .* \| 0 \(drho (\S+) kg/m\^3", alog)
    assert m and 90 < float(m.group(1)) < 160


def pack_positions(path):
    """{diameter: y} of the pack data file (the assembly renumbers the discs when it deletes
    those that cross the end walls; a disc's random diameter identifies it)"""
    lines = path.read_text().splitlines()
    i = next(k for k, l in enumerate(lines) if l.startswith("Atoms"))
    out = {}
    for line in lines[i + 2:]:
        if not line.strip():
            break
        w = line.split()
        out[float(w[2])] = float(w[5])
    return out


def test_reference_density_follows_the_salt(runs):
    """the SPH salt's reference density is a kernel density that counts each partner as salt
    (its size times the salt's material density, PairSaltdemViscous::pair_weights): 2160/2200
    of the paper's whatever the density of the walls (2200) and of the cover beside it (2160 or
    2500).  (With the partners' own masses the walls raised it by 0.2 % and the 2500 cover by
    more: a denser neighbour read as compressed salt.)"""
    p = rho0(runs["paper"][1])
    assert rho0(runs["light"][1]) == pytest.approx(p * 2160 / 2200, rel=1e-9)
    assert rho0(runs["buoyant"][1]) == pytest.approx(p * 2160 / 2200, rel=1e-9)
    assert "contrast" not in runs["paper"][1].split("fix             scale")[-1].split("\n")[0]
    assert re.search(r"buoyancy: density contrast 340 ", runs["buoyant"][1])
