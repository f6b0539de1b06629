"""The salt's viscosity in sub-steps (pair_style saltdem/viscous substeps N): the Morris
viscosity applied after the force pass as N explicit steps of dt/N at frozen positions.

The channel flows of test_viscous.py at ten times the paper's step (dt 0.02 s, above the
single-step viscous limit of 0.0092 s, which the style refuses without sub-steps) with four
sub-steps reproduce the analytic Couette and Poiseuille flows and the paper-step runs; MPI and
OpenMP give the serial result; a restart carries the sub-steps and continues exactly."""
import re

import numpy as np
import pytest

from lmprun import check_ok, run_lmp, assert_error
from test_viscous import (CHANNEL, ETA, NSTEPS, PACK, PARAMS, RMAX, Channel, channel,  # noqa: F401
                          max_diff, pack, read_dump)

DT_BIG = 0.02          # s: 10 x the paper's 0.002, 2.2 x the single-step viscous limit
SUB = 4
NBIG = NSTEPS // 10    # the same model time as the paper-step runs


@pytest.fixture(scope="module")
def big(pack, tmp_path_factory):
    cache = {}

    def get(V=0.0, gx=0.0, substeps=SUB, np_=1, omp=1, nsteps=NBIG, newton=False):
        key = (V, gx, substeps, np_, omp, nsteps, newton)
        if key not in cache:
            d = tmp_path_factory.mktemp("sub")
            kw = {}
            if np_ > 1:
                kw["np"] = np_
            if omp > 1:
                kw["omp"] = omp
            deck = CHANNEL.replace("newton          off", "newton          on") if newton else CHANNEL
            assert not newton or "newton          on" in deck
            r = run_lmp(f"include {PARAMS}\n" + deck, d, pack=pack, V=V, gx=gx,
                        dt=DT_BIG, substeps=substeps, nsteps=nsteps, **kw)
            check_ok(r)
            cache[key] = (Channel(r, PACK["H"], V=V, gx=gx), d)
        return cache[key]

    return get


def test_step_needs_the_substeps(pack, tmp_path):
    """Without sub-steps the style refuses dt 0.02 s: the viscous limit binds."""
    r = run_lmp(f"include {PARAMS}\n" + CHANNEL, tmp_path, pack=pack, V=1.0, dt=DT_BIG,
                substeps=1, nsteps=100)
    assert_error(r, "stable limit")
    assert re.search(r"eta = 5e\+08", r.out)


def test_couette_at_ten_times_the_step(big, channel):
    """Couette V 1 m/s: linear, eta_eff within 5 % of eta and within 2 % of the paper-step
    run (the scheme changes the time discretisation only)."""
    c, _ = big(V=1.0)
    ref = channel(V=1.0)
    p, r2 = c.fit(1)
    assert r2 > 0.99, f"Couette profile not linear: R^2 = {r2:.5f}"
    assert c.eta_eff == pytest.approx(ETA, rel=0.05), f"eta_eff = {c.eta_eff:.4g}"
    assert c.eta_eff == pytest.approx(ref.eta_eff, rel=0.02), \
        f"eta_eff {c.eta_eff:.4g} (dt 0.02, {SUB} sub-steps) vs {ref.eta_eff:.4g} (dt 0.002)"


def test_poiseuille_at_ten_times_the_step(big, channel):
    """Poiseuille gx 12 m/s^2: the parabola's maximum matches rho g H^2 / (8 eta) within 5 %
    and the paper-step run within 2 %."""
    g = 12.0
    c, _ = big(gx=g)
    ref = channel(gx=g)

    def vmax(ch):
        p, r2 = ch.fit(2)
        assert r2 > 0.99 and p[0] < 0
        return p, p[2] - p[1] ** 2 / (4 * p[0])

    p, v = vmax(c)
    y0, y1 = sorted(np.roots(p).real)
    pred = c.rhob * g * (y1 - y0) ** 2 / (8 * ETA)
    assert v == pytest.approx(pred, rel=0.05), f"v_max {v:.4g} vs {pred:.4g}"
    _, vref = vmax(ref)
    assert v == pytest.approx(vref, rel=0.02), f"v_max {v:.4g} vs paper step {vref:.4g}, analytic {pred:.4g}"


