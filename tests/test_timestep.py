"""saltdem/timestep (dt from the styles' stable limit) and pair saltdem/viscous with every
combination of its laws, alone and under pair hybrid (a deck whose viscous pairs are all
'contact' crashed in the force pass before: the continuity sum had no array)."""
import math
import re

import pytest

from lmprun import assert_error, check_ok


def deck(pair_style, coeffs, step="saltdem/timestep 0.85", nrun=20, fix="saltdem/nve inertia 20"):
    """10 x 10 discs (diameter 19, spacing 20): type 1 salt, type 2 cover, the lowest two rows
    type 3 walls (not integrated)."""
    lines = "\n".join(f"pair_coeff {c}" for c in coeffs)
    return f"""units si
dimension 2
atom_style sphere
boundary p f p
comm_modify vel yes
region box block 0 200 0 200 -0.5 0.5
create_box 3 box
lattice sq 20
create_atoms 1 box
region low block INF INF INF 25 INF INF units box
region high block INF INF 150 INF INF INF units box
set region high type 2
set region low type 3
set group all diameter 19
set group all density/disc 2200
group mobile type 1 2
neighbor 2.8 bin
pair_style {pair_style}
{lines}
neigh_modify exclude type 3 3
velocity mobile create 1e-3 7 loop geom
fix 1 mobile {fix}
fix 2 all enforce2d
{step}
thermo 10
thermo_style custom step dt pe ke
run {nrun}
"""


FLUID = "5e8 1e7 fluid 28 1e8"
CONTACT = "5e8 5e9 contact 0.5"
COH = "saltdem/cohesive 2.5e9 8e8 0.5 1e6 1e6 0.1"
LAWS = {
    "fluid only": ("saltdem/viscous", [f"* * {FLUID}"]),
    "contact only": ("saltdem/viscous", [f"* * {CONTACT}"]),
    "both": ("saltdem/viscous", [f"1 1 {FLUID}", f"2 2 {CONTACT}", f"3 3 {CONTACT}",
                                 f"1 2 {CONTACT}", f"1 3 {CONTACT}"]),
    "hybrid fluid only": ("hybrid saltdem/cohesive saltdem/viscous",
                          [f"2 2 {COH}", f"1 1 saltdem/viscous {FLUID}", f"1 2 saltdem/viscous {FLUID}",
                           f"1 3 saltdem/viscous {FLUID}", f"2 3 {COH}", "3 3 none"]),
    "hybrid contact only": ("hybrid saltdem/cohesive saltdem/viscous",
                            [f"2 2 {COH}", f"1 1 saltdem/viscous {CONTACT}",
                             f"1 2 saltdem/viscous {CONTACT}", f"1 3 saltdem/viscous {CONTACT}",
                             f"2 3 {COH}", "3 3 none"]),
    "hybrid both": ("hybrid saltdem/cohesive saltdem/viscous",
                    [f"2 2 {COH}", f"1 1 saltdem/viscous {FLUID}", f"1 2 saltdem/viscous {CONTACT}",
                     f"1 3 saltdem/viscous {CONTACT}", f"2 3 {COH}", "3 3 none"]),
}


def limits(out):
    """(dt, fraction, limit) of the saltdem/timestep line."""
    m = re.search(r"saltdem/timestep: timestep ([0-9.eE+-]+) = ([0-9.]+) of the stable limit "
                  r"([0-9.eE+-]+)", out)
    assert m, out[-2000:]
    return tuple(float(v) for v in m.groups())


@pytest.mark.parametrize("omp", [0, 2])
@pytest.mark.parametrize("law", list(LAWS))
def test_every_law_combination_runs(lmp, law, omp):
    style, coeffs = LAWS[law]
    r = lmp(deck(style, coeffs), omp=omp)
    check_ok(r)
    dt, frac, lim = limits(r.out)
    assert frac == 0.85 and dt == pytest.approx(0.85 * lim, rel=1e-5)
    t = r.thermo()
    assert t["Step"][-1] == 20 and all(v == pytest.approx(dt, rel=1e-5) for v in t["Dt"])
    assert all(abs(v) < 1e30 for v in t["PotEng"] + t["KinEng"])


def test_limit_is_the_smallest_of_the_hybrid_and_the_check_agrees(lmp):
    """The limit saltdem/timestep takes is the smallest the styles' own run-time check reports,
    and a step just above it is refused by that check."""
    style, coeffs = LAWS["hybrid both"]
    r = lmp(deck(style, coeffs, step="saltdem/timestep 1.0"))
    check_ok(r)
    dt, _, lim = limits(r.out)
    checks = [float(v) for v in re.findall(r"Pair style saltdem/\w+: timestep [0-9.eE+-]+ = [0-9.]+ of "
                                           r"the stable limit ([0-9.eE+-]+)", r.out)]
    assert len(checks) == 2 and min(checks) == pytest.approx(lim, rel=1e-5) and dt == pytest.approx(lim, rel=1e-5)
    r = lmp(deck(style, coeffs, step=f"timestep {lim * 1.01!r}"))
    assert_error(r, "exceeds the stable limit")


