"""3D triaxial test of the cover (examples/calibration/biaxial.in -var dim 3): a tiny box of
spheres between six walls of wall spheres consolidates to sigma3 on all four lateral walls and
all platens, then shears with the x and z walls held at sigma3 while q = sigma1 - sigma3 rises;
python/saltdem-calibrate --dim 3 runs it and reads its output; bad input (dim not 2 or 3, a 3D
depth under 4 rmax, a mode other than compression or tension, z walls fixed in 2D) stops with a
message before anything runs, and D means nothing in 2D.  With its z walls fixed the 3D test is a
plane-strain test.  The deck's tension mode (either dimension; tried on
discs, the cheaper sample) pulls a cohesive sample into tension and a cohesionless one not."""
import json
import os
import re
import sys

import numpy as np
import pytest

from lmprun import ROOT, lmp_path, run_cmd
from saltdem_post.calibration.fit import BiaxialCurve, find_peak

DECK = ROOT / "examples" / "calibration" / "biaxial.in"
TOOL = ROOT / "python" / "saltdem-calibrate"
SIGMA3 = 2e6
# a box of 125 x 250 x 125 m of the paper's radii, uniform: ~380 spheres in the pack, ~260 after
# the periodic edges are trimmed; 0.6 % axial strain at 5e-3 1/s (the calibration's strain rate is
# 5e-4: this one checks the machinery, not the material)
TINY = dict(dim=3, W=125, H=250, D=125, rmin=6.25, rmax=15.625, dist="uniform", seed=11,
            sigma3="2e6", erate=5e-3, strain_max=0.006, nout=25, tag="t")
FLOAT = r"([-+0-9.eE]+)"


