"""Reliability matrix, long part: the cases of tests/test_reliability.py at the paper's
resolution, at the scene's driving rate, and over many more steps (docs/reliability.md).
Excluded from the default run by pytest.ini; run them with

    /usr/bin/python3 -m pytest -m long tests

(a few minutes on 2 cores).  The checks are those of the fast module: "stable" means a
normal end, finite thermo, no atom lost, and E - W (energy of the scaled dynamics minus the
work of the moving hanging wall) never above its start by more than 1e-3 M g H.
"""
import math
import re

import pytest

from lmprun import check_ok
from reliability_lib import PRESETS, Scene, max_rel_diff, read_dump
from test_reliability import (DUMP, ENERGY, FAULT, FINAL, MPI_TOL, RESTART_TOL, RST_THERMO,
                              SCALE, assert_error, assert_stable, continue_from, growth,
                              limit_and_advice, max_wall_overlap, memory_run, read_data,
                              run_scene, settled_scenes, HEAP_TOL, RSS_TOL, REDEFINE)

pytestmark = pytest.mark.long


@pytest.fixture(scope="module")
def scenes(tmp_path_factory):
    kinds = {
        "quick": lambda: Scene("quick"),
        "paper": lambda: Scene("paper"),
        "weld": lambda: Scene("quick", weld=True, target=125.0),
        "thin": lambda: Scene("quick", salt=2, cover=6, target=312.5),
        "paper-thin": lambda: Scene("paper", salt=2, cover=6, target=80.0),
        "long": lambda: Scene("quick", target=2000.0),
        # about 1,100 of the paper's discs
        "paper-big": lambda: Scene("paper", width=96, salt=12, cover=12, target=40.0),
    }
    return settled_scenes(kinds, tmp_path_factory, 20000)


# ---- stiff ------------------------------------------------------------------------------------

@pytest.mark.parametrize("factor", [100, 10000])
def test_long_stiff_kn_paper_resolution(scenes, tmp_path, factor):
    """kn x100 and x10,000 with the paper's discs (S 20, dt 0.002 s): refused before the first
    step with the limit 0.6 sqrt(S m_min / kn) named; 20,000 steps at the named dt are stable."""
    s, data = scenes("paper")
    kn = 1e10 * factor
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "run 20000\n", kn_cover=kn, kn_wall=kn)
    line = assert_error(r, "stable limit", f"kn = {kn:g}")
    assert "Step" not in r.out
    lim, use = limit_and_advice(line)
    atoms = read_data(data)
    m_min = atoms[atoms[:, 1] == 1][:, 6].min() * PRESETS["paper"]["S"]
    assert lim == pytest.approx(0.6 * math.sqrt(m_min / kn), rel=1e-5)
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "thermo 1000\nrun 20000\n", kn_cover=kn,
                  kn_wall=kn, dt=use)
    assert_stable(r, data, natoms=len(atoms))


def test_long_stiff_viscosity_x100(scenes, tmp_path):
    """eta x100 at the paper's dt with the inertia factor the error asks for: 20,000 steps."""
    s, data = scenes("paper")
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "run 2000\n", eta=5e10)
    line = assert_error(r, "saltdem/viscous", "eta = 5e+10")
    need = float(re.search(r"S >= ([0-9.eE+-]+) times", line).group(1))
    S = math.ceil(need * 1.05) * PRESETS["paper"]["S"]
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "thermo 1000\nrun 20000\n", eta=5e10,
                  S=S, S_cover=S)
    assert_stable(r, data, natoms=len(read_data(data)))


def test_long_paper_viscosity_paper_rate(scenes, tmp_path):
    """The paper's salt, discs, dt and rate (0.05 m/s): 50,000 steps (2.5 m of fault slip)."""
    s, data = scenes("paper")
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "thermo 5000\nrun 50000\n")
    t = assert_stable(r, data, natoms=len(read_data(data)))
    assert t["f_fault[1]"][-1] == pytest.approx(0.05 * 0.002 * 50000, rel=1e-9)


# ---- extreme ----------------------------------------------------------------------------------

def test_long_weld_scene_rate(scenes, tmp_path):
    """The weld (one row of the smallest salt discs) under the hanging wall moving 2 rmax
    (125 m) at the scene's rate 0.5 m/s (100,000 steps): stable, no tunnelling."""
    s, data = scenes("weld")
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "thermo 5000\nrun 100500\n" + FINAL)
    t = assert_stable(r, data, natoms=len(read_data(data)))
    assert t["f_fault[1]"][-1] == pytest.approx(s.target, rel=1e-12)
    assert max_wall_overlap(tmp_path / "final.dump") < 0.5


def test_long_fault_beyond_salt_scene_rate(scenes, tmp_path):
    """Fault slip 312.5 m (throw 156 m) through 125 m of salt at the scene's rate 0.5 m/s
    (250,000 steps): stable, no tunnelling."""
    s, data = scenes("thin")
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "thermo 10000\nrun 251000\n" + FINAL)
    t = assert_stable(r, data, natoms=len(read_data(data)))
    assert t["f_fault[1]"][-1] == pytest.approx(s.target, rel=1e-12)
    assert max_wall_overlap(tmp_path / "final.dump") < 0.5


