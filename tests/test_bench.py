"""The scene benchmark command (bench/run-bench.sh) on a tiny scene: it runs the SaltDEM styles
and stock gran/hooke/history on 1 rank, 2 MPI ranks and 2 OpenMP threads and writes
well-formed result files.  No wall time is asserted: a benchmark, not a timed test."""
import json
import math
import os
import subprocess

import pytest

from lmprun import ROOT, lmp_path

TINY = ["--strip", "200", "--ncopy", "2", "--nlayer", "1", "--salt", "100", "--cover", "150",
        "--nsettle", "100", "--nwarm", "20", "--nsteps", "100"]


@pytest.fixture(scope="module")
def bench(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    cmd = ["bash", str(ROOT / "bench" / "run-bench.sh"), "--lmp", lmp_path(), "--out", str(out),
           *TINY]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=900,
                       env=dict(os.environ, SALTDEM_PYTHON="/usr/bin/python3"))
    assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
    return out, p.stdout


def test_results_are_well_formed(bench):
    out, stdout = bench
    res = json.loads((out / "results.json").read_text())
    runs = res["runs"]
    assert [(r["config"], r["style"]) for r in runs] == [
        (c, s) for c in ("serial", "mpi2", "omp2") for s in ("saltdem", "stock")]
    atoms = {r["atoms"] for r in runs}
    assert len(atoms) == 1 and atoms.pop() > 300          # the same scene for every run
    for r in runs:
        assert r["steps"] == 100
        assert r["rate"] > 0 and math.isfinite(r["rate"])
        assert r["loop_seconds"] > 0
        # the rate printed by the deck is atoms x steps over its own timer
        assert r["rate"] == pytest.approx(r["atoms"] * r["steps"] / r["timer_seconds"], rel=1e-3)
        b = r["breakdown"]
        assert set(b) >= {"Pair", "Neigh", "Comm", "Output", "Modify"}
        assert 95.0 < sum(v["percent"] for v in b.values()) < 105.0
        assert b["Pair"]["percent"] > 0
        assert (r["ranks"], r["threads"]) == {"serial": (1, 1), "mpi2": (2, 1),
                                              "omp2": (1, 2)}[r["config"]]
        assert r["procs"] == r["ranks"] * r["threads"]    # LAMMPS counts ranks x threads
    s = res["summary"]
    for c in ("serial", "mpi2", "omp2"):
        v = s["ratio_saltdem_over_stock"][c]
        assert math.isfinite(v) and v > 0
    for style in ("saltdem", "stock"):
        assert set(s["speedup_over_serial"][style]) == {"mpi2", "omp2"}
    p = s["projection"]
    assert p["atoms"] == 47000 and p["steps"] == 1e7
    for k, v in p["wall_time"].items():
        assert v["hours"] > 0 and v["days"] == pytest.approx(v["hours"] / 24)
    assert res["machine"]["cores"] >= 1 and res["machine"]["cpu"]


def test_text_summary_and_logs(bench):
    out, stdout = bench
    text = (out / "results.txt").read_text()
    assert "ratio saltdem/stock (serial)" in text and "projected wall time" in text
    assert text in stdout
    for c in ("serial", "mpi2", "omp2"):
        log = (out / "logs" / f"{c}.log").read_text()
        assert "pair_style      gran/hooke/history" in log or "gran/hooke/history" in log
        assert log.count("BENCH result") == 2
    # -sf omp picked the OpenMP variants of the SaltDEM styles and of the stock one
    log = (out / "logs" / "omp2.log").read_text()
    assert "Last active /omp style is pair_style saltdem/" in log
    assert "Last active /omp style is pair_style gran/hooke/history/omp" in log