def run_deck(wd, timeout=300, **var):
    cmd = [lmp_path(), "-in", str(DECK), "-log", "log.lammps", "-echo", "none", "-screen", "none",
           "-var", "root", str(ROOT)]
    for k, v in var.items():
        cmd += ["-var", k, str(v)]
    proc = run_cmd(cmd, cwd=wd, capture_output=True, text=True, timeout=timeout,
                   env=dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive"))
    log = wd / "log.lammps"
    return proc.returncode, (log.read_text(errors="replace") if log.exists() else "") + proc.stdout + proc.stderr


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    wd = tmp_path_factory.mktemp("triaxial3d")
    rc, out = run_deck(wd, **TINY)
    assert rc == 0, out[-3000:]
    return wd, out


def test_sample_is_a_box_of_spheres(tiny):
    wd, out = tiny
    m = re.search(r"biaxial: (\d+) spheres, sample 125 x ([0-9.]+) x 125 m, sigma3 2e6 Pa \(3D triaxial test\)", out)
    assert m, out[-2000:]
    assert 150 <= int(m.group(1)) <= 400
    # the pack the deck made is a 3D one (its own name, periodic in x and z: 3 box dimensions)
    assert (wd / "biaxial_pack3d_125x250x125_6.25_uniform_11.data").exists()
    assert "ERROR" not in out and "WARNING: consolidation" not in out


def test_consolidates_to_sigma3_on_every_wall(tiny):
    """The printed consolidated state: sigma1 (platens), the x walls' and the z walls' stresses
    each within 2 % of sigma3 (the deck's criterion is 1 % on every wall before a last 2000
    steps without the calming drag); the box shrank a little from 125 x 125."""
    _, out = tiny
    m = re.search(rf"biaxial: consolidated after (\d+) steps: sigma1 {FLOAT} sigma3 {FLOAT} \(x {FLOAT}, z {FLOAT}\) "
                  rf"width {FLOAT} depth {FLOAT} height {FLOAT}", out)
    assert m, out[-2000:]
    steps, s1, s3, sx, sz, wid, dep, hgt = (float(g) for g in m.groups())
    assert steps < 200000
    for s in (s1, s3, sx, sz):
        assert s == pytest.approx(SIGMA3, rel=0.02), m.group(0)
    assert 100 < wid < 125 and 100 < dep < 125 and 230 < hgt < 280


def test_shearing_raises_q_at_constant_sigma3(tiny):
    """While the platens compress: q starts near 0, rises above half of sigma3 by 0.6 % strain
    and grows on the whole (its last third above its first); sigma3 (mean of the four lateral
    walls) stays within 5 % of its target at every output; the volumetric strain is that of the
    box (0 at the start, within +-2 axial strains after)."""
    wd, _ = tiny
    path = wd / "biaxial_t.txt"
    head = path.read_text().splitlines()[0]
    assert head.startswith("# triaxial test (3D): sigma3_target 2e6 Pa") and "depth0" in head
    c = BiaxialCurve.read(path)
    assert c.sigma3_target == SIGMA3
    assert len(c.axial) >= 10
    assert c.axial[0] == pytest.approx(0, abs=1e-9) and c.volumetric[0] == pytest.approx(0, abs=1e-9)
    assert c.axial[-1] == pytest.approx(TINY["strain_max"], rel=0.05)
    assert np.all(np.diff(c.axial) > 0)
    q = c.q
    assert abs(q[0]) < 0.02 * SIGMA3
    assert q[-1] > 0.5 * SIGMA3
    n = len(q) // 3
    assert q[-n:].mean() > q[:n].mean() + 0.25 * SIGMA3
    assert np.max(np.abs(c.sigma3 / SIGMA3 - 1)) < 0.05, c.sigma3
    assert np.all(np.abs(c.volumetric[1:]) < 2 * c.axial[1:])
    pk = find_peak(c)
    assert pk.q > 0.5 * SIGMA3 and pk.sigma3 == pytest.approx(SIGMA3, rel=0.05)


@pytest.mark.parametrize("var,words", [
    (dict(dim=4), "biaxial: dim = 4 must be 2 or 3"),
    (dict(dim=1), "biaxial: dim = 1 must be 2 or 3"),
    (dict(dim=3, D=50), "biaxial: a 3D sample needs a depth D (m) of at least 4 rmax = 62.5 m: give -var D"),
])
def test_bad_input_stops_before_running(tmp_path, var, words):
    v = dict(TINY, **var)
    rc, out = run_deck(tmp_path, timeout=60, **v)
    assert rc == 1, out[-2000:]
    assert words in out
    assert "Loop time" not in out and not list(tmp_path.glob("biaxial_*"))


def test_depth_is_ignored_in_2d(tmp_path):
    """dim 2 with a D that 3D would refuse: the 2D biaxial test of discs runs."""
    rc, out = run_deck(tmp_path, dim=2, D=10, W=100, H=200, rmin=6.25, rmax=15.625, dist="uniform",
                       sigma3="2e6", erate=5e-3, strain_max=0.002, nout=20, tag="t")
    assert rc == 0, out[-2000:]
    assert re.search(r"biaxial: \d+ discs, sample 100 x", out)
    assert (tmp_path / "biaxial_t.txt").read_text().startswith("# biaxial test: sigma3_target 2e6 Pa")


@pytest.mark.parametrize("cohesive", [True, False])
def test_tension_mode_pulls_the_sample_apart(tmp_path, cohesive):
    """mode tension: the glued platens move apart and sigma1 falls from sigma3 through zero;
    the paper cover (contact cohesion and tensile strength) carries an axial tension, a
    cohesionless sample (glue and contacts without cohesion) none: it fails in extension as soon
    as sigma1 falls below sigma3 / N; the cohesive one's lateral walls keep confining it."""
    var = dict(dim=2, W=200, H=400, rmin=6.25, rmax=15.625, dist="uniform", seed=11, sigma3="1e6",
               erate=2e-3, strain_max=0.01, nout=200, tag="t", mode="tension")
    if not cohesive:
        var.update(coh_cover=0, ten_cover=0)
    rc, out = run_deck(tmp_path, **var)
    assert rc == 0, out[-2000:]
    c = BiaxialCurve.read(tmp_path / "biaxial_t.txt")
    assert c.axial[-1] == pytest.approx(-0.01, rel=0.1) and np.all(np.diff(c.axial) < 0)
    late = c.axial < -0.001           # past the platens' first, gluing steps
    if cohesive:
        # the walls still confine it (their servo lags behind the necking at this fast rate)
        assert np.all(np.abs(c.sigma3[late] / 1e6 - 1) < 0.35), c.sigma3
        assert c.sigma1[late].min() < -0.3e6, c.sigma1.min()
    else:
        assert c.sigma1[late].min() > -0.05e6, c.sigma1.min()


def test_bad_mode_stops_before_running(tmp_path):
    rc, out = run_deck(tmp_path, timeout=60, **dict(TINY, mode="shear"))
    assert rc == 1 and "biaxial: mode = shear must be compression or tension" in out, out[-2000:]


def test_plane_strain_holds_the_z_walls(tmp_path):
    """zwalls fixed: the z walls stay where the consolidation left them while the platens
    compress, so the sample presses on them: sigma2 (the seventh column) rises with q, where the
    triaxial test keeps it at sigma3; sigma3 is the x walls' stress, kept within 5 %."""
    rc, out = run_deck(tmp_path, **dict(TINY, zwalls="fixed"))
    assert rc == 0, out[-3000:]
    path = tmp_path / "biaxial_t.txt"
    assert path.read_text().startswith("# plane-strain test (3D, z walls fixed): sigma3_target 2e6 Pa")
    a = np.loadtxt(path, comments="#")
    assert a.shape[1] == 7 and len(a) >= 10
    c = BiaxialCurve.read(path)
    q, s2 = c.q, a[:, 6]
    assert np.max(np.abs(c.sigma3 / SIGMA3 - 1)) < 0.05, c.sigma3
    assert q[-1] > 0.5 * SIGMA3
    assert s2[0] == pytest.approx(SIGMA3, rel=0.02)
    assert s2[-1] > s2[0] + 0.05 * q[-1], (s2[0], s2[-1], q[-1])


@pytest.mark.parametrize("var,words", [
    (dict(zwalls="free"), "biaxial: zwalls = free must be servo or fixed"),
    (dict(dim=2, zwalls="fixed"), "biaxial: zwalls is a 3D option: a 2D biaxial test is plane strain already"),
])
def test_bad_zwalls_stops_before_running(tmp_path, var, words):
    rc, out = run_deck(tmp_path, timeout=60, **dict(TINY, **var))
    assert rc == 1 and words in out, out[-2000:]
    assert "Loop time" not in out


def test_calibrate_tool_refuses_plane_strain_in_2d(tmp_path):
    cmd = [sys.executable, str(TOOL), "-q", "-o", str(tmp_path / "cal"), "--lmp", lmp_path(), "biaxial",
           "--preset", "ci", "--plane-strain"]
    p = run_cmd(cmd, capture_output=True, text=True, timeout=60)
    assert p.returncode != 0
    assert "--plane-strain is a 3D option (--dim 3)" in p.stdout + p.stderr


def test_calibrate_tool_runs_3d_sets(tmp_path):
    """saltdem-calibrate biaxial --dim 3: makes a 3D pack (its name says so, settled with the
    stiffness x (rmin + rmax)), passes dim and D to the deck, reads the spheres' count and the
    curves, and fits (two confinements: the line through two points)."""
    out = tmp_path / "cal"
    cmd = [sys.executable, str(TOOL), "-q", "-o", str(out), "--lmp", lmp_path(), "biaxial", "--preset", "ci",
           "--dim", "3", "--size", "100", "200", "--radii", "6.25", "15.625", "--dist", "uniform", "--seeds", "11",
           "--confinements", "1", "2", "--erate", "5e-3", "--strain-max", "0.002", "--label", "t3d"]
    p = run_cmd(cmd, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "biaxial t3d: phi" in p.stdout and "spheres, 3D" in p.stdout
    r = json.loads((out / "results.json").read_text())["biaxial"]["t3d"]
    assert r["sample"]["dim"] == 3 and r["sample"]["D"] == 100
    packs = [f.name for f in (out / "packs").glob("*.data")]
    assert packs == ["pack_3d_100x200x100_r6.25-15.625uniform_kn5.46875e+10_s11.data"], packs
    assert len(r["tests"]) == 2
    for t in r["tests"]:
        assert 60 <= t["discs"] <= 250
        assert t["peak"]["q"] > 0
        assert t["peak"]["sigma3"] == pytest.approx(t["sigma3_target"], rel=0.05)
        cmdline = (out / t["dir"] / "command.sh").read_text()
        assert "-var dim 3 -var D 100" in cmdline
        assert "3D triaxial test" in (out / t["dir"] / "log.lammps").read_text()
    assert "(3D triaxial tests)" in (out / "report.md").read_text()
