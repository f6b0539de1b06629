"""The scene benchmark command (bench/performance/run-bench.sh) on a tiny scene: it runs the SaltDEM styles
and stock gran/hooke/history on 1 rank, 2 MPI ranks, 2 OpenMP threads and 4 MPI ranks and
writes well-formed result files, with the per-rank counts a scaling model needs (processor
grid, ghost cutoff, Nlocal/Nghost/Neighs, min/avg/max of the timing breakdown) and the 4-rank
run marked oversubscribed on a machine with fewer cores.  No wall time is asserted: a benchmark,
not a timed test."""
import json
import math
import os

import pytest

from lmprun import ROOT, lmp_path, run_cmd

TINY = ["--strip", "200", "--ncopy", "2", "--nlayer", "1", "--salt", "100", "--cover", "150",
        "--nsettle", "100", "--nwarm", "20", "--nsteps", "100",
        "--configs", "serial,mpi2,omp2,mpi4"]
CONFIGS = ("serial", "mpi2", "omp2", "mpi4")
RANKS = {"serial": (1, 1), "mpi2": (2, 1), "omp2": (1, 2), "mpi4": (4, 1)}


@pytest.fixture(scope="module")
def bench(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    cmd = ["bash", str(ROOT / "bench" / "performance" / "run-bench.sh"), "--lmp", lmp_path(), "--out", str(out),
           *TINY]
    p = run_cmd(cmd, capture_output=True, text=True, timeout=900,
                       env=dict(os.environ, SALTDEM_PYTHON="/usr/bin/python3"))
    assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
    return out, p.stdout


def test_results_are_well_formed(bench):
    out, stdout = bench
    res = json.loads((out / "results.json").read_text())
    runs = res["runs"]
    assert [(r["config"], r["style"]) for r in runs] == [
        (c, s) for c in CONFIGS for s in ("saltdem", "stock")]
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
        assert (r["ranks"], r["threads"]) == RANKS[r["config"]]
        assert r["procs"] == r["ranks"] * r["threads"]    # LAMMPS counts ranks x threads
        assert r["oversubscribed"] == (r["ranks"] * r["threads"] > res["machine"]["cores"])
    s = res["summary"]
    assert s["oversubscribed"] == [c for c in CONFIGS
                                   if RANKS[c][0] * RANKS[c][1] > res["machine"]["cores"]]
    for c in CONFIGS:
        v = s["ratio_saltdem_over_stock"][c]
        assert math.isfinite(v) and v > 0
    for style in ("saltdem", "stock"):
        assert set(s["speedup_over_serial"][style]) == {"mpi2", "omp2", "mpi4"}
    p = s["projection"]
    assert p["atoms"] == 48256 and p["steps"] == 3.26e6
    for k, v in p["wall_time"].items():
        assert v["hours"] > 0 and v["days"] == pytest.approx(v["hours"] / 24)
    assert res["machine"]["cores"] >= 1 and res["machine"]["cpu"]


def test_per_rank_counts(bench):
    """The fields of a strong-scaling model: grid, ghost cutoff, counts over the ranks, the
    breakdown's min/avg/max."""
    out, stdout = bench
    res = json.loads((out / "results.json").read_text())
    for r in res["runs"]:
        px, py, pz = r["grid"]
        assert px * py == r["ranks"] and pz == 1                  # 2D: no split in z
        assert r["ghost_cutoff"] > 0
        c = r["counts"]
        assert set(c) == {"Nlocal", "Nghost", "Neighs"}
        for k, v in c.items():
            assert v["min"] <= v["ave"] <= v["max"], (r["config"], k, v)
            assert v["min"] >= 0
        # the owned discs add up to the scene, on every rank count
        assert c["Nlocal"]["ave"] * r["ranks"] == pytest.approx(r["atoms"])
        if r["ranks"] == 1:
            assert c["Nlocal"]["max"] == r["atoms"]
            assert c["Nghost"]["max"] == 0                         # no periodic x or y
        else:
            assert c["Nghost"]["max"] > 0                          # neighbours across a cut
        for sec, d in r["breakdown"].items():
            if sec == "Other":
                continue
            assert d["min_seconds"] <= d["avg_seconds"] * (1 + 1e-6) + 1e-9
            assert d["avg_seconds"] <= d["max_seconds"] * (1 + 1e-6) + 1e-9
            if d["avg_seconds"] > 0:
                assert d["imbalance"] == pytest.approx(d["max_seconds"] / d["avg_seconds"])
                if r["ranks"] * r["threads"] == 1:
                    assert d["imbalance"] == pytest.approx(1.0)
        if r["style"] == "stock":                                  # a plain half list
            assert c["Neighs"]["ave"] * r["ranks"] == pytest.approx(r["neighbors_total"], rel=1e-6)
    # the same scene cut 2 and 4 ways: more ghosts in all on 4 ranks
    by = {(r["config"], r["style"]): r for r in res["runs"]}
    for style in ("saltdem", "stock"):
        g2, g4 = (by[(c, style)]["counts"]["Nghost"]["ave"] * n for c, n in (("mpi2", 2), ("mpi4", 4)))
        assert g4 > g2


def test_text_summary_and_logs(bench):
    out, stdout = bench
    text = (out / "results.txt").read_text()
    assert "ratio saltdem/stock (serial)" in text and "projected wall time" in text
    assert text in stdout
    assert "per rank (ave / max / min" in text
    if res_cores(out) < 4:
        assert "OVERSUBSCRIBED" in text and "(oversubscribed: not speed)" in text
    for c in CONFIGS:
        log = (out / "logs" / f"{c}.log").read_text()
        assert "pair_style      gran/hooke/history" in log or "gran/hooke/history" in log
        assert log.count("BENCH result") == 2
    # -sf omp picked the OpenMP variants of the SaltDEM styles and of the stock one
    log = (out / "logs" / "omp2.log").read_text()
    assert "Last active /omp style is pair_style saltdem/" in log
    assert "Last active /omp style is pair_style gran/hooke/history/omp" in log


def res_cores(out):
    return json.loads((out / "results.json").read_text())["machine"]["cores"]


def test_pair_cost_reports_every_style_per_interacting_pair(tmp_path):
    """bench/performance/pair_cost.py on a tiny pack: every style's timed run, its interacting pairs (the
    granular styles' contacts about 2-4 per disc in a settled pack, the salt's kernel about 20),
    a finite cost per pair and the ratio to stock; no timings asserted."""
    js = tmp_path / "r.json"
    p = run_cmd(["/usr/bin/python3", str(ROOT / "bench" / "performance" / "pair_cost.py"), "--lmp", lmp_path(),
                        "--work", str(tmp_path), "--W", "300", "--H", "150", "--nsteps", "20",
                        "--json", str(js)], capture_output=True, text=True, timeout=600,
                       env=dict(os.environ, PYTHONPATH=str(ROOT / "python")))
    assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
    res = json.loads(js.read_text())
    assert list(res) == ["hooke", "cohesive", "viscous", "viscous2"]
    atoms = {r["atoms"] for r in res.values()}
    assert len(atoms) == 1 and atoms.pop() > 50
    for name, r in res.items():
        assert r["steps"] == 20
        assert math.isfinite(r["ns_per_pair"]) and r["ns_per_pair"] > 0, (name, r)
        assert 0 < r["pair_s"] <= r["loop_s"]
        lo, hi = (8, 40) if name.startswith("viscous") else (1.5, 5)
        assert lo < r["pairs_per_atom"] < hi, (name, r["pairs_per_atom"])
    assert res["hooke"]["vs_stock"] == pytest.approx(1.0)
    # the same pack: both granular styles see the same contacts
    assert res["cohesive"]["pairs"] == pytest.approx(res["hooke"]["pairs"], rel=0.05)
    assert "ns/pair" in p.stdout


def test_pair_cost_in_3d(tmp_path):
    """--D: the same benchmark on a sphere pack: spheres touch about 4-8 others, the salt's
    kernel (1.3 sphere spacings) holds about 40-90; a finite cost per pair; no timings asserted."""
    js = tmp_path / "r.json"
    p = run_cmd(["/usr/bin/python3", str(ROOT / "bench" / "performance" / "pair_cost.py"), "--lmp", lmp_path(),
                 "--work", str(tmp_path), "--W", "300", "--H", "150", "--D", "100", "--nsteps", "20",
                 "--styles", "hooke,cohesive,viscous", "--json", str(js)], capture_output=True, text=True,
                timeout=600, env=dict(os.environ, PYTHONPATH=str(ROOT / "python")))
    assert p.returncode == 0, (p.stdout + p.stderr)[-3000:]
    res = json.loads(js.read_text())
    for name, r in res.items():
        assert math.isfinite(r["ns_per_pair"]) and r["ns_per_pair"] > 0, (name, r)
        lo, hi = (40, 90) if name == "viscous" else (4, 8)
        assert lo < r["pairs_per_atom"] < hi, (name, r["pairs_per_atom"])
    assert res["cohesive"]["pairs"] == pytest.approx(res["hooke"]["pairs"], rel=0.05)
