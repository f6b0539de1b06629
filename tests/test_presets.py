"""Scene presets at the paper's physics: every preset of every scene deck runs a few hundred
steps of faulting (narrower sections at the finer presets, so that CI stays short), takes its
time step from the stable limit, and prints its dimensionless groups beside the paper's; the
study's deck options parse, run, and refuse bad values."""
import re

import pytest

from lmprun import ROOT, lmp_path, run_cmd
from test_scenes import run_deck

# paper, standard rate (Table 1; brief): eta v / (rho g H_salt H_cover), Reynolds number per unit
# inertia factor S rho v H_salt / eta, the cover's inertial number per sqrt(S) at the mean disc
PAPER_VISC = 5e8 * 0.05 / (2200 * 9.81 * 1000 * 1750)
PAPER_RE = 2200 * 0.05 * 1000 / 5e8
SHORT = dict(target=0.05, f=0.05, nsettle=100)
# preset: (S, section width for the finer presets).  The finer presets run a 625 m section (one
# settling strip of the full pack) so that CI stays short; Expt 2's keystone needs a wider
# section and runs at the quick preset only (the presets are shared: scene/params.in)
PRESETS = {"quick": (4, None), "medium": (16, 625), "full": (20, 625)}
CASES = [(p, d) for p in PRESETS for d in ("expt1", "expt2", "expt3") if p == "quick" or d != "expt2"]


@pytest.fixture(scope="module")
def packs(tmp_path_factory):
    """One working directory per preset: Expts 1 and 3 share their pack there."""
    return {p: tmp_path_factory.mktemp(p) for p in PRESETS}


def groups(out):
    """The 'scene groups' block: {name: value} and the time step line's numbers."""
    vals = {}
    for key, pat in [("visc", r"viscous stress / overburden .* ([0-9.eE+-]+) \| 6.6e-4"),
                     ("re", r"Reynolds number with inertia .* ([0-9.eE+-]+) \| 2.2e-4"),
                     ("coh", r"cover strength / overburden .* ([0-9.eE+-]+) \| 0.066"),
                     ("inertial", r"cover inertial number .* ([0-9.eE+-]+) \| 3.8e-6"),
                     ("dt", r"time step ([0-9.eE+-]+) s, drive"),
                     ("dstep", r"drive ([0-9.eE+-]+) m per step")]:
        m = re.search(pat, out)
        assert m, f"no '{key}' in the scene groups:\n{out[-3000:]}"
        vals[key] = float(m.group(1))
    m = re.search(r"saltdem/timestep: timestep ([0-9.eE+-]+) = ([0-9.]+) of the stable limit", out)
    assert m, out[-3000:]
    vals["dt_set"], vals["frac"] = float(m.group(1)), float(m.group(2))
    return vals


@pytest.mark.parametrize("preset,deck", CASES)
def test_preset_runs_at_the_papers_physics(packs, preset, deck):
    S, width = PRESETS[preset]
    extra = dict(width=width) if width else {}
    proc = run_deck(f"{deck}.in", packs[preset], timeout=1200, preset=preset, **SHORT, **extra)
    assert f"{deck}: done, displacement" in proc.stdout
    g = groups(proc.stdout)
    # the paper's salt and drive: the viscous group and the Reynolds number per unit S are the paper's
    assert g["visc"] == pytest.approx(PAPER_VISC, rel=0.01)
    assert g["re"] == pytest.approx(S * PAPER_RE, rel=0.01) and g["re"] < 0.01
    assert g["inertial"] < 1e-3
    assert 0.02 < g["coh"] < 0.1
    # dt: 0.85 of the limit, and the drive of the paper's 0.05 m/s
    assert g["frac"] == 0.85 and g["dt"] == pytest.approx(g["dt_set"], rel=1e-3)
    assert g["dstep"] / g["dt"] == pytest.approx(0.05, rel=1e-3)
    # a few hundred faulting steps at most
    steps = re.search(r"(\d+) steps to 0.05 m", proc.stdout)
    assert steps and 20 < int(steps.group(1)) < 1000


