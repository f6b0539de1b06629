#!/usr/bin/env python3
"""Error against run time of a quick Expt 1 (the scene of examples/expt1.in, preset quick,
shortened to --target m of fault displacement; bench/performance/expt1_knob.in) for the knobs that speed a
scene run up, each against a slower, more accurate reference run of the same scene.  All runs
settle alike and change the knob when the faulting starts:

  speedup  drive rate x k and salt viscosity / k (eta V constant, as the paper's scaling keeps
           the stresses): k = 1 (the quick preset), 2, 4 against k = 0.5
  dt       time step 0.0025 s (the quick preset) against 0.00125 s, the same drive rate

Measures, all of what happened during the faulting (from each run's own frame at displacement
0 to its last frame, so that small differences of the settled states cancel), on cells of
250 m (about five quick disc diameters):
  thickness  change of the salt thickness profile (python/saltdem_post salt_thickness), RMS
             difference from the reference over the salt thickness
  marker     mean displacement of the cover and salt discs (the markers) per cell, RMS
             difference from the reference over the fault displacement
  strain     mean incremental maximum shear strain (strain_between) per cell, RMS difference
             over the reference's RMS

A control pair - the k = 1 run on one thread and on two OpenMP threads, which differ by
round-off only - gives the floor: the granular cover turns round-off into a different, equally
valid run, and no knob's error below that floor is meaningful.

Cost: CPU time of the whole LAMMPS run (assembly, settling and faulting; the pack of the
assembly is made once beforehand).  Writes OUT/expt1.json,
OUT/expt1_table.md and, with --img DIR, DIR/error_vs_time_expt1.png.

  PYTHONPATH=python /usr/bin/python3 bench/performance/expt1_error.py [--out out/error] [--img docs/img] [--target 50]

(from the repository root; PYTHONPATH=python imports the checkout's saltdem_post, not needed
once it is installed, see the README)
"""
import argparse
import json
import os
import pathlib
import resource
import subprocess
import sys
import time

import numpy as np

try:
    from saltdem_post.checkout import lmp_path
    from saltdem_post.dump import match_ids, read_frame
    from saltdem_post.measure import salt_thickness
    from saltdem_post.strain import strain_between
except ImportError as exc:
    sys.exit(f"expt1_error: {exc}: run with PYTHONPATH=python (from the repository root) or install "
             "the Python tools (pip install ./python)")

ROOT = pathlib.Path(__file__).resolve().parents[2]

QUICK = dict(dt=0.0025, dstep=0.00125, eta=5e8)    # examples/scene/params.in, preset quick
SALT = 1000.0                                     # m, the scene's salt thickness

CELL = 250.0             # m: fields are compared as means over cells of this size (about 5 quick
                         # disc diameters), which keeps what the figures show and averages out
                         # the motion of single discs

RUNS = {
    # name: (k, dt factor, OpenMP threads); dstep = rate x dt, rate = 0.5 m/s x k
    "k0.5": (0.5, 1.0, 0),
    "k1": (1.0, 1.0, 0),
    "k2": (2.0, 1.0, 0),
    "k4": (4.0, 1.0, 0),
    "dt0.5": (1.0, 0.5, 0),
    "k1-omp2": (1.0, 1.0, 2),
}
# the control: k1 on two OpenMP threads differs from k1 by round-off only; the granular cover
# amplifies it into a different but equally valid run, and the difference is the floor below
# which no knob's error can be told apart
COMPARE = [("control", "k1", ["k1-omp2"]), ("speedup", "k0.5", ["k1", "k2", "k4"]),
           ("dt", "dt0.5", ["k1"])]