def test_limit_follows_the_inertia_factor(lmp):
    """The viscous limit of the fluid grows linearly with the inertia factor S."""
    style, coeffs = LAWS["fluid only"]
    lims = []
    for s in (20, 80):
        r = lmp(deck(style, coeffs, fix=f"saltdem/nve inertia {s}"))
        check_ok(r)
        lims.append(limits(r.out)[2])
    assert lims[1] > lims[0]


@pytest.mark.parametrize("step,words", [
    ("saltdem/timestep", ["usage"]),
    ("saltdem/timestep 0", ["must be in (0, 1]"]),
    ("saltdem/timestep 1.5", ["must be in (0, 1]"]),
    ("saltdem/timestep -0.5", ["must be in (0, 1]"]),
    ("saltdem/timestep nan", ["Expected floating point"]),
    ("saltdem/timestep 0.5 0.5", ["usage"]),
    ("saltdem/timestep abc", ["Expected floating point"]),
])
def test_bad_fraction_is_refused(lmp, step, words):
    style, coeffs = LAWS["both"]
    assert_error(lmp(deck(style, coeffs, step=step)), *words)


def test_needs_a_saltdem_pair_style(lmp):
    r = lmp(deck("gran/hooke 1e5 NULL 0 NULL 0.5 0", [("* *")], step="saltdem/timestep 0.5"))
    assert_error(r, "needs a SaltDEM pair style")


def test_limit_skips_a_pair_that_another_substyle_computes(lmp):
    """pair hybrid: types 1 and 2 are both saltdem/viscous types, but pair 1 2 is given to
    saltdem/cohesive.  The viscous sub-style's limit comes from the pairs it computes (1 1,
    2 2, 1 3), each with the coefficients init_one() derived; before, the limit mixed 1 2 from
    1 1 and 2 2 itself and took that pair's limit (half of 1 1's here: the light type 1 with the
    series viscosity of a 100x more viscous type 2), which no pair of the run has."""
    coeffs = ["1 1 saltdem/viscous 5e8 5e9 contact 0.5", "2 2 saltdem/viscous 5e10 5e9 contact 0.5",
              f"1 2 {COH}", "1 3 saltdem/viscous 5e8 5e9 contact 0.5", f"2 3 {COH}", "3 3 none"]
    step = "set type 2 density/disc 2.2e6\nsaltdem/timestep 0.85"
    r = lmp(deck("hybrid saltdem/cohesive saltdem/viscous", coeffs, step=step, nrun=2))
    check_ok(r)
    m1 = 2200 * math.pi * 9.5 ** 2
    lim = 0.5 * 20 * m1 / (5e8 * (1 + 3 * 1.0))    # viscfactor S m / (calibration eta (1 + 3 ratio))
    dt, _, got = limits(r.out)
    assert got == pytest.approx(lim, rel=1e-5)
    line = [l for l in r.out.splitlines() if l.startswith("Pair style saltdem/viscous: timestep")]
    assert len(line) == 1 and "of types 1 1" in line[0], line


def test_substeps_need_a_viscous_style(lmp):
    """saltdem/timestep ... substeps N sets the sub-steps of saltdem/viscous; with only
    saltdem/cohesive there is none to set, and the command says so."""
    r = lmp(deck("saltdem/cohesive", [f"* * {COH.split(' ', 1)[1]}"],
                 step="saltdem/timestep 0.5 substeps 2"))
    assert_error(r, "substeps 2 given, but no pair style has viscous sub-steps")


def test_substeps_switched_on_between_runs(lmp):
    """A run without sub-steps, then saltdem/timestep ... substeps 2 and a second run: the
    second run has the sub-steps' arrays (it read unallocated ones before) and twice the
    single-step limit."""
    style, coeffs = LAWS["fluid only"]
    text = deck(style, coeffs, step="saltdem/timestep 0.85") + (
        "saltdem/timestep 0.85 substeps 2\nrun 20\n")
    r = lmp(text)
    check_ok(r)
    lims = [float(x) for x in re.findall(r"saltdem/timestep: timestep ([0-9.eE+-]+)", r.out)]
    assert len(lims) == 2 and lims[1] == pytest.approx(2 * lims[0], rel=1e-6)
    ke = [float(l.split()[3]) for l in r.out.splitlines()
          if re.match(r"\s+\d+\s+\S+\s+\S+\s+\S+\s*$", l)]
    assert ke and all(math.isfinite(k) for k in ke)
