"""Calibration workflow (python/saltdem-calibrate, examples/calibration/*.in,
potentials/*.params; docs/validation.md).

  fit code     the Mohr-Coulomb fit recovers phi and C from synthetic failure
               states, its standard errors match the scatter of repeated
               noisy fits; the repose-angle and peak measurements recover
               known slopes and peaks
  params       potentials/cover_paper.params and salt_paper.params parse in
               LAMMPS (included into a deck that runs 0 steps with their
               pair coefficients); the radius rule scales cohesion, tensile
               strength and range with rscale_cover; the tool's own params
               writer round-trips
  reduced run  the biaxial preset 'ci' (one pack of ~350 discs, two
               confinements) lands within the band documented in
               docs/validation.md of the full calibration recorded in
               cover_paper.params
  repose 3D    a tiny slab of spheres (repose.in -var dim 3) comes to rest
               at an angle of 15-60 deg; the deck refuses dim 4 and a depth
               below 4 rmax
  long         (pytest -m long) the full calibration: phi = 38 +- 1 deg and
               C = 2.5 +- 0.3 MPa; eta_eff of the paper salt within 5 % over
               two decades of shear rate
"""
import math
import re
import sys

import numpy as np
import pytest

from lmprun import ROOT, check_ok, lmp_path, run_cmd
# python/ is on the module path through pytest.ini (pythonpath = python)
from saltdem_post.calibration import experiments, runner, writers
from saltdem_post.calibration import fit as calibfit

COVER = ROOT / "potentials" / "cover_paper.params"
SALT = ROOT / "potentials" / "salt_paper.params"
TOOL = ROOT / "python" / "saltdem-calibrate"
MPA = 1e6

# docs/validation.md, "Reduced run (CI)": the band of the 'ci' preset around the full calibration
CI_BAND_PHI = 3.0        # degrees
CI_BAND_C = 0.8          # MPa


def measured(path=COVER):
    """The full calibration recorded in the params file: the first '# measured: phi ...' line."""
    m = re.search(r"# measured: phi ([0-9.]+) \+- ([0-9.]+) deg, C ([0-9.]+) \+- ([0-9.]+) MPa", path.read_text())
    assert m, f"no '# measured: phi ...' line in {path}"
    return tuple(float(g) for g in m.groups())


# ---------------------------------------------------------------------------
# the fit code on synthetic data
# ---------------------------------------------------------------------------

def test_mohr_coulomb_exact_line():
    """Failure states on the envelope of phi 38 deg, C 2.5 MPa give them back."""
    s3 = np.array([1, 2, 5, 10]) * MPA
    s1 = calibfit.sigma1_from_mc(s3, 38.0, 2.5 * MPA)
    f = calibfit.mohr_coulomb_fit(s3, s1)
    assert f.phi == pytest.approx(38.0, abs=1e-9)
    assert f.cohesion == pytest.approx(2.5 * MPA, rel=1e-9)
    assert f.friction == pytest.approx(math.tan(math.radians(38.0)))
    assert f.phi_err == pytest.approx(0.0, abs=1e-6) and f.cohesion_err == pytest.approx(0.0, abs=1e-3)
    # two points: the line is exact, the errors unknown
    f2 = calibfit.mohr_coulomb_fit(s3[:2], s1[:2])
    assert f2.phi == pytest.approx(38.0) and math.isnan(f2.phi_err) and math.isnan(f2.cohesion_err)