def run(name, k, dtf, target, nsettle, work, omp=0):
    d = work / f"expt1_{name}"
    d.mkdir(parents=True, exist_ok=True)
    done = d / "done.json"
    if done.exists():
        return json.loads(done.read_text())
    dt = QUICK["dt"] * dtf
    args = [lmp_path(ROOT), "-in", str(ROOT / "bench" / "performance" / "expt1_knob.in"), "-log", "log.lammps",
            "-echo", "none", "-screen", "none", "-var", "root", str(ROOT), "-var", "preset", "quick",
            "-var", "target", f"{target:g}", "-var", "f", f"{target / 2:g}", f"{target:g}",
            "-var", "nsettle", str(nsettle), "-var", "k", f"{k:g}", "-var", "dtf", f"{dtf:g}",
            "-var", "packfile", str(work / "expt1_quick_pack.data")]
    if omp:
        args += ["-sf", "omp", "-pk", "omp", str(omp)]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    p = subprocess.run(args, cwd=d, capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS=str(omp or 1), OMP_WAIT_POLICY="passive"))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        log = (d / "log.lammps").read_text() if (d / "log.lammps").exists() else ""
        err = [l for l in (p.stdout + log).splitlines() if "ERROR" in l]
        raise RuntimeError(f"expt1 {name} failed: {err[:1] or log[-1500:]}")
    dumps = sorted(d.glob("dump.expt1.*.txt"), key=lambda q: int(q.name.split(".")[2]))
    res = dict(name=name, k=k, dt=dt, cpu_s=(after.ru_utime - before.ru_utime)
               + (after.ru_stime - before.ru_stime), wall_s=time.time() - t0,
               first=str(dumps[0]), last=str(dumps[-1]))
    done.write_text(json.dumps(res) + "\n")
    return res


