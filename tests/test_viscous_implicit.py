"""The salt's viscosity in an implicit step (pair_style saltdem/viscous implicit yes): the
Morris viscosity applied after the force pass as one backward-Euler step at frozen positions,
solved by preconditioned conjugate gradients.

The channel flows of test_viscous.py at 5 and 10 times the single-step viscous limit (0.0092 s
at the paper's salt) reproduce the analytic Couette and Poiseuille flows within 5 % and the
explicit runs at the paper's step within 2 %.  The salt-wall stiffness is 8e8 N/m here (5e9 in
the paper's file), so that the wall contact's own limit (0.096 s) lies above 10 times the
viscous one; the explicit reference runs use the same stiffness.  MPI, newton on and OpenMP give
the serial result; a restart carries the setting and continues exactly; a solve that does not
converge stops the run."""
import math
import re

import pytest

from lmprun import assert_error, check_ok, run_lmp
from test_viscous import (CHANNEL, ETA, NSTEPS, PACK, PARAMS, Channel, max_diff, pack,  # noqa: F401
                          read_dump)
from test_viscous_substeps import RESTART_A, RESTART_B    # the channel written and resumed

VISC_LIMIT = 0.0092    # s: the explicit viscous limit of the paper's salt in the channel
KNW = 8e8              # N/m: the salt-wall contact, its limit 0.096 s
MODEL_TIME = NSTEPS * 0.002


def run_channel(pack, d, dt, implicit=True, V=0.0, gx=0.0, np_=1, omp=1, newton=False,
                nsteps=None, popts="", deck=None):
    # (a multiple of 200: the deck averages over nsteps / 20 samples every 10 steps)
    nsteps = nsteps or 200 * math.ceil(MODEL_TIME / dt / 200)
    kw = {}
    if np_ > 1:
        kw["np"] = np_
    if omp > 1:
        kw["omp"] = omp
    text = deck or CHANNEL
    if newton:
        text = text.replace("newton          off", "newton          on")
    opts = ("implicit yes " if implicit else "") + popts
    return run_lmp(f"include {PARAMS}\n" + text, d, pack=pack, V=V, gx=gx, dt=dt, knw=KNW,
                   popts=opts, nsteps=nsteps, **kw)


@pytest.fixture(scope="module")
def flows(pack, tmp_path_factory):
    cache = {}

    def get(dt, implicit=True, V=0.0, gx=0.0, **kw):
        key = (dt, implicit, V, gx, tuple(sorted(kw.items())))
        if key not in cache:
            d = tmp_path_factory.mktemp("imp")
            r = run_channel(pack, d, dt, implicit=implicit, V=V, gx=gx, **kw)
            check_ok(r)
            cache[key] = Channel(r, PACK["H"], V=V, gx=gx)
        return cache[key]

    return get


def test_explicit_step_is_refused(pack, tmp_path):
    """Without the implicit step, 5 times the viscous limit is refused: the viscous limit
    binds (the wall contact's does not)."""
    r = run_channel(pack, tmp_path, 5 * VISC_LIMIT, implicit=False, V=1.0, nsteps=200)
    assert_error(r, "stable limit")
    assert re.search(r"eta = 5e\+08", r.out)


@pytest.mark.parametrize("factor", [5, 10])
def test_couette_beyond_the_limit(flows, factor):
    """Couette V 1 m/s: linear, eta_eff within 5 % of eta and within 2 % of the explicit run
    at the paper's step; the iterations are reported."""
    c = flows(factor * VISC_LIMIT, V=1.0)
    ref = flows(0.002, implicit=False, V=1.0)
    p, r2 = c.fit(1)
    assert r2 > 0.99, f"Couette profile not linear: R^2 = {r2:.5f}"
    assert c.eta_eff == pytest.approx(ETA, rel=0.05), f"eta_eff = {c.eta_eff:.4g}"
    assert c.eta_eff == pytest.approx(ref.eta_eff, rel=0.02), \
        f"eta_eff {c.eta_eff:.4g} (dt {factor} x limit) vs {ref.eta_eff:.4g} (dt 0.002)"
    its = [float(x) for x in re.findall(r"implicit viscous step: ([0-9.]+) iterations", c.run.out)]
    assert len(its) == 2 and all(0 < n < 200 for n in its), its