def test_mohr_coulomb_noisy_errors_match_scatter():
    """4 confinements x 3 samples with 1 MPa noise on sigma1: over 400 draws
    the estimates centre on the truth, their scatter equals the mean reported
    standard error within 15 %, and about 68 % of the 1-sigma intervals hold
    the truth."""
    rng = np.random.default_rng(7)
    s3 = np.repeat([1, 2, 5, 10], 3) * MPA
    true = calibfit.sigma1_from_mc(s3, 38.0, 2.5 * MPA)
    fits = [calibfit.mohr_coulomb_fit(s3, true + rng.normal(0, 1 * MPA, len(s3))) for _ in range(400)]
    phi = np.array([f.phi for f in fits])
    C = np.array([f.cohesion for f in fits])
    ephi = np.array([f.phi_err for f in fits])
    eC = np.array([f.cohesion_err for f in fits])
    assert abs(phi.mean() - 38.0) < 0.2 and abs(C.mean() / MPA - 2.5) < 0.05
    assert phi.std() == pytest.approx(ephi.mean(), rel=0.15)
    assert C.std() == pytest.approx(eC.mean(), rel=0.15)
    cover_phi = np.mean(np.abs(phi - 38.0) < ephi)
    cover_C = np.mean(np.abs(C - 2.5 * MPA) < eC)
    assert 0.58 < cover_phi < 0.78 and 0.58 < cover_C < 0.78, (cover_phi, cover_C)


def test_mohr_coulomb_rejects_bad_input():
    with pytest.raises(ValueError, match="two different confining"):
        calibfit.mohr_coulomb_fit([2e6, 2e6], [10e6, 11e6])
    with pytest.raises(ValueError, match="no positive friction"):
        calibfit.mohr_coulomb_fit([1e6, 5e6], [9e6, 9e6])


def test_find_peak_of_noisy_curve():
    """A smooth hump (peak q 20 MPa at 2 % strain) with stick-slip noise: the
    smoothed peak is within 0.5 MPa (the maximum of a noisy curve lies a
    little above the noise-free one) and 0.2 % strain of the hump's."""
    rng = np.random.default_rng(3)
    ea = np.linspace(0, 0.06, 600)
    q = 20e6 * np.exp(-((ea - 0.02) / 0.012) ** 2) + 5e6 * (ea > 0.02) * (1 - np.exp(-(ea - 0.02) / 0.01))
    q = np.where(ea < 0.02, 20e6 * np.exp(-((ea - 0.02) / 0.012) ** 2), q)
    s3 = 2e6 + rng.normal(0, 2e4, ea.size)
    c = calibfit.BiaxialCurve(np.arange(ea.size), ea, -ea / 3, s3 + q + rng.normal(0, 2e5, ea.size), s3)
    p = calibfit.find_peak(c, window=0.002)
    assert p.reached
    assert abs(p.axial - 0.02) < 0.002
    assert p.q == pytest.approx(20e6, abs=0.5e6)
    assert p.sigma3 == pytest.approx(2e6, rel=0.01)


@pytest.mark.parametrize("angle", [22.0, 31.0, 40.0])
def test_repose_angle_of_synthetic_heap(angle):
    """Discs (radii 6.25-15.625 m) filling a heap with a flat top 300 m high
    and a flank at a known angle: the fitted angle is within 1.5 deg of it."""
    rng = np.random.default_rng(int(angle))
    t = math.tan(math.radians(angle))
    xs, ys, rs = [], [], []
    x = 0.0
    while x < 500 + 300 / t + 200:
        y = 0.0
        surf = 300.0 if x < 500 else max(300.0 - (x - 500) * t, 0.0)
        while True:
            r = rng.uniform(6.25, 15.625)
            if y + 2 * r > surf and y > 0:
                break
            xs.append(x + rng.uniform(-2, 2))
            ys.append(y + r)
            rs.append(r)
            y += 2 * r
            if y + 2 * r > surf:
                break
        x += 18.0
    rep = calibfit.repose_angle(np.array(xs), np.array(ys), np.array(rs))
    assert rep.n_points >= 6
    assert rep.angle == pytest.approx(angle, abs=1.5), rep


# ---------------------------------------------------------------------------
# the parameter files
# ---------------------------------------------------------------------------