def test_long_fault_beyond_salt_paper_resolution(scenes, tmp_path):
    """The paper's discs: salt 31.25 m, fault slip 80 m (throw 40 m) at 0.5 m/s, dt 0.002 s
    (80,000 steps): stable, no tunnelling."""
    s, data = scenes("paper-thin")
    assert s.target * math.sin(math.radians(s.dip)) > s.Hs
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "thermo 5000\nrun 80500\n" + FINAL,
                  rate=0.5)
    t = assert_stable(r, data, natoms=len(read_data(data)))
    assert t["f_fault[1]"][-1] == pytest.approx(s.target, rel=1e-12)
    assert max_wall_overlap(tmp_path / "final.dump") < 0.5


def test_long_reynolds_one_paper_resolution(scenes, tmp_path):
    """Re_model = 1 with the paper's discs and salt (V = eta / (S rho L)): the warning, and
    10,000 stable steps."""
    s, data = scenes("paper")
    S, rho, eta, L = PRESETS["paper"]["S"], 2200.0, 5e8, s.Hs
    V = eta / (S * rho * L)
    fix = (f"fix scale all saltdem/viscosity lambda 1e9 model {eta} rate {V!r} length {L!r} "
           f"density {rho} inertia {S}\n")
    r = run_scene(tmp_path, s, data, fix + FAULT + ENERGY + "thermo 1000\nrun 10000\n", rate=V,
                  target=2 * s.rmax)
    assert_stable(r, data, natoms=len(read_data(data)))
    assert re.search(r"WARNING: Fix saltdem/viscosity: the model Reynolds number 1 \(", r.out)


# ---- restart, parallel ------------------------------------------------------------------------

def test_long_restart_paper_resolution(scenes, tmp_path):
    """About 1,100 of the paper's discs at the paper's rate, split at 10,000 of 20,000 steps:
    read_restart in a fresh process reproduces 'run N; write_restart; run N' within 1e-10 of
    the box width."""
    s, data = scenes("paper-big")
    kw = dict(n=10000, rate=0.05, target=10.0)
    tail = FAULT + SCALE + RST_THERMO + "run ${n}\nwrite_restart split.restart\nrun ${n}\n" + \
        DUMP.format("split.dump")
    check_ok(run_scene(tmp_path, s, data, tail, **kw))
    r = continue_from(tmp_path, s, data, kw, "split.restart", "cont.dump")
    assert "WARNING" not in r.out
    W = s.box()[1] - s.box()[0]
    assert max_rel_diff(read_dump(tmp_path / "split.dump"), read_dump(tmp_path / "cont.dump"),
                        W) < RESTART_TOL


PAR_LONG = FAULT + SCALE + RST_THERMO + "run 20000\n" + DUMP.format("final.dump")


@pytest.fixture(scope="module")
def big_serial(scenes, tmp_path_factory):
    s, data = scenes("paper-big")
    d = tmp_path_factory.mktemp("big1")
    check_ok(run_scene(d, s, data, PAR_LONG))
    return s, data, read_dump(d / "final.dump")


@pytest.mark.parametrize("mode", ["np2", "omp2", "np4"])
def test_long_parallel_paper_resolution(big_serial, tmp_path, mode):
    """About 1,100 of the paper's discs, 20,000 steps at the paper's rate: 2 ranks, 2 threads
    and 4 (oversubscribed) ranks give the serial positions within 1e-8 of the box width."""
    s, data, a = big_serial
    tail = PAR_LONG
    kw = {"np2": dict(np=2), "omp2": dict(omp=2), "np4": dict(np=4)}[mode]
    r = run_scene(tmp_path, s, data, tail, **kw)
    check_ok(r)
    W = s.box()[1] - s.box()[0]
    assert max_rel_diff(a, read_dump(tmp_path / "final.dump"), W) < MPI_TOL


# ---- memory -----------------------------------------------------------------------------------

@pytest.mark.parametrize("body", ["", REDEFINE], ids=["runs", "redefine"])
def test_long_memory_many_rebuilds(scenes, tmp_path, body):
    """40 x 5,000 steps (hanging wall at 4 m/s for 2,000 m, skin 0.3 m: a rebuild every few
    steps, over 30,000 in all): from loop 5 to loop 40 the heap in use grows by less than 0.25
    MB and the peak resident size by less than 2 MB."""
    s, data = scenes("long")
    out, samples, builds = memory_run(s, data, tmp_path, body, nloop=40, nrun=5000, rate=4.0,
                                      skin=0.3, timeout=1200)
    assert builds > 30000, builds
    dheap, drss = growth(out, samples, 40, warm=5)
    assert dheap < HEAP_TOL, f"heap grew by {dheap:.3f} MB"
    assert drss < RSS_TOL, f"resident size grew by {drss:.3f} MB"