@pytest.mark.parametrize("factor", [5, 10])
def test_poiseuille_beyond_the_limit(flows, factor):
    """Poiseuille gx 12 m/s^2: v_max within 5 % of rho g H^2 / (8 eta) and within 2 % of the
    explicit run at the paper's step."""
    import numpy as np
    g = 12.0
    c = flows(factor * VISC_LIMIT, gx=g)
    ref = flows(0.002, implicit=False, gx=g)

    def vmax(ch):
        p, r2 = ch.fit(2)
        assert r2 > 0.99 and p[0] < 0
        return p, p[2] - p[1] ** 2 / (4 * p[0])

    p, v = vmax(c)
    y0, y1 = sorted(np.roots(p).real)
    pred = c.rhob * g * (y1 - y0) ** 2 / (8 * ETA)
    assert v == pytest.approx(pred, rel=0.05), f"v_max {v:.4g} vs {pred:.4g}"
    _, vref = vmax(ref)
    assert v == pytest.approx(vref, rel=0.02), f"v_max {v:.4g} vs explicit {vref:.4g}"


@pytest.mark.parametrize("mode", ["np2", "omp2", "newton"])
def test_implicit_parallel(flows, mode):
    """2 MPI ranks (newton off or on: the ghosts' parts of each product go home) or 2 OpenMP
    threads: the serial flow within 1e-6."""
    dt = 10 * VISC_LIMIT
    a = flows(dt, V=1.0, nsteps=200)
    kw = {"np2": {"np_": 2}, "omp2": {"omp": 2}, "newton": {"np_": 2, "newton": True}}[mode]
    b = flows(dt, V=1.0, nsteps=200, **kw)
    assert b.tau == pytest.approx(a.tau, rel=1e-6)
    assert b.rate == pytest.approx(a.rate, rel=1e-6)


def test_restart_keeps_the_implicit_step(pack, tmp_path):
    """A restart file holds implicit yes, the tolerance and maxiter: the resumed run (which
    does not give them again) continues as the uninterrupted one."""
    dt = 10 * VISC_LIMIT
    a = tmp_path / "a"
    a.mkdir()
    r = run_lmp(RESTART_A, a, pack=pack, V=1.0, dt=dt, knw=KNW,
                popts="implicit yes tolerance 1e-6 maxiter 150", nsteps=100)
    check_ok(r)
    b = tmp_path / "b"
    b.mkdir()
    (b / "r.restart").write_bytes((a / "r.restart").read_bytes())
    r2 = run_lmp(RESTART_B.replace("read_restart r.restart\n", f"read_restart r.restart\ntimestep {dt}\n"), b)
    check_ok(r2)
    assert "implicit step (tolerance 1e-06, maxiter 150)" in r2.out
    da, db = read_dump(a / "final.dump"), read_dump(b / "final.dump")
    assert len(da) == len(db) > 900
    assert max_diff(da, db) / PACK["W"] < 1e-10
    assert max_diff(da, db, cols=(2, 3)) < 1e-8


def test_no_convergence_stops_the_run(pack, tmp_path):
    """A solve that does not reach its tolerance in maxiter iterations stops the run and
    names the residual and what to change."""
    r = run_channel(pack, tmp_path, 10 * VISC_LIMIT, V=1.0, nsteps=200,
                    popts="tolerance 1e-12 maxiter 2")
    assert_error(r, "did not converge")
    assert re.search(r"residual [0-9.e+-]+ of the start's after maxiter 2", r.out)
    assert "Raise maxiter or tolerance" in r.out


def test_implicit_and_substeps_exclude_each_other(lmp):
    head = ("units si\ndimension 2\natom_style sphere\nregion b block 0 1 0 1 -0.5 0.5\n"
            "create_box 1 b\n")
    assert_error(lmp(head + "pair_style saltdem/viscous implicit yes substeps 4\n"),
                 "choose one")


