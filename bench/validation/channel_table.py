#!/usr/bin/env python3
"""The measured-viscosity table of docs/pair_saltdem_viscous.rst, re-measured with the present
build: plane Couette and Poiseuille flows of the paper's salt in tests/decks/channel.in (the runs
and pack of tests/test_viscous.py, read by saltdem_post.channel as the tests read them).

  PYTHONPATH=python /usr/bin/python3 bench/validation/channel_table.py [--out out/channel_table] [--nsteps 10000]

Prints the table as RST rows and writes OUT/table.json.  About 7 runs of 2 x nsteps steps of
1,038 discs (a few CPU minutes).
"""
import argparse
import json
import pathlib
import sys

from saltdem_post.calibration.runner import Context, Job, run_one
from saltdem_post.channel import ChannelFlow, read_params
from saltdem_post.checkout import lmp_path

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHANNEL = ROOT / "tests" / "decks" / "channel.in"
PARAMS = ROOT / "potentials" / "salt_paper.params"
PAPER = read_params(PARAMS)
ETA, RHO, S_PAPER = PAPER["eta"], PAPER["rho"], PAPER["S"]
RMIN, RMAX = PAPER["rmin"], PAPER["rmax"]
PACK = dict(W=1000, H=500, seed=7)        # the pack of tests/test_viscous.py
NSTEPS = 10000                            # the channel deck runs 2 x NSTEPS, averages the second half

CASES = [  # label, V, gx, eta, S
    ("Couette V = 0.5 m/s", 0.5, 0.0, ETA, S_PAPER),
    ("Couette V = 1 m/s", 1.0, 0.0, ETA, S_PAPER),
    ("Couette V = 3 m/s", 3.0, 0.0, ETA, S_PAPER),
    ("Couette V = 1, eta 1e9", 1.0, 0.0, 2 * ETA, 2 * S_PAPER),
    ("Couette V = 1, eta 2.5e8", 1.0, 0.0, 0.5 * ETA, 0.5 * S_PAPER),
    ("Poiseuille gx = 3", 0.0, 3.0, ETA, S_PAPER),
    ("Poiseuille gx = 12", 0.0, 12.0, ETA, S_PAPER),
]


def measure(c):
    """(tau, eta_eff, R^2) of a channel run: Couette tau / rate, Poiseuille -rho g / (2 a)."""
    if c.V:
        return c.tau, c.eta_eff, c.fit(1)[1]
    p, r2 = c.fit(2)
    return None, -c.rhob * c.gx / (2.0 * p[0]), r2


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(ROOT / "out" / "channel_table"))
    ap.add_argument("--nsteps", type=int, default=NSTEPS)
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out).resolve()
    ctx = Context(lmp=lmp_path(ROOT), out=out, rerun=True, root=ROOT)
    run_one(ctx, Job(ROOT / "tools" / "pack.in", out / "pack",
                     dict(rmin=RMIN, rmax=RMAX, out="pack.data", **PACK), "pack"))
    pack = out / "pack" / "pack.data"
    rows = []
    for k, (label, V, gx, eta, S) in enumerate(CASES):
        d = out / f"case{k}"
        d.mkdir(parents=True, exist_ok=True)
        (d / "in.deck").write_text(f"include {PARAMS}\n" + CHANNEL.read_text())
        job = run_one(ctx, Job(d / "in.deck", d, dict(pack=pack, V=V, gx=gx, eta=eta, S=S, nsteps=args.nsteps),
                               label))
        c = ChannelFlow(d, job.output, PACK["H"], RMAX, RHO, V, gx, eta=eta, S=S)
        tau, eta_eff, r2 = measure(c)
        rows.append(dict(flow=label, S=S, Re_S=float(c.reynolds), tau=tau, eta=eta,
                         eta_eff=float(eta_eff), ratio=float(eta_eff / eta), R2=float(r2)))
        print(f"{label:<24}  {S:<6g}  {c.reynolds:<9.3f}  "
              f"{'--' if tau is None else f'{tau:.4g}':<11}  "
              f"{eta_eff:.4g} ({eta_eff / eta:.3f})  {r2:.4f}", flush=True)
    (out / "table.json").write_text(json.dumps(rows, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