@pytest.mark.parametrize("mode", ["np2", "omp2"])
def test_substeps_parallel(big, mode):
    """2 MPI ranks (newton off: each rank sums its own atoms' pairs) or 2 OpenMP threads:
    the serial flow within 1e-6."""
    a, _ = big(V=1.0, nsteps=200)
    b, _ = big(V=1.0, nsteps=200, **({"np_": 2} if mode == "np2" else {"omp": 2}))
    assert b.tau == pytest.approx(a.tau, rel=1e-6)
    assert b.rate == pytest.approx(a.rate, rel=1e-6)


def test_substeps_newton_on(big):
    """newton on (the ghosts' sub-step forces go home by reverse communication), 2 ranks:
    the serial flow within 1e-6."""
    a, _ = big(V=1.0, nsteps=200)
    b, _ = big(V=1.0, nsteps=200, np_=2, newton=True)
    assert b.tau == pytest.approx(a.tau, rel=1e-6)
    assert b.rate == pytest.approx(a.rate, rel=1e-6)


RESTART_A = f"include {PARAMS}\n" + CHANNEL.replace(
    "run             $(v_nsteps)\nrun             $(v_nsteps)\n",
    "run 100\nwrite_restart r.restart\nrun 100\n"
    "write_dump all custom final.dump id x y vx vy modify sort id format float %.17g\n")
RESTART_B = """read_restart r.restart
comm_modify vel yes
neighbor 2.8 bin
neigh_modify exclude type 3 3
neigh_modify every 1 delay 0 check yes
fix integ salt saltdem/nve inertia 20
fix drive top move linear 1 0 0 units box
fix 2d all enforce2d
run 100
write_dump all custom final.dump id x y vx vy modify sort id format float %.17g
"""


def test_restart_keeps_the_substeps(pack, tmp_path):
    """A restart file holds the sub-steps: the resumed run (which does not give them again)
    continues as the uninterrupted one (to round-off); saltdem/timestep ... substeps N sets them on a resumed style."""
    a = tmp_path / "a"
    a.mkdir()
    r = run_lmp(RESTART_A, a, pack=pack, V=1.0, dt=DT_BIG, substeps=SUB, nsteps=100)
    check_ok(r)
    b = tmp_path / "b"
    b.mkdir()
    (b / "r.restart").write_bytes((a / "r.restart").read_bytes())
    r2 = run_lmp(RESTART_B.replace("read_restart r.restart\n", "read_restart r.restart\ntimestep 0.02\n"),
                 b)
    check_ok(r2)
    da, db = read_dump(a / "final.dump"), read_dump(b / "final.dump")
    assert len(da) == len(db) > 900
    # (as the plain style's restart test: the resumed run sums in another order)
    assert max_diff(da, db) / PACK["W"] < 1e-10
    assert max_diff(da, db, cols=(2, 3)) < 1e-8
    # the same file resumed with one sub-step: the step is refused, as without the keyword
    c = tmp_path / "c"
    c.mkdir()
    (c / "r.restart").write_bytes((a / "r.restart").read_bytes())
    r3 = run_lmp(RESTART_B.replace("read_restart r.restart\n",
                                   "read_restart r.restart\n"
                                   "saltdem/timestep 0.5 substeps 1\ntimestep 0.02\n"), c)
    assert_error(r3, "stable limit")


def test_timestep_command_sets_substeps(pack, tmp_path):
    """saltdem/timestep F substeps N: the limit it reports is N times the single-step viscous
    limit (while that binds)."""
    deck = f"include {PARAMS}\n" + CHANNEL.replace(
        "timestep        ${dt}\n", "saltdem/timestep 1.0\nsaltdem/timestep 1.0 substeps 2\n").replace(
        "run             $(v_nsteps)\nrun             $(v_nsteps)\n", "run 0\n")
    r = run_lmp(deck, tmp_path, pack=pack, V=1.0, nsteps=100)
    check_ok(r)
    lims = [float(x) for x in re.findall(r"saltdem/timestep: timestep ([0-9.eE+-]+)", r.out)]
    assert len(lims) == 2 and lims[1] == pytest.approx(2 * lims[0], rel=1e-5), lims
    assert "substeps 2" in r.out


def test_bad_substeps(lmp):
    for v in ("0", "-1", "65", "two"):
        r = lmp("units si\ndimension 2\natom_style sphere\nregion b block 0 1 0 1 -0.5 0.5\n"
                f"create_box 1 b\npair_style saltdem/viscous substeps {v}\n")
        assert_error(r, "substeps" if v != "two" else "integer")
