#!/usr/bin/env python3
"""The measured-viscosity table of docs/pair_saltdem_viscous.rst, re-measured with the present
build: plane Couette and Poiseuille flows of the paper's salt in tests/decks/channel.in (the runs,
fits and eta_eff of tests/test_viscous.py, whose Channel class this script uses).

  /usr/bin/python3 bench/channel_table.py [--out out/channel_table] [--nsteps 10000]

Prints the table as RST rows and writes OUT/table.json.  About 7 runs of 2 x nsteps steps of
1,038 discs (a few CPU minutes).
"""
import argparse
import json
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
import test_viscous as tv  # noqa: E402  (the channel deck, its parameters and fits)
from lmprun import check_ok, run_lmp  # noqa: E402

CASES = [  # label, V, gx, eta, S
    ("Couette V = 0.5 m/s", 0.5, 0.0, tv.ETA, tv.S_PAPER),
    ("Couette V = 1 m/s", 1.0, 0.0, tv.ETA, tv.S_PAPER),
    ("Couette V = 3 m/s", 3.0, 0.0, tv.ETA, tv.S_PAPER),
    ("Couette V = 1, eta 1e9", 1.0, 0.0, 2 * tv.ETA, 2 * tv.S_PAPER),
    ("Couette V = 1, eta 2.5e8", 1.0, 0.0, 0.5 * tv.ETA, 0.5 * tv.S_PAPER),
    ("Poiseuille gx = 3", 0.0, 3.0, tv.ETA, tv.S_PAPER),
    ("Poiseuille gx = 12", 0.0, 12.0, tv.ETA, tv.S_PAPER),
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
    ap.add_argument("--nsteps", type=int, default=tv.NSTEPS)
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out).resolve()
    (out / "pack").mkdir(parents=True, exist_ok=True)
    r = run_lmp(tv.PACK_IN.read_text(), out / "pack", rmin=tv.RMIN, rmax=tv.RMAX,
                out="pack.data", **tv.PACK)
    check_ok(r)
    pack = out / "pack" / "pack.data"
    rows = []
    for k, (label, V, gx, eta, S) in enumerate(CASES):
        d = out / f"case{k}"
        d.mkdir(exist_ok=True)
        r = run_lmp(f"include {tv.PARAMS}\n" + tv.CHANNEL, d, pack=pack, V=V, gx=gx, eta=eta,
                    S=S, nsteps=args.nsteps, timeout=3600)
        check_ok(r)
        c = tv.Channel(r, tv.PACK["H"], V=V, gx=gx, eta=eta, S=S)
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
