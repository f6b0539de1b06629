#!/usr/bin/env python3
"""Measured stable time step of the SaltDEM styles against the limits they report.

For each case the script bisects the time step dt = X * L, with L the stable limit the styles
report for the case (the smallest of their limits at the default factors, as logged at the case's first run with its walls static: "timestep ... of the
stable limit L (...)"; docs/performance.md's table was measured at the factors of the time,
dtfactor 0.2 and viscfactor 0.5 with the fluid constant 0.1: L is 3x and 2.8x larger since), and
finds the largest X at which the case runs N steps stably:

  stable = LAMMPS ends without error (no NaN: fix saltdem/nve check 10; no lost disc; every
           thermo value finite) and the kinetic energy never exceeds GROW times the largest of
           the nearest stable run below (nor GROW^2 times that of the first run, at X = XREF):
           the physical motion of the case, not an oscillation grown out of round-off.

The styles refuse a time step above their limit at the start of every run (viscfactor <= 1 and
dtfactor <= 0.75 raise it 1.25x only), so the runs above it are reached in exact ways
(docs/performance.md, "Measured stability limits"):

  dt switch   (cases with saltdem/viscous only) the case settles at X_SETTLE, a 'run 0' at the
              settling step passes the check, then 'timestep X*L' and 'run N pre no': 'pre no'
              skips LAMMPS's init and with it the check.  saltdem/viscous, its density update
              and fix saltdem/nve read the time step every step: this is the run at X*L.
  mass switch (cases with saltdem/cohesive, which keeps the time step of its init for its
              tangential and rolling springs; no gravity) the case settles at X_SETTLE, then
              every integrated mass is divided by Y = (X / X_SETTLE)^2 ('set mass') and the run
              goes on at the same dt with 'run N pre no'.  Springs, cohesion and a lid's load do
              not depend on the mass, the dashpots 2 zeta sqrt(m k) scale with it: this is the
              trajectory of the true masses at dt * sqrt(Y) = X * L, step for step.
  the scene   (--scene) examples/expt1.in as it is, its frames replaced: settled once, resumed
              by the deck's own resume path for each trial and driven with a dt switch; the
              cover's springs are kept right by running it with kt, kr x R and zeta_t / sqrt(R)
              and an init at X L / R (see SceneCase).

Cases (--cases; the full preset's discs, power law 6.25-15.625 m from tools/pack.in, h = 1.3
disc spacings as examples/scene/laws.in makes it; the scenes' salt, cover and wall coefficients):

  fluid      SPH salt (pair saltdem/viscous fluid) in plane Couette flow between bands of wall
             discs, the top band a lid moving at V; unloaded (lid held) or under a weighted lid
             at P (load ramped up, settled with a drag); variants of h, S, K, kn_wall and the
             quick preset's discs
  contact    the scenes' contact salt (saltlaw contact: calibration 0.5, salt-salt kn = the
             cover's) in the same flows
  cover      the cover (pair saltdem/cohesive, potentials/cover_paper.params, rough cover-wall
             contacts of kn_wall) between a fixed band and a lid at P, at rest

  PYTHONPATH=python python3 bench/validation/stable_limit.py [--cases fluid,contact,cover|NAME,...] [--table FILE]
  PYTHONPATH=python python3 bench/validation/stable_limit.py --wall-study              # what kn_wall 2.5e9 / 1e10 change
  PYTHONPATH=python python3 bench/validation/stable_limit.py --scene quick             # the real Expt 1 (quick or full;
  PYTHONPATH=python python3 bench/validation/stable_limit.py --scene full --width 625 --pack-kelim 1e-4    # a strip)
  common: [--lmp build/lmp] [--work out/stable] [--decks DIR] [--steps 3000] [--tol 0.03]

One lmp runs at a time; a component case is a few hundred discs (2-15 CPU s per case after its
pack).  Writes WORK/results.json (every run: X, dt, verdict, largest kinetic energy, error) and,
with --table, a markdown table of all cases in it.

The code: this file (the command line, the table), stable_cases.py (materials, the component cases
and their decks), stable_run.py (lmp runs, packs, log parsing), stable_bisect.py (the bisection and
the verdict), stable_scene.py (--scene), stable_wall.py (--wall-study).
"""
import argparse
import json
import pathlib
import re
import time

from saltdem_post.checkout import lmp_path