PAIR_DECK = """include {params}
units si
dimension 2
atom_style sphere
boundary f f p
comm_modify vel yes
region box block -100 100 -100 100 -0.5 0.5
create_box 1 box
create_atoms 1 single -9.9 0 0
create_atoms 1 single 10.0 0 0
set type 1 diameter 20
set type 1 density/disc 2200
pair_style saltdem/cohesive
pair_coeff 1 1 ${{kn_cover}} ${{kt_cover}} ${{mu_cover}} ${{coh_cover}} ${{ten_cover}} ${{rng_cover}} &
           damp ${{zn_cover}} ${{zt_cover}} rolling ${{kr_cover}} ${{mur_cover}}
neighbor 1.0 bin
fix 1 all saltdem/nve
timestep 0.001
run 0
print "P {names}"
"""


def plain_values(path):
    """{name: value} of the plain 'variable NAME index NUMBER' lines."""
    vals = {}
    for line in path.read_text().splitlines():
        s = line.split("#")[0].split()
        if len(s) == 4 and s[0] == "variable" and s[2] == "index":
            try:
                vals[s[1]] = float(s[3])
            except ValueError:
                pass
    return vals


def run_cover_params(lmp, path, **var):
    names = " ".join(f"{n}=${{{n}}}" for n in experiments.COVER_NAMES)
    r = lmp(PAIR_DECK.format(params=path, names=names), **var)
    check_ok(r)
    line = next(l for l in r.out.splitlines() if l.startswith("P rscale_cover="))
    return {k: float(v) for k, v in (w.split("=") for w in line.split()[1:])}


def test_cover_params_parse_and_scale(lmp):
    """cover_paper.params runs a saltdem/cohesive pair; its plain values come
    through; with rscale_cover 4 (the quick preset's radii) cohesion, tensile
    strength and range are 4x, everything else unchanged; its cohesive range
    exceeds tensile/kn (the attraction can reach its peak)."""
    got = run_cover_params(lmp, COVER)
    plain = plain_values(COVER)
    assert set(experiments.COVER_NAMES) - set(experiments.SCALED) <= set(plain)
    for k, v in plain.items():
        assert got[k] == pytest.approx(v)
    assert got["rng_cover"] > got["ten_cover"] / got["kn_cover"]
    q = run_cover_params(lmp, COVER, rscale_cover=4)
    for k in experiments.COVER_NAMES:
        if k == "rscale_cover":
            assert q[k] == 4
        elif k in experiments.SCALED:
            assert q[k] == pytest.approx(4 * got[k])
        else:
            assert q[k] == pytest.approx(got[k])
    # the time step of the paper (0.002 s) is stable for the cover at the paper's radii
    m_min = 2200 * math.pi * 6.25 ** 2
    assert 0.002 <= 0.2 * math.sqrt(m_min / max(got["kn_cover"], 3 * got["kt_cover"]))


def test_params_together_in_a_scene_deck(lmp):
    """Both params files included into one deck (cover and salt types, hybrid
    pair) run 0 steps: their names do not clash."""
    deck = f"""include {COVER}
include {SALT}
units si
dimension 2
atom_style sphere
boundary f f p
comm_modify vel yes
region box block -200 200 -200 200 -0.5 0.5
create_box 2 box
create_atoms 1 single -30 0 0
create_atoms 1 single -10.2 0 0
create_atoms 2 single 30 0 0
create_atoms 2 single 52 0 0
set group all diameter 20
set group all density/disc ${{rho}}
pair_style hybrid saltdem/cohesive saltdem/viscous
pair_coeff 1 1 saltdem/cohesive ${{kn_cover}} ${{kt_cover}} ${{mu_cover}} ${{coh_cover}} ${{ten_cover}} ${{rng_cover}} &
           damp ${{zn_cover}} ${{zt_cover}} rolling ${{kr_cover}} ${{mur_cover}}
pair_coeff 2 2 saltdem/viscous ${{eta}} ${{kn_salt}} fluid ${{h_salt}} ${{K_salt}}
pair_coeff 1 2 none
neighbor 2.0 bin
group cover type 1
group salt type 2
fix 1 cover saltdem/nve
fix 2 salt saltdem/nve inertia ${{S}}
timestep ${{dt}}
run 0
"""
    check_ok(lmp(deck))