@pytest.mark.parametrize("dim,given,expect", [(2, None, 1.41e6), (3, None, 1.94e6), (3, 3.1e6, 3.1e6)])
def test_quick_cover_cohesion_is_its_dimensions(tmp_path, dim, given, expect):
    """The cover cohesion the groups print is the one measured for the preset's discs or spheres
    (2D biaxial, 3D triaxial tests at the quick radii); -var C_cover still wins."""
    deck = tmp_path / "c.in"
    deck.write_text("include ${root}/examples/scene/params.in\nprint 'C_cover ${C_cover}'\n")
    cmd = [lmp_path(), "-in", str(deck), "-log", "none", "-echo", "none", "-var", "root", str(ROOT),
           "-var", "preset", "quick", "-var", "dim", str(dim), "-var", "depth", "250"]
    if given:
        cmd += ["-var", "C_cover", str(given)]
    proc = run_cmd(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=60)
    m = re.search(r"^C_cover (\S+)$", proc.stdout, re.M)
    assert proc.returncode == 0 and m, (proc.stdout + proc.stderr)[-2000:]
    assert float(m.group(1)) == expect


def test_low_rate_scales_the_viscous_group(tmp_path):
    """Fig. 6's 5x lower rate: the viscous group and Re fall 5x (Table 2: Re 0.000044)."""
    proc = run_deck("expt1.in", tmp_path, preset="quick", rate=0.01, **dict(SHORT, target=0.01, f=0.01))
    g = groups(proc.stdout)
    assert g["visc"] == pytest.approx(PAPER_VISC / 5, rel=0.01)
    assert g["re"] / 4 == pytest.approx(0.000044, rel=0.05)


# the study's variants (docs/scenes.md): each runs on the tiny scene and says so
VARIANTS = [
    (dict(endwall="smooth"), "salt law sph, end walls smooth, frame damping 0 Pa s/m^2 on salt"),
    (dict(endwall="bonded"), "salt law sph, end walls bonded"),
    (dict(rightwall="fixed"), "salt law sph, end walls rough"),
    (dict(saltlaw="contact"), "salt law contact, end walls rough"),
    (dict(damping="5e4"), "frame damping 5e4 Pa s/m^2 on salt"),
    (dict(damping="5e4", damping_group="all"), "frame damping 5e4 Pa s/m^2 on all"),
]


@pytest.mark.parametrize("opts,line", VARIANTS, ids=lambda v: str(v) if isinstance(v, dict) else "")
def test_study_variant_runs(tmp_path, opts, line):
    proc = run_deck("expt1.in", tmp_path, preset="tiny", **opts)
    assert "expt1: done, displacement 2.0 m" in proc.stdout
    assert line in proc.stdout
    # the contact salt has no SPH fluid (no reference density measured)
    assert ("reference density of fluid type" in proc.stdout) == (opts.get("saltlaw") != "contact")


def test_fixed_right_wall_stays(tmp_path):
    from test_scenes import dumps, wall_motion
    run_deck("expt1.in", tmp_path, preset="tiny", rightwall="fixed")
    frames = dumps(tmp_path, "expt1")
    right = wall_motion(frames, lambda x, y: (x > 6300) & (y > 0))
    assert len(right) > 5
    assert abs(right).max() < 1e-9


@pytest.mark.parametrize("opts,words", [
    (dict(endwall="glued"), "endwall glued must be rough, smooth or bonded"),
    (dict(saltlaw="granular"), "saltlaw granular must be sph or contact"),
    (dict(rightwall="away"), "rightwall away must be moving or fixed"),
    (dict(damping_group="cover"), "damping_group cover must be salt or all"),
    (dict(preset="huge"), "preset huge must be full, medium, quick or tiny"),
])
def test_bad_variant_stops(tmp_path, opts, words):
    from lmprun import ROOT, lmp_path, run_cmd
    cmd = [lmp_path(), "-in", str(ROOT / "examples" / "expt1.in"), "-echo", "none", "-var", "root", str(ROOT)]
    opts = dict(dict(preset="tiny"), **opts)
    for k, v in opts.items():
        cmd += ["-var", k, str(v)]
    proc = run_cmd(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert proc.returncode != 0 and words in proc.stdout, proc.stdout[-2000:]
