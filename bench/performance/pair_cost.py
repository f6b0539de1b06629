#!/usr/bin/env python3
"""Time per interacting pair of each pair style, side by side in one LAMMPS run.

bench/performance/bench_pair.in runs one settled 2D pack (tools/pack.in, the paper's disc radii) under
gravity with stock gran/hooke/history, saltdem/cohesive, saltdem/viscous (the SPH salt) and
saltdem/viscous with 2 viscous sub-steps (the full preset's), one after the other in the same
invocation, and counts each style's interacting pairs at the end: touching pairs for the
granular styles (compute contact/atom), pairs within the kernel's 2h = 56 m for the salt
(compute coord/atom).  The cost per pair is the run's Pair time (LAMMPS's breakdown, which for
the salt includes its kernel-moment and density passes and the sub-steps) over steps x pairs.

  PYTHONPATH=python python3 bench/performance/pair_cost.py [--lmp build/lmp] [--work out/pair_cost] [--nsteps 2000]
        [--W 800 --H 750] [--D 200] [--styles hooke,cohesive,viscous,viscous2] [--json FILE]

--D DEPTH: the same in 3D, a sphere pack DEPTH m deep along z (stiffnesses x rmin + rmax as the
3D scenes, the kernel 1.3 sphere spacings).
"""
import argparse
import json
import math
import pathlib
import re
import subprocess
import sys

from saltdem_post.checkout import lmp_path, make_pack

ROOT = pathlib.Path(__file__).resolve().parents[2]

LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps")
PAIR = re.compile(r"^Pair\s+\|\s*(\S+)\s*\|\s*(\S+)\s*\|\s*(\S+)")
RATE = re.compile(r"^BENCH (\S+): (\d+) atoms, (\S+) atom-steps/s")
PAIRS = re.compile(r"^BENCH (\S+) pairs (\S+) steps (\d+)")


def parse(text):
    """Per style: atoms, steps, loop and Pair time of its timed run, interacting pairs."""
    out, loop, pair = {}, None, None
    for line in text.splitlines():
        m = LOOP.match(line)
        if m:
            loop = (float(m.group(1)), int(m.group(3))) if int(m.group(3)) > 0 else loop
            continue
        m = PAIR.match(line)
        if m and loop is not None:
            pair = float(m.group(2))
            continue
        m = RATE.match(line)
        if m:
            out[m.group(1)] = dict(atoms=int(m.group(2)), rate=float(m.group(3)))
            continue
        m = PAIRS.match(line)
        if m:
            s = out[m.group(1)]
            steps = int(m.group(3))
            if loop is None or pair is None or loop[1] != steps:
                raise ValueError(f"no timed run of {steps} steps before the pairs of {m.group(1)}")
            npair = float(m.group(2))
            s.update(steps=steps, loop_s=loop[0], pair_s=pair, pairs=npair,
                     pairs_per_atom=2 * npair / s["atoms"],
                     ns_per_pair=1e9 * pair / (steps * npair) if npair > 0 else float("nan"))
            loop = pair = None
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lmp", default=lmp_path(ROOT))
    ap.add_argument("--work", default=str(ROOT / "out" / "pair_cost"))
    ap.add_argument("--nsteps", type=int, default=2000)
    ap.add_argument("--W", type=float, default=800.0)
    ap.add_argument("--H", type=float, default=750.0)
    ap.add_argument("--D", type=float, help="3D: a sphere pack this deep along z (m)")
    ap.add_argument("--styles", default="hooke,cohesive,viscous,viscous2")
    ap.add_argument("--json")
    args = ap.parse_args()
    if args.nsteps < 1:
        ap.error("--nsteps must be >= 1")
    work = pathlib.Path(args.work).resolve()
    lmp = str(pathlib.Path(args.lmp).resolve())
    pack = make_pack(lmp, work / "packs", args.W, args.H, 6.25, 15.625, D=args.D)
    styles = args.styles.replace(",", " ")
    dim = []
    if args.D:
        # the kernel of the 3D scenes: 1.3 spacings of spheres of the pack's mean volume (0.62)
        text = pack.read_text()
        rows = text.split("Atoms")[1].split("Velocities")[0].split("\n")
        d = [float(r.split()[2]) for r in rows if len(r.split()) >= 7]
        v = sum(math.pi / 6 * x ** 3 for x in d) / len(d)
        dim = ["-var", "dim", "3", "-var", "zthick", str(6.25 + 15.625),
               "-var", "h3", f"{1.3 * (v / 0.62) ** (1 / 3):.4f}"]
    subprocess.run([lmp, "-in", str(ROOT / "bench" / "performance" / "bench_pair.in"), "-log", "log.lammps",
                    "-screen", "none", "-nocite", "-var", "pack", str(pack), "-var", "nsteps",
                    str(args.nsteps), "-var", "styles", styles, *dim], cwd=work, check=True)
    res = parse((work / "log.lammps").read_text())
    missing = [s for s in styles.split() if s not in res or "ns_per_pair" not in res[s]]
    if missing:
        sys.exit(f"pair_cost: no result for {missing} in {work / 'log.lammps'}")
    ref = res.get("hooke")
    print(f"{'style':10s} {'atoms':>6s} {'pairs/atom':>10s} {'Pair s':>8s} {'ns/pair':>8s} "
          f"{'vs stock':>8s} {'atom-steps/s':>12s}")
    for name, s in res.items():
        rel = s["ns_per_pair"] / ref["ns_per_pair"] if ref else float("nan")
        s["vs_stock"] = rel
        print(f"{name:10s} {s['atoms']:6d} {s['pairs_per_atom']:10.2f} {s['pair_s']:8.3f} "
              f"{s['ns_per_pair']:8.1f} {rel:8.2f} {s['rate']:12.4g}")
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
