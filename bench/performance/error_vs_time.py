#!/usr/bin/env python3
"""Error against run time for the knobs that trade accuracy for speed.

Each knob is varied alone around the paper's salt (potentials/salt_paper.params: eta 5e8 Pa s,
discs 6.25-15.625 m, h 28 m, S 20, dt 0.002 s) in the channel flows of tests/decks/channel.in
(1000 m x 500 m, x periodic, no-slip wall bands of 2 rmax):

  plane Couette    top band at V = 1 m/s: error of the wall shear stress against eta V / H_ch and
                   RMS deviation of the salt's velocity profile from the analytic line
  plane Poiseuille body force g = 12 m/s^2: RMS deviation from the analytic parabola
                   rho g (y - y0)(y1 - y) / (2 eta), and its maximum

where H_ch is the distance between the band edges (the SPH boundary) and rho the salt's mass
per area.  Every run covers the same physical flow: 40 m of top-wall travel (Couette) or the
same physical time (Poiseuille), the deck's second half averaged (steps 3/4 to 4/4).

Knobs (docs/performance.md explains each):
  resolution  disc radii x f (pack made by tools/pack.in; h, band width with them; dt x f^2,
              the viscous stability limit scales so)
  dt          time step at S 20
  inertia     inertia factor S of fix saltdem/nve, dt x S/20 (the viscous limit scales so)
  speedup     drive velocity x k and viscosity / k (eta V constant), dt x k up to the elastic
              wall limit: the run reaches its displacement k times sooner
  skin        neighbour skin (the list is rebuilt as needed: no effect on the result)
  kernel      SPH smoothing length h: fewer neighbours within 2h, less work, a noisier sum

The cost is the CPU time of the LAMMPS process (on a busy machine the wall time of one run
says less), measured on the machine that runs the script.  Writes OUT/results.json,
OUT/table.md and, with --img DIR, one PNG per flow (error against CPU time, one line per knob).

  PYTHONPATH=python /usr/bin/python3 bench/performance/error_vs_time.py [--out out/error] [--img docs/img] [--knobs dt,inertia]

(from the repository root; PYTHONPATH=python imports the checkout's saltdem_post, not needed
once it is installed, see the README)
"""
import argparse
import json
import math
import os
import pathlib
import re
import resource
import subprocess
import sys
import time

import numpy as np

try:
    from saltdem_post.checkout import lmp_path
    from saltdem_post.dump import read_ave_chunk
except ImportError as exc:
    sys.exit(f"error_vs_time: {exc}: run with PYTHONPATH=python (from the repository root) or install "
             "the Python tools (pip install ./python)")

ROOT = pathlib.Path(__file__).resolve().parents[2]

CHANNEL = ROOT / "tests" / "decks" / "channel.in"
PARAMS = ROOT / "potentials" / "salt_paper.params"
PACK_IN = ROOT / "tools" / "pack.in"

RMIN, RMAX, H_SALT, ETA, S0, DT0, RHO = 6.25, 15.625, 28.0, 5e8, 20.0, 0.002, 2200.0
W, H = 1000.0, 500.0
TRAVEL = 40.0            # m of Couette top-wall travel (the test suite's 2 x 10,000 steps at 1 m/s)
G_POIS = 12.0            # m/s^2, Poiseuille body force
T_POIS = 40.0            # s of Poiseuille flow (the test suite's 2 x 10,000 steps of 0.002 s)
DT_MAX_WALL = 0.006      # s: the salt-wall contact limit 0.2 sqrt(S m / kn) is 0.0064 s at S 20

KNOBS = {
    "resolution": dict(label="disc size f (radii x f, dt x f^2)", values=[2.0, 1.5, 1.0, 0.75],
                       default=1.0),
    "dt": dict(label="time step dt (s), S 20", values=[0.003, 0.002, 0.001, 0.0005], default=0.002),
    "inertia": dict(label="inertia factor S (dt x S/20)", values=[80.0, 40.0, 20.0, 10.0, 5.0],
                    default=20.0),
    "speedup": dict(label="speed-up k (V x k, eta / k)", values=[8.0, 4.0, 2.0, 1.0], default=1.0),
    "skin": dict(label="neighbour skin (m)", values=[0.7, 2.8, 8.4, 28.0], default=2.8),
    "kernel": dict(label="SPH smoothing length h (m; 2h holds ~21 discs at 28 m)",
                   values=[28.0, 25.0, 23.0], default=28.0),
}