def cell_means(xy, values, x0, y0, nx, ny):
    """Mean of values (n or n x m) over the discs whose position xy falls in each cell."""
    ix = np.clip(((xy[:, 0] - x0) // CELL).astype(int), 0, nx - 1)
    iy = np.clip(((xy[:, 1] - y0) // CELL).astype(int), 0, ny - 1)
    cell = ix * ny + iy
    v = values.reshape(len(values), -1)
    count = np.bincount(cell, minlength=nx * ny).astype(float)
    sums = np.stack([np.bincount(cell, weights=v[:, c], minlength=nx * ny) for c in range(v.shape[1])], 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return sums / count[:, None], count


def fields(res):
    """Faulting-stage fields of one run on a fixed grid of CELL x CELL cells (by the discs'
    positions at displacement 0): salt thickness change per column, mean displacement and
    mean incremental maximum shear strain of the cover and salt discs per cell; and the mean
    horizontal displacement of the cover's discs (glide, m)."""
    a, b = read_frame(res["first"]), read_frame(res["last"])
    x0, x1, y0, y1 = 0.0, 6250.0, -250.0, 3000.0
    nx, ny = int(round((x1 - x0) / CELL)), int(round((y1 - y0) / CELL))
    th0 = salt_thickness(a, bin_width=CELL, x_range=(x0, x1))
    th1 = salt_thickness(b, bin_width=CELL, x_range=(x0, x1))
    ia, ib = match_ids(a.ids, b.ids)
    mobile = np.isin(a["type"][ia], (1, 2))
    xy0 = a.xy[ia][mobile]
    disp, count = cell_means(xy0, (b.xy[ib] - a.xy[ia])[mobile], x0, y0, nx, ny)
    strain = strain_between(a, b)
    sa, _ = match_ids(strain.ids, a.ids[ia][mobile])
    ok = np.isfinite(strain.max_shear[sa])
    shear, _ = cell_means(strain.ref_xy[sa][ok], strain.max_shear[sa][ok], x0, y0, nx, ny)
    full = count >= 3
    # the cover's glide on the salt: the mean horizontal displacement of its discs (type 1)
    cover = a["type"][ia] == 1
    glide = float((b.xy[ib][cover, 0] - a.xy[ia][cover, 0]).mean())
    return dict(dth=th1.thickness - th0.thickness, disp=disp, shear=shear[:, 0], full=full,
                glide=glide)


def compare(ref, run, fault):
    """Relative RMS differences of the three fields over the cells both runs fill."""
    dth = run["dth"] - ref["dth"]
    thickness = float(np.sqrt(np.nanmean(dth ** 2))) / SALT
    both = ref["full"] & run["full"]
    d = run["disp"][both] - ref["disp"][both]
    marker = float(np.sqrt(np.mean(np.sum(d ** 2, axis=1)))) / fault
    e_ref, e_run = ref["shear"][both], run["shear"][both]
    strain = float(np.sqrt(np.mean((e_run - e_ref) ** 2) / np.mean(e_ref ** 2)))
    return dict(thickness=thickness, marker=marker, strain=strain)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(ROOT / "out" / "error"))
    ap.add_argument("--img", default=None)
    ap.add_argument("--target", type=float, default=50.0, help="fault displacement (m)")
    ap.add_argument("--nsettle", type=int, default=6000, help="settling steps at dt 0.0025 s")
    args = ap.parse_args(argv)
    work = pathlib.Path(args.out).resolve()
    work.mkdir(parents=True, exist_ok=True)
    results = {}
    if not (work / "expt1_quick_pack.data").exists():
        # the assembly's pack is made once (minutes), outside the timed runs
        print("expt1_error: making the quick pack ...", flush=True)
        run("pack", 1.0, 1.0, 1.0, 10, work)
    # the quick preset's pack of examples/expt1.in, if there is one: the same assembly
    for name, (k, dtf, omp) in RUNS.items():
        print(f"expt1_error: run {name} (k {k}, dt x {dtf}) ...", flush=True)
        results[name] = run(name, k, dtf, args.target, args.nsettle, work, omp)
        print(f"  CPU {results[name]['cpu_s']:.1f} s", flush=True)
    f = {name: fields(r) for name, r in results.items()}
    rows = []
    for knob, ref, names in COMPARE:
        for name in names:
            e = compare(f[ref], f[name], args.target)
            rows.append(dict(knob=knob, run=name, reference=ref, cpu_s=results[name]["cpu_s"],
                             ref_cpu_s=results[ref]["cpu_s"], k=results[name]["k"],
                             dt=results[name]["dt"], **e))
    (work / "expt1.json").write_text(json.dumps(dict(target=args.target, runs=results,
                                                     errors=rows), indent=1) + "\n")
    lines = ["| knob | run | reference | CPU s (reference) | thickness | marker displacement | "
             "incremental strain |", "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        lines.append(f"| {r['knob']} | {r['run']} (k {r['k']:g}, dt {r['dt']:g} s) | {r['reference']} | "
                     f"{r['cpu_s']:.0f} ({r['ref_cpu_s']:.0f}) | {100 * r['thickness']:.2f} % | "
                     f"{100 * r['marker']:.2f} % | {100 * r['strain']:.1f} % |")
    table = "\n".join(lines) + "\n"
    (work / "expt1_table.md").write_text(table)
    print(table)
    if args.img:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
        sp = [r for r in rows if r["knob"] == "speedup"]
        floor = [r for r in rows if r["knob"] == "control"]
        for key, label, mk in (("thickness", "salt thickness change", "o"),
                               ("marker", "marker displacement", "s"),
                               ("strain", "incremental max shear strain", "^")):
            line, = ax.plot([r["cpu_s"] for r in sp], [100 * r[key] for r in sp], mk + "-",
                            label=label)
            if floor:
                ax.axhline(100 * floor[0][key], color=line.get_color(), lw=0.8, ls=":")
            for r in sp:
                ax.annotate(f"k {r['k']:g}", (r["cpu_s"], 100 * r[key]), textcoords="offset points",
                            xytext=(3, 3), fontsize=7)
        for level in (1, 5, 10):
            ax.axhline(level, color="0.6", lw=0.6, ls="--")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("CPU time of the run (s, one core)")
        ax.set_ylabel("difference from the k = 0.5 run (%)")
        ax.text(0.98, 0.02, "dotted: k 1 on 2 threads against k 1 (round-off only)",
                transform=ax.transAxes, fontsize=7, ha="right")
        ax.set_title(f"quick Expt 1 to {args.target:g} m: speed-up k (rate x k, eta / k)",
                     fontsize=10)
        ax.legend(fontsize=7, loc="center left")
        fig.tight_layout()
        img = pathlib.Path(args.img)
        img.mkdir(parents=True, exist_ok=True)
        fig.savefig(img / "error_vs_time_expt1.png")
        plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