def test_params_writer_round_trips(tmp_path):
    """The tool's params writer: the file it writes for a material gives that
    material back through LAMMPS, at rscale_cover 1 and 4."""
    mat = dict(rscale_cover=1.0, kn_cover=3e9, kt_cover=1e9, mu_cover=0.55, coh_cover=2.5e8, ten_cover=2.0e8,
               rng_cover=0.2, zn_cover=0.3, zt_cover=0.3, kr_cover=3e9, mur_cover=0.17)
    p = tmp_path / "cover_test.params"
    p.write_text(writers.params_text_cover(mat, None, None, None, "test", "pytest"))
    ctx = runner.Context(lmp=lmp_path(), out=tmp_path / "out", quiet=True)
    got = experiments.cover_material(ctx, str(p), {}, 1.0)
    assert got == pytest.approx(mat)
    got4 = experiments.cover_material(ctx, str(p), {"mu_cover": "0.6"}, 4.0)
    for k in experiments.COVER_NAMES:
        want = 4.0 if k == "rscale_cover" else 0.6 if k == "mu_cover" else \
            mat[k] * (4 if k in experiments.SCALED else 1)
        assert got4[k] == pytest.approx(want), k


# ---------------------------------------------------------------------------
# the reduced biaxial run against the full calibration
# ---------------------------------------------------------------------------

def run_tool(out, *args, timeout=900):
    cmd = [sys.executable, str(TOOL), "-q", "-o", str(out), "--lmp", lmp_path(), *args]
    p = run_cmd(cmd, capture_output=True, text=True, timeout=timeout)
    assert p.returncode == 0, p.stdout + p.stderr
    return p


def results(out):
    import json
    return json.loads((out / "results.json").read_text())


def test_reduced_biaxial_within_band(tmp_path):
    """saltdem-calibrate biaxial --preset ci (two packs, sigma3 1 and 10 MPa):
    every peak is inside the test, the confining servo held sigma3 within
    5 %, and phi, C lie within the documented band (CI_BAND_PHI, CI_BAND_C)
    of the full calibration recorded in cover_paper.params.  Writes the
    report with its two plots."""
    out = tmp_path / "cal"
    p = run_tool(out, "biaxial", "--preset", "ci")
    assert "biaxial ci: phi" in p.stdout
    r = results(out)["biaxial"]["ci"]
    for t in r["tests"]:
        assert t["peak"]["reached"], t
        assert t["peak"]["sigma3"] == pytest.approx(t["sigma3_target"], rel=0.05)
        assert t["peak"]["q"] > 0
    phi_full, _, c_full, _ = measured()
    f = r["fit"]
    assert abs(f["phi"] - phi_full) < CI_BAND_PHI, f"phi {f['phi']:.2f} vs full {phi_full}"
    assert abs(f["cohesion"] / MPA - c_full) < CI_BAND_C, f"C {f['cohesion'] / MPA:.3f} vs full {c_full}"
    for png in ("biaxial_ci_curves.png", "biaxial_ci_mohr.png"):
        assert (out / png).stat().st_size > 10000
    assert "Mohr-Coulomb fit of the peaks" in (out / "report.md").read_text()


# ---------------------------------------------------------------------------
# the angle of repose in 3D
# ---------------------------------------------------------------------------