# the stable_*.py modules next to this script
import stable_run
from stable_bisect import Case
from stable_cases import component_cases
from stable_run import ROOT, Runner
from stable_scene import SceneCase
from stable_wall import wall_study


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lmp", default=lmp_path(ROOT))
    ap.add_argument("--work", default=str(ROOT / "out" / "stable"))
    ap.add_argument("--cases", default="fluid,contact,cover",
                    help="comma list of fluid, contact, cover, or case names")
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--tol", type=float, default=0.03, help="bisection: hi/lo - 1 at the end")
    ap.add_argument("--timeout", type=float, default=3600)
    ap.add_argument("--table", default=None)
    ap.add_argument("--scene", choices=["quick", "full"], help="bisect the real Expt 1 scene instead")
    ap.add_argument("--width", type=float, help="scene: section width (m), default the deck's")
    ap.add_argument("--nsettle", type=int, help="scene: settling steps, default the preset's")
    ap.add_argument("--R", type=float, default=8.0, help="scene: dt switch factor of the cover springs")
    ap.add_argument("--wall-study", action="store_true",
                    help="what kn_wall 2.5e9 and 1e10 change in a small settled scene")
    ap.add_argument("--pack-kelim", type=float, help="scene: settling criterion of tools/pack.in "
                    "(kinetic energy per disc / m g r, default the tool's 1e-6)")
    ap.add_argument("--decks", default=str(ROOT), help="where examples/, tools/ and potentials/ "
                    "come from (default: this repository)")
    args = ap.parse_args()
    stable_run.DECKS = pathlib.Path(args.decks).resolve()

    runner = Runner(args.lmp, args.work, args.timeout)
    resfile = pathlib.Path(args.work) / "results.json"
    results = json.loads(resfile.read_text()) if resfile.exists() else {}
    if args.wall_study:
        results["wall_study"] = wall_study(runner, [2.5e9, 1e10])
        resfile.write_text(json.dumps(results, indent=1))
        return
    if args.scene:
        sc = SceneCase(runner, args.scene, args.steps, args.tol, R=args.R, width=args.width,
                       nsettle=args.nsettle, pack_kelim=args.pack_kelim)
        t0 = time.time()
        sc.probe_limit()
        sc.settle()
        lo, hi = sc.measure(xmax=args.R)
        results[sc.name] = {"params": {"preset": args.scene, "width": args.width, "nsettle": args.nsettle,
                                       "R": args.R, "steps": args.steps},
                            "limit": sc.limit, "style": sc.style, "why": sc.why, "dt_scene": sc.dt_scene,
                            "x_stable": lo, "x_unstable": hi, "runs": sc.runs,
                            "wall_s": round(time.time() - t0)}
        resfile.write_text(json.dumps(results, indent=1))
        print(f"{sc.name}: reported limit {sc.limit:.5g} s; stable up to X {lo:.3f}, unstable at "
              f"{hi if hi else '-'}", flush=True)
        if args.table:
            pathlib.Path(args.table).write_text(table(results))
        return
    which = args.cases.split(",")
    sel = [c for c in component_cases() if c["law"] in which or c["name"] in which]
    for c in sel:
        W, H, kw = c.pop("pack_spec")
        c["pack"] = runner.pack(W, H, **kw).name
        case = Case(runner, c, args.steps, args.tol)
        t0 = time.time()
        case.probe_limit()
        lo, hi = case.measure()
        results[c["name"]] = {"params": c, "limit": case.limit, "style": case.style, "why": case.why,
                              "x_stable": lo, "x_unstable": hi, "runs": case.runs,
                              "wall_s": round(time.time() - t0)}
        resfile.write_text(json.dumps(results, indent=1))
        print(f"{c['name']}: reported limit {case.limit:.5g} s ({case.why}); stable up to X {lo:.3f}, "
              f"unstable at {hi if hi else '-'}", flush=True)
    if args.table:
        pathlib.Path(args.table).write_text(table(results))


def what_sets(why):
    """A short name for the limit a log line names."""
    types = re.search(r"of types (\d+) (\d+)", why)
    t = f" {types.group(1)}-{types.group(2)}" if types else ""
    if "h^2" in why:
        return "fluid viscosity" + t
    if "calibration" in why:
        return "contact dashpots" + t
    if "sound" in why:
        return "sound" + t
    m = re.match(r"(kn|kt) = (\S+)", why)
    if m:
        return f"elastic {m.group(1)} {float(m.group(2)):g}" + t
    return why[:40]


def table(results):
    lines = ["| case | reported limit L (s) | set by | stable up to X | unstable at X | "
             "measured limit (s) |", "| --- | --- | --- | --- | --- | --- |"]
    for name, r in results.items():
        if "limit" not in r or "x_stable" not in r:
            continue
        hi = f"{r['x_unstable']:.2f}" if r["x_unstable"] else f"> {r['x_stable']:.2f}"
        lines.append(f"| {name} | {r['limit']:.4g} | {what_sets(r['why'])} | {r['x_stable']:.2f} | {hi} | "
                     f"{r['x_stable'] * r['limit']:.4g} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