@pytest.mark.parametrize("opts,msg", [("implicit maybe", "implicit"),
                                      ("tolerance 0", "tolerance"),
                                      ("tolerance 1.5", "tolerance"),
                                      ("maxiter 0", "maxiter"),
                                      ("maxiter many", "integer")])
def test_bad_implicit_settings(lmp, opts, msg):
    r = lmp("units si\ndimension 2\natom_style sphere\nregion b block 0 1 0 1 -0.5 0.5\n"
            f"create_box 1 b\npair_style saltdem/viscous {opts}\n")
    assert_error(r, msg)


def test_timestep_command_sets_implicit(pack, tmp_path):
    """saltdem/timestep F implicit yes: the viscous limit no longer binds, the next one (the
    salt-wall core) does; implicit no brings the viscous limit back."""
    deck = f"include {PARAMS}\n" + CHANNEL.replace(
        "timestep        ${dt}\n",
        "saltdem/timestep 1.0\nsaltdem/timestep 1.0 implicit yes\nsaltdem/timestep 1.0 implicit no\n"
    ).replace("run             $(v_nsteps)\nrun             $(v_nsteps)\n", "run 0\n")
    r = run_lmp(deck, tmp_path, pack=pack, V=1.0, knw=KNW, nsteps=200)
    check_ok(r)
    lines = re.findall(r"saltdem/timestep: timestep ([0-9.eE+-]+) = .*?\((eta|kn) = ", r.out)
    assert [w for _, w in lines] == ["eta", "kn", "eta"], lines
    assert float(lines[1][0]) > 5 * float(lines[0][0])


def test_timestep_command_sets_the_tolerance(pack, tmp_path):
    """saltdem/timestep F implicit yes tolerance T maxiter N sets the solver of a style made
    (or read from a restart file) without them: the run reports them and stops at the new
    maxiter; tolerance without implicit yes is refused."""
    deck = f"include {PARAMS}\n" + CHANNEL.replace(
        "timestep        ${dt}\n",
        "timestep        ${dt}\nsaltdem/timestep 0.9 implicit yes tolerance 1e-12 maxiter 3\n")
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    r = run_channel(pack, tmp_path / "a", 10 * VISC_LIMIT, implicit=False, V=1.0, nsteps=200,
                    deck=deck[deck.index("#"):])
    assert "implicit step (tolerance 1e-12, maxiter 3)" in r.out
    assert_error(r, "did not converge")
    assert re.search(r"after maxiter 3", r.out)
    bad = f"include {PARAMS}\n" + CHANNEL.replace(
        "timestep        ${dt}\n", "timestep        ${dt}\nsaltdem/timestep 0.9 tolerance 1e-3\n")
    r = run_lmp(bad, tmp_path / "b", pack=pack, V=1.0, knw=KNW, nsteps=200)
    assert_error(r, "tolerance and maxiter are options of implicit yes")


def test_compute_pair_reports_iterations(pack, tmp_path):
    """compute pair saltdem/viscous gives the iterations of the last step, their mean and the
    last residual (below the tolerance)."""
    deck = f"include {PARAMS}\n" + CHANNEL.replace(
        "thermo_style    custom step time c_kes v_tau",
        "compute imp all pair saltdem/viscous\n"
        "thermo_style    custom step time c_kes v_tau c_imp[1] c_imp[2] c_imp[3]")
    r = run_channel(pack, tmp_path, 10 * VISC_LIMIT, V=1.0, nsteps=200, deck=deck[deck.index("#"):])
    check_ok(r)
    rows = re.findall(r"^\s*200\s+\S+\s+\S+\s+\S+\s+(\S+)\s+(\S+)\s+(\S+)\s*$", r.out, re.M)
    assert rows, r.out[-2000:]
    last, mean, resid = (float(x) for x in rows[-1])
    assert 1 <= last < 200 and 1 <= mean < 200 and 0 < resid < 1e-4
