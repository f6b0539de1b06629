#!/usr/bin/env python3
"""The salts under load, side by side: plane Couette flow under a weighted lid
(examples/calibration/couette_load.in) at lid pressures P and shear rates, for the contact salt
and the SPH salt with or without a plastic strength (the frictional-viscous salt).

  PYTHONPATH=python python3 bench/validation/couette_load_sweep.py [--lmp build/lmp]
      [--work out/couette_load] [--pressures 5e6,1e7,2e7] [--rates 5e-5,5e-4] [--strain 2]
      [--salt NAME:VARS ...] [--fit NAME] [--compare NAME:REF]

--salt NAME:VARS  a salt and its couette_load.in variables, e.g.
                  contact:'law contact cal 0.5' or fv:'law sph mu_y 0.1 c_y 0 eta 5e8'
                  (default: those two);
--fit NAME        fit tau = mu P + eta rate (least squares, relative) to that salt's runs;
--compare A:B     the relative difference of A's tau from B's at each point.

Each run is a few hundred discs; ~10 s at 5e-4 1/s and 1-3 min at 5e-5 1/s (strain 2).  A
finished run (its result line in WORK/NAME/P_rate.txt) is not run again.  Writes
WORK/results.json and prints a markdown table.
"""
import argparse
import json
import pathlib
import re
import shlex
import subprocess
import sys

from saltdem_post.checkout import lmp_path

ROOT = pathlib.Path(__file__).resolve().parents[2]
DECK = ROOT / "examples" / "calibration" / "couette_load.in"
RESULT = re.compile(r"couette_load: result law \S+ P \S+ rate (\S+) tau (\S+) Pa")


def run_one(lmp, work, name, vars_, P, rate, strain):
    d = work / name
    d.mkdir(parents=True, exist_ok=True)
    out = d / f"P{P}_r{rate}.txt"
    if not (out.exists() and RESULT.search(out.read_text())):
        cmd = [lmp, "-in", str(DECK), "-var", "root", str(ROOT), "-log", "none",
               "-var", "P", P, "-var", "rate", rate, "-var", "strain", str(strain),
               "-var", "tag", f"{name}_P{P}_r{rate}"]
        words = shlex.split(vars_)
        for k in range(0, len(words), 2):
            cmd += ["-var", words[k], words[k + 1]]
        proc = subprocess.run(cmd, cwd=d, capture_output=True, text=True,
                              env={"OMP_NUM_THREADS": "1", "PATH": "/usr/bin:/bin"})
        out.write_text(proc.stdout + proc.stderr)
        if proc.returncode != 0:
            sys.exit(f"couette_load_sweep: {name} P {P} rate {rate} failed:\n{proc.stdout[-2000:]}")
    m = RESULT.search(out.read_text())
    return {"P": float(P), "rate": float(m.group(1)), "tau": float(m.group(2))}


def fit(points):
    """tau = mu P + eta rate, least squares in relative terms (2x2 normal equations)."""
    a11 = a12 = a22 = b1 = b2 = 0.0
    for p in points:
        w = 1.0 / p["tau"]
        x1, x2, y = p["P"] * w, p["rate"] * w, 1.0
        a11 += x1 * x1
        a12 += x1 * x2
        a22 += x2 * x2
        b1 += x1 * y
        b2 += x2 * y
    det = a11 * a22 - a12 * a12
    mu = (b1 * a22 - b2 * a12) / det
    eta = (a11 * b2 - a12 * b1) / det
    worst = max(abs(mu * p["P"] + eta * p["rate"] - p["tau"]) / p["tau"] for p in points)
    return mu, eta, worst


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=None)
    ap.add_argument("--work", default=str(ROOT / "out" / "couette_load"))
    ap.add_argument("--pressures", default="5e6,1e7,2e7")
    ap.add_argument("--rates", default="5e-5,5e-4")
    ap.add_argument("--strain", type=float, default=2.0)
    ap.add_argument("--salt", action="append", default=None)
    ap.add_argument("--fit", action="append", default=[])
    ap.add_argument("--compare", action="append", default=[])
    a = ap.parse_args()
    lmp = a.lmp or str(lmp_path())
    work = pathlib.Path(a.work)
    salts = a.salt or ["contact:law contact cal 0.5", "fv:law sph mu_y 0.1 c_y 0 eta 5e8"]
    results = {}
    for s in salts:
        name, vars_ = s.split(":", 1)
        results[name] = {"vars": vars_, "points": [
            run_one(lmp, work, name, vars_, P, r, a.strain)
            for P in a.pressures.split(",") for r in a.rates.split(",")]}
    print("| salt | P (MPa) | rate (1/s) | tau (Pa) | tau / P |")
    print("|---|---|---|---|---|")
    for name, res in results.items():
        for p in res["points"]:
            print(f"| {name} | {p['P'] / 1e6:g} | {p['rate']:.3g} | {p['tau']:.4g} | {p['tau'] / p['P']:.4f} |")
    for name in a.fit:
        mu, eta, worst = fit(results[name]["points"])
        results[name]["fit"] = {"mu": mu, "eta": eta, "worst": worst}
        print(f"\n{name}: tau = {mu:.4f} P + {eta:.3g} rate (worst point {100 * worst:.1f} %)")
    for c in a.compare:
        x, ref = c.split(":")
        diffs = [pa["tau"] / pb["tau"] - 1.0
                 for pa, pb in zip(results[x]["points"], results[ref]["points"])]
        results[x][f"vs_{ref}"] = diffs
        print(f"\n{x} against {ref}: " + ", ".join(f"{100 * d:+.1f} %" for d in diffs)
              + f" (worst {100 * max(map(abs, diffs)):.1f} %)")
    (work / "results.json").write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