def test_repose_3d_heap_and_refusals(tmp_path):
    """saltdem-calibrate repose --dim 3 (repose.in -var dim 3): a tiny slab of
    spheres (block 400 x 200 m, D 62.5 m = 4 rmax, radii 6.25-15.625 m
    uniform, mu_cover 0.8, mur_cover 0.4, cohesionless) slumps, comes to rest
    and stands at an angle between 15 and 60 deg (measured: 29.3 +- 1.7 deg,
    487 spheres, heap 212 m, at rest after 44000 steps; about 16 s of CPU);
    the dump keeps id x y radius first and adds z inside the period.  The
    deck refuses dim 4 and a depth below 4 rmax with a 'repose: ...' line
    and exit status 1, before it makes a pack."""
    out = tmp_path / "cal"
    p = run_tool(out, "repose", "--dim", "3", "--depth", "62.5", "--size", "400", "200", "--dist", "uniform",
                 "--set", "mu_cover=0.8", "--set", "mur_cover=0.4", timeout=600)
    assert "repose 3D (cohesion x 0," in p.stdout and "at rest" in p.stdout, p.stdout
    r = results(out)["repose"]["c0_3d"]
    assert r["dim"] == 3 and r["depth"] == 62.5 and not r["still_moving"]
    assert r["spheres"] > 300
    assert 15.0 < r["angle"] < 60.0, r["angle"]
    assert r["angle_err"] < 5.0 and r["n_points"] >= 5
    with open(out / r["dir"] / "repose_t.dump") as fh:
        head = [next(fh) for _ in range(9)]
    assert head[8].split()[2:] == ["id", "x", "y", "radius", "z"]
    a = np.loadtxt(out / r["dir"] / "repose_t.dump", skiprows=9)
    assert a.shape == (r["spheres"], 5)
    assert (a[:, 4] >= 0).all() and (a[:, 4] < 62.5).all()
    # the refusals
    deck = ROOT / "examples" / "calibration" / "repose.in"
    for extra, words in ((["-var", "dim", "4"], "repose: dim = 4 must be 2 or 3"),
                         (["-var", "dim", "3", "-var", "D", "60"],
                          "repose: a 3D heap needs a depth D (m) of at least 4 rmax = 62.5 m")):
        d = tmp_path / f"refuse_{'_'.join(extra)}"
        d.mkdir()
        q = run_cmd([lmp_path(), "-in", str(deck), "-echo", "none", "-log", "none", "-var", "root", str(ROOT),
                     *extra], cwd=d, capture_output=True, text=True, timeout=60)
        assert q.returncode == 1, q.stdout + q.stderr
        assert words in q.stdout and "ERROR" not in q.stdout + q.stderr, q.stdout + q.stderr
        assert not list(d.iterdir()), "a refused run must not make a pack"


# ---------------------------------------------------------------------------
# long: the full calibration (pytest -m long)
# ---------------------------------------------------------------------------

@pytest.mark.long
def test_full_calibration_meets_targets(tmp_path):
    """The full biaxial set (3 packs x 4 confinements): phi = 38 +- 1 deg and
    C = 2.5 +- 0.3 MPa, as recorded in cover_paper.params."""
    out = tmp_path / "cal"
    run_tool(out, "-j", "2", "biaxial", "--preset", "full", timeout=3600)
    f = results(out)["biaxial"]["full"]["fit"]
    assert abs(f["phi"] - 38.0) <= 1.0 and abs(f["cohesion"] / MPA - 2.5) <= 0.3, f
    phi_full, _, c_full, _ = measured()
    assert f["phi"] == pytest.approx(phi_full, abs=0.01) and f["cohesion"] / MPA == pytest.approx(c_full, abs=0.001)


@pytest.mark.long
def test_salt_newtonian_over_two_decades(tmp_path):
    """Couette sweep V 0.01-1 m/s (shear rate 2.3e-5 to 2.3e-3 1/s) of the
    paper salt: eta_eff = 5e8 Pa s within 5 % at every rate, power-law index
    within 0.02 of 1, every Re_S < 0.05."""
    out = tmp_path / "cal"
    run_tool(out, "-j", "2", "couette", "--etas", "5e8", timeout=3600)
    c = results(out)["couette"]
    assert c["rate_span"] >= 100
    for r in c["runs"]:
        assert r["eta_eff"] == pytest.approx(5e8, rel=0.05), r
        assert r["reynolds"] < 0.05 and r["r2"] > 0.99
    assert abs(c["newtonian"]["n"] - 1.0) < 0.02
