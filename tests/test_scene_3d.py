"""3D scenes: the sphere pack (tools/pack.in -var dim 3) and the paper's Expt 1 extruded along z
into a slab of spheres, periodic in z (examples/expt1.in -var dim 3 -var depth D).  Checked
against the pack's geometry and the fault's closed-form motion, serial against two MPI ranks,
a restart that continues exactly, and 2D-only input refused."""
import os
import re
import sys

import numpy as np
import pytest
from scipy.spatial import cKDTree

from lmprun import ROOT, lmp_path, run_cmd
from test_scenes import dumps, read_dump, run_deck

DEPTH = 1000    # m: the tiny preset's 3D slab (4 of its largest radii)


def run3d(wd, check=True, np_=1, **var):
    var = dict(dict(preset="tiny", dim=3, depth=DEPTH), **var)
    if np_ == 1:
        return run_deck("expt1.in", wd, check=check, **var)
    extra = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    cmd = ["mpirun", *extra, "--oversubscribe", "-np", str(np_), lmp_path(), "-in", str(ROOT / "examples" / "expt1.in"),
           "-log", "log.lammps", "-echo", "none", "-var", "root", str(ROOT)]
    for k, v in var.items():
        cmd += ["-var", k, *str(v).split()]
    proc = run_cmd(cmd, cwd=wd, capture_output=True, text=True, timeout=900,
                   env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    return proc


@pytest.fixture(scope="module")
def slab(tmp_path_factory):
    wd = tmp_path_factory.mktemp("slab3d")
    return wd, run3d(wd)


def pack_deck(wd, check=True, **var):
    cmd = [lmp_path(), "-in", str(ROOT / "tools" / "pack.in"), "-log", "none", "-echo", "none"]
    var = dict(dict(W=1000, H=400, rmin=25, rmax=62.5, seed=5, out="p.data", kn=2.5e9), **var)
    for k, v in var.items():
        cmd += ["-var", k, str(v)]
    proc = run_cmd(cmd, cwd=wd, capture_output=True, text=True, timeout=600,
                   env=dict(os.environ, OMP_NUM_THREADS="1"))
    if check:
        assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    return proc


def read_data_atoms(path):
    lines = path.read_text().splitlines()
    box = {}
    for l in lines[:20]:
        w = l.split()
        if len(w) == 4 and w[2].endswith("lo"):
            box[w[2][0]] = (float(w[0]), float(w[1]))
    k = next(i for i, l in enumerate(lines) if l.startswith("Atoms"))
    rows = []
    for l in lines[k + 2:]:
        if not l.strip():
            break
        rows.append([float(v) for v in l.split()[:7]])
    a = np.array(rows)      # id type diameter density x y z
    return box, a


def test_sphere_pack_fills_the_slab(tmp_path):
    """A 1000 x 400 x 250 m pack of the quick radii: every sphere inside the box, spread over
    the whole periodic depth, dense and without deep overlaps."""
    # kn: the scene's cover stiffness in 3D, 2.5e9 N/m x 87.5 m (examples/scene/spheres.in)
    p = pack_deck(tmp_path, dim=3, D=250, kn=2.1875e11)
    assert "spheres, mean radius" in p.stdout
    box, a = read_data_atoms(tmp_path / "p.data")
    assert box["z"] == pytest.approx((0.0, 250.0)) and box["x"] == pytest.approx((0.0, 1000.0))
    r, x, y, z = a[:, 2] / 2, a[:, 4], a[:, 5], a[:, 6]
    assert np.all((r >= 25 - 1e-9) & (r <= 62.5 + 1e-9))
    assert np.all((y > 0) & (y < 400)) and np.all((z >= 0) & (z < 250))
    # mass of a sphere (density 2200): 4/3 pi r^3 rho
    # spread along z: every quarter of the depth holds at least a sixth of the spheres
    counts = np.histogram(z, bins=4, range=(0, 250))[0]
    assert counts.min() > len(z) / 6
    # dense: sphere volume below the top layer is over half the box volume there (random close
    # packing of spheres is about 0.64)
    below = y < 400 - 2 * 62.5
    vol = (4 / 3 * np.pi * r[below] ** 3).sum()
    frac = vol / (1000 * 250 * (400 - 2 * 62.5))
    assert 0.5 < frac < 0.72, frac
    # settled: overlaps (periodic in x and z) below 2 % of the smaller radius
    pts = np.c_[x, y, z]
    tree = cKDTree(pts, boxsize=[1000, 1e9, 250])
    pairs = tree.query_pairs(2 * 62.5, output_type="ndarray")
    d = np.linalg.norm(((pts[pairs[:, 0]] - pts[pairs[:, 1]]) + [500, 0, 125]) % [1000, 1e9, 250]
                       - [500, 0, 125], axis=1)
    overlap = r[pairs[:, 0]] + r[pairs[:, 1]] - d
    assert overlap.max() < 0.02 * np.minimum(r[pairs[:, 0]], r[pairs[:, 1]]).min()


def test_section_deck_tapers_as_the_example_deck(slab, tmp_path):
    """A section description's deck (python/saltdem-section) takes zends walls and the taper as
    examples/expt1.in does: the same frames, bit for bit."""
    wd, _ = slab
    deck = tmp_path / "expt1_section.in"
    r = run_cmd([sys.executable, str(ROOT / "python" / "saltdem-section"),
                 str(ROOT / "examples" / "sections" / "expt1.toml"), "-o", str(deck)],
                capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    runs = {}
    for name, d in (("deck", "expt1.in"), ("section", deck)):
        (tmp_path / name).mkdir()
        for p in wd.glob("pack_*.data"):
            (tmp_path / name / p.name).write_bytes(p.read_bytes())
        run_deck(d, tmp_path / name, dim=3, depth=DEPTH, preset="tiny", zends="walls",
                 taper_from=0, taper_to=DEPTH)
        runs[name] = {p.name: p.read_bytes() for p in (tmp_path / name).glob("dump.expt1.*.txt")}
    assert len(runs["deck"]) >= 3 and runs["deck"].keys() == runs["section"].keys()
    for k in runs["deck"]:
        assert runs["deck"][k] == runs["section"][k], f"frame {k} differs"


@pytest.mark.parametrize("var,words", [
    (dict(dim=3, D=100), "a 3D pack needs a depth D (m) of at least 4 rmax = 250 m"),
    (dict(dim=4), "pack: dim = 4 must be 2 or 3"),
    (dict(dim=3, D=250, kn=2.1875e11, phiL=0.75), "spheres found room in the starting column; lower phiL"),
    (dict(dim=3, D=250, kn=2.1875e11, phi0=0.3), "below H = 400 m: raise phi0"),
])
def test_bad_pack_is_refused(tmp_path, var, words):
    p = pack_deck(tmp_path, check=False, **var)
    assert p.returncode != 0 and words in p.stdout


def test_3d_slab_runs_to_target(slab):
    wd, proc = slab
    assert "expt1: done, displacement 2.0 m" in proc.stdout
    assert f"scene: 3D slab {DEPTH} m deep along z (periodic), spheres" in proc.stdout
    frames = dumps(wd, "expt1")
    assert len(frames) == 3
    first, last = frames[0], frames[-1]
    assert "z" in first and "vz" in first
    assert (first["type"] == 1).sum() > 50 and (first["type"] == 2).sum() > 20
    # the wall spheres tile the periodic depth: rows at several z, all inside [0, depth)
    wz = np.unique(np.round(first["z"][first["type"] == 3], 6))
    assert len(wz) >= 3 and wz.min() >= 0 and wz.max() < DEPTH
    # the hanging wall moved 2 m down the 30 degree fault, in the section plane only
    w = first["type"] == 3
    dx, dy, dz = (last[c][w] - first[c][w] for c in ("x", "y", "z"))
    moved = np.hypot(dx, dy) > 1.0
    assert moved.sum() > 0 and (~moved).sum() > 0
    np.testing.assert_allclose(dx[moved], 2 * np.cos(np.pi / 6), rtol=1e-6)
    np.testing.assert_allclose(dy[moved], -2 * np.sin(np.pi / 6), rtol=1e-6)
    np.testing.assert_array_equal(dz, 0.0)
    # nothing lost, nothing blown up: every sphere stays inside the slab and moves little
    assert len(last["id"]) == len(first["id"])
    assert np.all(np.isfinite(last["vz"])) and np.abs(last["vz"]).max() < 10 * 2.0    # 2 m/s drive


def test_3d_contact_laws_are_the_2d_ones_per_sphere_diameter(slab):
    """The 2D contact coefficients times zthick = rmin + rmax (350 m at the tiny preset)."""
    wd, proc = slab
    assert "contact laws x 350 m of thickness (cover kn 875000000000 N/m, cohesion " in proc.stdout


WEIGHT = re.compile(r"scene: weight (\w+): spheres of (\d+) kg/m\^3, the slab (\d+) kg/m\^3 in bulk "
                    r"\(the 2D section: (\d+)\)")


def test_3d_slab_weighs_what_the_section_weighs(slab, tmp_path):
    """weight section (the default): each sphere has the density rho x phi_2d / phi_3d (0.878 /
    0.672), so the slab weighs per volume what the 2D section of discs weighs; weight element
    keeps the paper's element density on each sphere, and the same slab weighs 0.77 of that."""
    wd, proc = slab
    m = WEIGHT.search(proc.stdout)
    assert m and m[1] == "section", proc.stdout[-2000:]
    assert int(m[2]) == round(2200 * 0.878 / 0.672) and int(m[4]) == round(2200 * 0.878)
    for p in wd.glob("pack_*.data"):
        (tmp_path / p.name).write_bytes(p.read_bytes())
    e = WEIGHT.search(run3d(tmp_path, weight="element").stdout)
    assert e and e[1] == "element" and int(e[2]) == 2200
    # the masses the slab was given (its bulk: mass over W x H x depth)
    assert int(m[3]) / int(e[3]) == pytest.approx(0.878 / 0.672, rel=2e-3)


def test_3d_two_ranks_match_serial(slab, tmp_path):
    wd, _ = slab
    for p in wd.glob("pack_*.data"):
        (tmp_path / p.name).write_bytes(p.read_bytes())
    proc = run3d(tmp_path, np_=2)
    assert "MPI processor grid" in proc.stdout and "2 by 1 by 1" in proc.stdout
    # atom ids follow the ranks' order of creation (walls) and deletion: match the atoms by
    # where they start
    fa, fb = dumps(wd, "expt1"), dumps(tmp_path, "expt1")
    start = lambda f: np.c_[f["x"], f["y"], f["z"]]
    d, k = cKDTree(start(fb[0])).query(start(fa[0]))
    assert d.max() < 1e-6 * 7000 and len(set(k)) == len(k)
    a = fa[-1]
    b = {c: v[k] for c, v in fb[-1].items()}
    for c in ("x", "y", "z"):
        np.testing.assert_allclose(b[c], a[c], rtol=0, atol=1e-6 * 7000)
    for c in ("vx", "vy", "vz"):
        np.testing.assert_allclose(b[c], a[c], rtol=0, atol=1e-6 * np.abs(a["vx"]).max())


def test_3d_resume_continues_exactly(slab, tmp_path):
    wd, _ = slab
    for p in wd.glob("pack_*.data"):
        (tmp_path / p.name).write_bytes(p.read_bytes())
    run3d(tmp_path, f=1)
    newest = max(tmp_path.glob("expt1.restart.[ab]"), key=lambda p: p.stat().st_mtime)
    proc = run3d(tmp_path, restart=newest.name)
    assert "resumed from" in proc.stdout and "expt1: done, displacement 2.0 m" in proc.stdout
    a, b = dumps(wd, "expt1")[-1], dumps(tmp_path, "expt1")[-1]
    for c in ("x", "y", "z", "vx", "vy", "vz"):
        np.testing.assert_allclose(b[c], a[c], rtol=1e-10, atol=1e-10 * np.abs(a[c]).max())


def test_fault_dying_out_along_strike(slab, tmp_path):
    """zends walls, taper_from 0, taper_to 1000: the slab between smooth end walls, the
    hanging wall's slip whole at z = 0 and none at z = 1000, linear between; the wall
    spheres span the depth inside the walls."""
    wd, _ = slab
    for p in wd.glob("pack_*.data"):
        (tmp_path / p.name).write_bytes(p.read_bytes())
    proc = run3d(tmp_path, zends="walls", taper_from=0, taper_to=DEPTH)
    assert "between smooth end walls" in proc.stdout and "expt1: done, displacement 2.0 m" in proc.stdout
    first, last = (f for f in (dumps(tmp_path, "expt1")[k] for k in (0, -1)))
    w = first["type"] == 3
    z = first["z"][w]
    r = first["radius"][w]
    assert np.all(z - r >= -1e-9) and np.all(z + r <= DEPTH + 1e-9)
    d = np.hypot(last["x"][w] - first["x"][w], last["y"][w] - first["y"][w])
    moved = d > 1e-3
    np.testing.assert_allclose(d[moved], 2.0 * (DEPTH - z[moved]) / DEPTH, atol=1e-5)
    assert len(np.unique(np.round(d[moved], 3))) >= 3
    # every sphere stays between the end walls
    assert np.all(last["z"] - last["radius"] > -0.05 * last["radius"])
    assert np.all(last["z"] + last["radius"] < DEPTH + 0.05 * last["radius"])


@pytest.mark.parametrize("var,words", [
    (dict(dim=2, zends="walls"), "zends and taper_from/taper_to are 3D options"),
    (dict(zends="open"), "scene: zends open must be periodic or walls"),
    (dict(taper_from=0, taper_to=500), "taper in a box periodic in z"),
    (dict(depth=0), "a 3D scene needs -var depth of at least 4 rmax = 1000 m"),
    (dict(dim=4), "scene: dim 4 must be 2 or 3"),
    (dict(dim=2, weight="element"), "scene: weight is a 3D option"),
    (dict(weight="bulk"), "scene: weight bulk must be section or element"),
    (dict(damping=5e4), "frame damping (-var damping) is a 2D option"),
    (dict(sediment="fill"), "requires dimension 2"),
])
def test_2d_only_or_bad_3d_input_is_refused(tmp_path, var, words):
    proc = run3d(tmp_path, check=False, **var)
    assert proc.returncode != 0 and words in proc.stdout, proc.stdout[-2000:]
