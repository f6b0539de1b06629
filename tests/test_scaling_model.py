"""bench/performance/scaling_model.py on the result of a tiny scene benchmark (serial, 2 MPI ranks cut
vertically and horizontally, 4 MPI ranks):
it runs, writes a well-formed model (constants with their sources, projections for P = 1..pmax,
the full Expt 1 and 2 step counts), and its geometric ghost counts match the ghosts LAMMPS
reported on 2 and 4 ranks and grow with P for strips.  No wall time is asserted."""
import json
import math
import os

import pytest

from lmprun import ROOT, lmp_path, run_cmd

TINY = ["--strip", "200", "--ncopy", "2", "--nlayer", "1", "--salt", "100", "--cover", "150",
        "--nsettle", "100", "--nwarm", "20", "--nsteps", "50", "--styles", "saltdem",
        "--configs", "serial,mpi2,mpi2y,mpi4",
        # a short drive: a box that ends 50 m below the salt, so that the horizontal cut of
        # mpi2y (the box's middle) falls in the scene and separates salt from cover
        "--var", "target", "50"]
PMAX, NODE = 6, 4


@pytest.fixture(scope="module")
def model(tmp_path_factory):
    out = tmp_path_factory.mktemp("scaling")
    env = dict(os.environ, SALTDEM_PYTHON="/usr/bin/python3")
    p = run_cmd(["bash", str(ROOT / "bench" / "performance" / "run-bench.sh"), "--lmp", lmp_path(),
                        "--out", str(out), *TINY], capture_output=True, text=True, timeout=900,
                       env=env)
    assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
    # the benchmark's own scene as the "real" dump: exercises the calibration path
    cmd = ["/usr/bin/python3", str(ROOT / "bench" / "performance" / "scaling_model.py"), str(out / "results.json"),
           "--pmax", str(PMAX), "--node", str(NODE), "--scene-dump", str(out / "bench_settled.dump"),
           "--scene-size", "400", "100", "150",
           "--one-core-step", "0.0142", "--two-rank-step", "0.0083"]
    p = run_cmd(cmd, capture_output=True, text=True, timeout=600,
                       env=dict(os.environ, PYTHONPATH=str(ROOT / "python")))
    assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
    res = json.loads((out / "results.json").read_text())
    return json.loads((out / "scaling-model.json").read_text()), res, p.stdout


def test_constants_and_sources(model):
    m, res, stdout = model
    for k in ("a_pair", "a_rest", "w", "b", "k", "cutghost", "latency", "passes"):
        v = m["model"][k]
        assert math.isfinite(v["value"]) and v["value"] >= 0, k
        assert v["source"], k
    assert m["model"]["a_pair"]["value"] > 0 and m["model"]["a_rest"]["value"] > 0
    assert m["model"]["cutghost"]["value"] == res["runs"][0]["ghost_cutoff"]
    # full preset: 50,000 settling steps + 1000 m at 0.05 m/s with dt 0.01185 s
    assert m["steps"]["full_preset"] == pytest.approx(50000 + 1000 / (0.05 * 0.01185))
    assert "SaltDEM strong-scaling model" in stdout and "latency sensitivity" in stdout


def test_ghosts_against_lammps(model):
    """The geometric counts on the scene's dump against LAMMPS's own, on the runs' grids."""
    m, res, stdout = model
    assert m["validation"]["mpi2y"]["grid_measured"] == [1, 2]
    # the horizontal cut: one rank holds (nearly) all the salt, so w can be fitted from it
    # (whether the fit lands in its range depends on the timings: not asserted)
    src = m["model"]["w"]["source"]
    assert src.startswith("fitted: the mpi2y run") or "the mpi2y run's Pair max/min" in src, src
    for c in ("mpi2", "mpi2y", "mpi4"):
        v = m["validation"][c]
        assert v["grid_model"] == v["grid_measured"]
        g, gm = v["nghost_measured"], v["nghost_model"]
        for q in ("ave", "max"):
            assert abs(gm[q] - g[q]) <= max(3, 0.2 * g[q]), (c, q, g, gm)
        assert v["nlocal_model"]["max"] == pytest.approx(v["nlocal_measured"]["max"], abs=3)
    assert m["validation"]["mpi4"]["oversubscribed"] == (res["machine"]["cores"] < 4)
    assert "step_measured" not in m["validation"]["mpi4"] or res["machine"]["cores"] >= 4


def test_projections(model):
    m, res, stdout = model
    assert set(m["projections"]) == {"expt1", "expt2", "expt1-dump"}
    e1, e2 = m["projections"]["expt1"], m["projections"]["expt2"]
    # Expt 2 is the twice as long section: about twice the discs
    assert 1.8 < e2["discs"] / e1["discs"] < 2.2
    for p in m["projections"].values():
        assert p["steps"] == m["steps"]["full_preset"]
        for kind, rows in p["table"].items():
            assert [r["P"] for r in rows] == list(range(1, PMAX + 1))
            assert rows[0]["speedup"] == pytest.approx(1.0)
            for r in rows:
                assert r["grid"][0] * r["grid"][1] == r["P"]
                assert r["step_s"] > 0 and 0 < r["efficiency"] <= 1.0 + 1e-9
                assert r["imbalance"] >= 1.0 - 1e-9
            if kind.startswith("strips"):
                assert all(r["grid"] == [r["P"], 1] for r in rows)
                tot = [r["ghost"]["total"] for r in rows]
                assert tot[0] == 0 and all(t > 0 for t in tot[1:])
                assert all(b > a for a, b in zip(tot, tot[1:])), (kind, tot)
        assert set(p["node"]) == {"grid", "grid+balance", "strips", "strips+balance"}
        for n in p["node"].values():
            assert n["P"] == NODE and n["hours"] > 0 and n["hours_overhead"] > 0
    # calibrated to a one-core step of the "real" scene: its serial step is that step
    cal = m["calibrated"]
    assert cal["expt1-dump"]["serial_step_s"] == pytest.approx(0.0142)
    assert "scale" in cal and cal["scale"]["scale"] > 0