def settings(knob, value):
    """Deck settings of one run: radius factor f, dt, S, k, skin."""
    s = dict(f=1.0, dt=DT0, S=S0, k=1.0, skin=0.1 * H_SALT, h=H_SALT)
    if knob == "resolution":
        s.update(f=value, dt=DT0 * value ** 2, skin=0.1 * H_SALT * value, h=H_SALT * value)
    elif knob == "dt":
        s.update(dt=value)
    elif knob == "inertia":
        s.update(S=value, dt=min(DT0 * value / S0, DT_MAX_WALL * math.sqrt(value / S0)))
    elif knob == "speedup":
        s.update(k=value, dt=min(DT0 * value, DT_MAX_WALL))
    elif knob == "skin":
        s.update(skin=value)
    elif knob == "kernel":
        s.update(h=value)
    return s


def run_lmp(deck_args, cwd, timeout=3600):
    """Run lmp; returns (stdout, cpu seconds of the child, wall seconds)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    p = subprocess.run([lmp_path(ROOT), *deck_args], cwd=cwd, capture_output=True, text=True,
                       timeout=timeout, env=dict(os.environ, OMP_NUM_THREADS="1"))
    wall = time.time() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if p.returncode != 0:
        log = pathlib.Path(cwd) / "log.lammps"
        text = p.stdout + p.stderr + (log.read_text() if log.exists() else "")
        err = [l for l in text.splitlines() if "ERROR" in l]
        raise RuntimeError(f"lmp {' '.join(deck_args)} failed: {err[:1] or p.stdout[-1500:]}")
    return p.stdout, cpu, wall


def pack_for(f, work):
    """The channel pack of disc size f (made once)."""
    path = work / f"pack_f{f:g}.data"
    if not path.exists():
        run_lmp(["-in", str(PACK_IN), "-log", "none", "-echo", "none", "-screen", "none",
                 "-var", "W", f"{W:g}", "-var", "H", f"{H:g}", "-var", "rmin", f"{RMIN * f:g}",
                 "-var", "rmax", f"{RMAX * f:g}", "-var", "seed", "7", "-var", "out", str(path)],
                work)
    return path


def read_profile(path):
    """Blocks of the deck's channel_profile.txt (fix ave/chunk): list of arrays (y, count, vx)."""
    return [b[:, 1:] for b in read_ave_chunk(path)]


def channel_run(flow, s, work, tag):
    """One channel run; returns the measured errors and the cost."""
    f = s["f"]
    rmax = RMAX * f
    d = work / tag
    d.mkdir(parents=True, exist_ok=True)
    V = s["k"] * 1.0 if flow == "couette" else 0.0
    gx = G_POIS if flow == "poiseuille" else 0.0
    eta = ETA / s["k"]
    t_phys = TRAVEL / V if flow == "couette" else T_POIS / s["k"]
    # the deck averages every 10 steps over nsteps/20 samples: nsteps a multiple of 200
    nsteps = max(200 * int(round(0.5 * t_phys / s["dt"] / 200)), 200)
    deck = d / "in.channel"
    deck.write_text(f"include {PARAMS}\n" + CHANNEL.read_text().replace(
        "neighbor        $(0.1*v_h) bin", "neighbor        ${skin} bin"))
    args = ["-in", str(deck), "-log", "log.lammps", "-echo", "none", "-screen", "none"]
    for k, v in dict(pack=pack_for(f, work), eta=eta, V=V, gx=gx, S=s["S"], dt=s["dt"],
                     nsteps=nsteps, rmax=rmax, h=s["h"], skin=s["skin"]).items():
        args += ["-var", k, str(v)]
    out, cpu, wall = run_lmp(args, d)
    log = (d / "log.lammps").read_text()
    natoms = int(re.search(r"Loop time of \S+ on \d+ procs for \d+ steps with (\d+) atoms", log).group(1))
    builds = sum(int(v) for v in re.findall(r"Neighbor list builds = (\d+)", log))
    rhob = float(re.search(r"salt mass per area: ([0-9.eE+-]+)", log).group(1))
    y, n, vx = read_profile(d / "channel_profile.txt")[-1].T
    y0, y1 = 2 * rmax, H - 2 * rmax                     # band edges: the SPH boundary
    hch = y1 - y0
    inner = (y > y0 + 3 * rmax) & (y < y1 - 3 * rmax) & (n > 0)
    res = dict(flow=flow, atoms=natoms, steps=2 * nsteps, cpu_s=cpu, wall_s=wall,
               neighbor_builds=builds, reynolds=None)
    if flow == "couette":
        taus = [float(l.split()[1]) for l in (d / "channel_stress.txt").read_text().splitlines()
                if l.strip() and not l.startswith("#")]
        tau_exact = eta * V / hch
        exact = V * (y - y0) / hch
        res.update(stress_error=taus[-1] / tau_exact - 1.0,
                   profile_rms=float(np.sqrt(np.mean((vx[inner] - exact[inner]) ** 2))) / V,
                   reynolds=RHO * s["S"] * V * hch / eta)
        res["error"] = max(abs(res["stress_error"]), res["profile_rms"])
    else:
        exact = rhob * gx * (y - y0) * (y1 - y) / (2.0 * eta)
        umax = rhob * gx * hch ** 2 / (8.0 * eta)
        p = np.polyfit(y[inner], vx[inner], 2)
        vmax = p[2] - p[1] ** 2 / (4 * p[0])
        res.update(profile_rms=float(np.sqrt(np.mean((vx[inner] - exact[inner]) ** 2))) / umax,
                   vmax_error=vmax / umax - 1.0, reynolds=RHO * s["S"] * umax * hch / eta)
        res["error"] = max(abs(res["vmax_error"]), res["profile_rms"])
    return res


def plot(results, path, flow, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=100)
    for knob, spec in KNOBS.items():
        rows = [r for r in results if r["knob"] == knob and r["flow"] == flow]
        if not rows:
            continue
        rows.sort(key=lambda r: r["cpu_s"])
        x = [r["cpu_s"] for r in rows]
        e = [100 * r["error"] for r in rows]
        ax.plot(x, e, "o-", label=spec["label"])
        for r, xi, ei in zip(rows, x, e):
            ax.annotate(f"{r['value']:g}", (xi, ei), textcoords="offset points", xytext=(3, 3),
                        fontsize=7)
    for level in (1, 5, 10):
        ax.axhline(level, color="0.6", lw=0.6, ls="--")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU time of the run (s, one core)")
    ax.set_ylabel("error (%)")
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def table(results):
    lines = ["| knob | value | flow | discs | steps | CPU s | Re | stress or v_max error | "
             "profile RMS error | error |", "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in results:
        main = r.get("stress_error", r.get("vmax_error"))
        lines.append(f"| {r['knob']} | {r['value']:g} | {r['flow']} | {r['atoms']} | {r['steps']} | "
                     f"{r['cpu_s']:.1f} | {r['reynolds']:.3g} | {100 * main:+.2f} % | "
                     f"{100 * r['profile_rms']:.2f} % | {100 * r['error']:.2f} % |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(ROOT / "out" / "error"))
    ap.add_argument("--img", default=None, help="write the PNG plots here (e.g. docs/img)")
    ap.add_argument("--knobs", default=",".join(KNOBS))
    ap.add_argument("--flows", default="couette,poiseuille")
    ap.add_argument("--redo", action="store_true", help="run again what results.json holds")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    store = out / "results.json"
    results = json.loads(store.read_text())["runs"] if store.exists() and not args.redo else []
    done = {(r["knob"], r["value"], r["flow"]) for r in results}
    for knob in args.knobs.split(","):
        for value in KNOBS[knob]["values"]:
            for flow in args.flows.split(","):
                if (knob, value, flow) in done:
                    continue
                s = settings(knob, value)
                tag = f"{flow}_{knob}_{value:g}"
                print(f"error_vs_time: {tag} {s} ...", flush=True)
                r = channel_run(flow, s, out, tag)
                r.update(knob=knob, value=value, settings=s)
                results.append(r)
                store.write_text(json.dumps(dict(runs=results), indent=1) + "\n")
                print(f"  error {100 * r['error']:.2f} %, CPU {r['cpu_s']:.1f} s", flush=True)
    order = {k: n for n, k in enumerate(KNOBS)}
    results.sort(key=lambda r: (order[r["knob"]], r["flow"], -r["cpu_s"]))
    store.write_text(json.dumps(dict(runs=results), indent=1) + "\n")
    (out / "table.md").write_text(table(results))
    if args.img:
        img = pathlib.Path(args.img)
        img.mkdir(parents=True, exist_ok=True)
        plot(results, img / "error_vs_time_couette.png", "couette",
             "Couette (V 1 m/s, 40 m of wall travel): error vs CPU time")
        plot(results, img / "error_vs_time_poiseuille.png", "poiseuille",
             "Poiseuille (g 12 m/s^2, 40 s): error vs CPU time")
    print(table(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
