#!/usr/bin/env python3
"""SaltDEM scene benchmark driver (bench/performance/run-bench.sh calls it).

Runs bench/performance/bench_scene.in - the Expt 1 scene with the SaltDEM styles and the same packing with
stock gran/hooke/history, in one LAMMPS invocation - on 1 MPI rank, 2 MPI ranks and 1 rank with
2 OpenMP threads (and, on request, 4 MPI ranks: mpi4, and 2 ranks cut horizontally through the
salt and cover layers: mpi2y), and writes

  OUT/results.json   every run: atoms, steps, loop time, atom-steps/s (wall clock and per
                     CPU second of the process), LAMMPS's timing breakdown (Pair, Neigh, Comm,
                     Output, Modify, Other: % of the loop time, and min/avg/max seconds over the
                     ranks), the MPI processor grid, the ghost atom cutoff, Nlocal, Nghost and
                     Neighs (ave/max/min over the ranks), neighbour list builds, and whether
                     the run had fewer cores than ranks x threads (oversubscribed: its timings
                     are not speed, its counts are valid); ratios SaltDEM/stock per
                     configuration, speed-ups over 1 rank, the machine, and the projected wall
                     time of the full Expt 1 (--project-atoms discs, --project-steps steps).
                     bench/performance/scaling_model.py fits a strong-scaling model to these.
  OUT/results.txt    the same as a readable table
  OUT/logs/          the LAMMPS logs

The scene (restart file) and its packs are built once in OUT and reused.  A benchmark, not a
test: nothing here asserts a wall time.
"""
import argparse
import datetime
import json
import os
import pathlib
import platform
import re
import shutil
import subprocess
import sys

from saltdem_post.checkout import lmp_path

ROOT = pathlib.Path(__file__).resolve().parents[2]
SECTIONS = ("Pair", "Neigh", "Comm", "Output", "Modify", "Other")
CONFIGS = {
    "serial": dict(np=1, omp=0, label="1 rank, 1 thread"),
    "mpi2": dict(np=2, omp=0, label="2 MPI ranks"),
    "omp2": dict(np=1, omp=2, label="1 rank, 2 OpenMP threads"),
    # 4 ranks: on a machine with fewer cores oversubscribed - its counts (ghosts, pairs and
    # atoms per rank, processor grid) are valid, its timings are not speed
    "mpi4": dict(np=4, omp=0, label="4 MPI ranks"),
    # 2 ranks cut horizontally (processors 1 2 1): one rank holds the salt, the other cover only,
    # so that the Pair times of the two tell a salt disc's cost from a cover disc's
    "mpi2y": dict(np=2, omp=0, label="2 MPI ranks, processors 1 2 1", procgrid="1 2 1"),
}
# the histogram lines of the log's end-of-run statistics
COUNTS = ("Nlocal", "Nghost", "Neighs")


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--lmp", default=lmp_path(ROOT),
                   help="LAMMPS executable (default build/lmp or $SALTDEM_LMP)")
    p.add_argument("--out", default=str(ROOT / "out" / "bench"), help="output directory")
    p.add_argument("--preset", default="full",
                   help="examples/scene/params.in preset: full (the paper's discs) or tiny")
    p.add_argument("--strip", type=float, default=500, help="width of the packed strip (m)")
    p.add_argument("--ncopy", type=int, default=8, help="strips side by side (scene width)")
    p.add_argument("--nlayer", type=int, default=5, help="strips stacked (scene height)")
    p.add_argument("--salt", type=float, default=None, help="salt thickness (m; default 1000)")
    p.add_argument("--cover", type=float, default=None, help="cover thickness (m; default 1750)")
    p.add_argument("--nsettle", type=int, default=10000,
                   help="untimed settling steps before the timed runs")
    p.add_argument("--nwarm", type=int, default=500, help="untimed steps of each style first")
    p.add_argument("--nsteps", type=int, default=1000, help="timed steps per style")
    p.add_argument("--styles", default="saltdem stock", help="styles to run (saltdem, stock)")
    p.add_argument("--configs", default="serial,mpi2,omp2",
                   # mpi4, mpi2y on request: bench/performance/scaling_model.py wants serial,mpi2,mpi2y,mpi4
                   help="comma list of: " + ", ".join(CONFIGS))
    p.add_argument("--var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                   help="extra -var NAME VALUE for the deck (e.g. skin 2.5)")
    p.add_argument("--project-atoms", type=float, default=48256,
                   help="discs of the run to project (default: the full Expt 1 with its walls)")
    p.add_argument("--project-steps", type=float, default=3.26e6,
                   help="steps of the projected run (default: the full Expt 1 to 1000 m at the "
                        "full preset's step, 0.00623 s, with its 50,000 settling steps; the "
                        "paper's 0.002 s takes 1.0e7)")
    p.add_argument("--tag", default="", help="name added to the result files (results-TAG.*)")
    p.add_argument("--timeout", type=int, default=7200, help="seconds per LAMMPS invocation")
    return p.parse_args(argv)


def machine():
    """A short description of the machine the numbers come from."""
    cpu = platform.processor() or platform.machine()
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    info = dict(cpu=cpu, cores=os.cpu_count(), system=f"{platform.system()} {platform.release()}",
                python=platform.python_version())
    try:
        info["load_average_before"] = os.getloadavg()
    except OSError:
        pass
    try:
        mem = open("/proc/meminfo").readline().split()
        info["memory_GiB"] = round(int(mem[1]) / 2 ** 20, 1)
    except (OSError, IndexError, ValueError):
        pass
    return info


def lammps_version(lmp):
    try:
        out = subprocess.run([lmp, "-h"], capture_output=True, text=True, timeout=60).stdout
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    m = re.search(r"Large-scale Atomic/Molecular Massively Parallel Simulator - (.+)", out)
    return m.group(1).strip() if m else "unknown"


def parse_log(text):
    """Per timed run (between 'BENCH begin' and 'BENCH result'): the result line's numbers, the
    loop time and the breakdown of the 'MPI task timing breakdown' table (% of total)."""
    runs = []
    cur = None
    grid = cutghost = None
    lines = text.splitlines()
    for k, line in enumerate(lines):
        m = re.match(r"\s+(\d+) by (\d+) by (\d+) MPI processor grid", line)
        if m:
            grid = [int(g) for g in m.groups()]
        m = re.match(r"\s+ghost atom cutoff = ([0-9.eE+-]+)", line)
        if m:
            cutghost = float(m.group(1))
        if line.startswith("BENCH begin"):
            # the grid and cutoff the timed run was set up with: the last ones printed before it
            # (the warm-up run's setup, the same neighbour settings)
            cur = dict(style=line.split("style=")[1].strip(), breakdown={}, grid=grid,
                       ghost_cutoff=cutghost)
        elif cur is not None and line.startswith("Loop time of"):
            m = re.match(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms",
                         line)
            if m:
                cur.update(loop_seconds=float(m.group(1)), procs=int(m.group(2)),
                           steps=int(m.group(3)), atoms=int(m.group(4)))
        elif cur is not None and "% CPU use with" in line:
            # CPU time over wall time of the loop (per rank, summed over its threads): below
            # 100 % per thread when the machine is shared with other work
            cur["cpu_percent"] = float(line.split("%")[0])
        elif cur is not None and line.startswith("Section |"):
            for row in lines[k + 2:k + 2 + len(SECTIONS)]:
                s = [c.strip() for c in row.split("|")]
                if len(s) >= 6 and s[0] in SECTIONS:
                    d = dict(avg_seconds=float(s[2]), percent=float(s[5]))
                    if s[1] and s[3]:
                        # min and max over the ranks (LAMMPS leaves them out for Other)
                        d.update(min_seconds=float(s[1]), max_seconds=float(s[3]))
                        d["imbalance"] = d["max_seconds"] / d["avg_seconds"] \
                            if d["avg_seconds"] > 0 else None
                    cur["breakdown"][s[0]] = d
        elif cur is not None and line.split(":")[0] in COUNTS and " ave " in line:
            m = re.match(r"(\w+):\s+([0-9.eE+-]+) ave\s+([0-9.eE+-]+) max\s+([0-9.eE+-]+) min",
                         line)
            if m and m.group(1) not in cur.get("counts", {}):
                cur.setdefault("counts", {})[m.group(1)] = dict(
                    ave=float(m.group(2)), max=float(m.group(3)), min=float(m.group(4)))
        elif cur is not None and line.startswith("Total # of neighbors"):
            cur["neighbors_total"] = int(line.split("=")[1])
        elif cur is not None and line.startswith("Neighbor list builds"):
            cur["neighbor_builds"] = int(line.split("=")[1])
        elif cur is not None and line.startswith("Ave neighs/atom"):
            cur["neighbors_per_atom"] = float(line.split("=")[1])
        elif cur is not None and line.startswith("BENCH result"):
            kv = dict(w.split("=", 1) for w in line.split()[2:])
            cur["rate"] = float(kv["rate"])
            cur["timer_seconds"] = float(kv["seconds"])
            cpu = cur.get("cpu_percent", 0.0) / 100.0 * cur.get("loop_seconds", 0.0)
            # atom-steps per CPU second of one rank (all its threads): what the loop would
            # run at with its cores to itself, whatever else shares the machine
            cur["rate_cpu"] = cur["atoms"] * cur["steps"] / cpu if cpu > 0 else None
            pair = cur["breakdown"].get("Pair", {}).get("avg_seconds", 0.0)
            # atom-steps per second of pair-force time alone (without neighbour builds,
            # communication and fixes)
            cur["pair_rate"] = cur["atoms"] * cur["steps"] / pair if pair > 0 else None
            runs.append(cur)
            cur = None
    return runs


def run_config(args, name, cfg, outdir):
    """One invocation of the deck under a configuration; returns its runs."""
    logdir = outdir / "logs"
    logdir.mkdir(parents=True, exist_ok=True)
    log = logdir / f"{name}{'-' + args.tag if args.tag else ''}.log"
    cmd = [args.lmp, "-in", str(ROOT / "bench" / "performance" / "bench_scene.in"), "-log", str(log),
           "-echo", "none", "-screen", "none",
           "-var", "root", str(ROOT), "-var", "preset", args.preset,
           "-var", "strip", f"{args.strip:g}", "-var", "ncopy", str(args.ncopy),
           "-var", "nlayer", str(args.nlayer),
           "-var", "nsettle", str(args.nsettle), "-var", "nwarm", str(args.nwarm),
           "-var", "nsteps", str(args.nsteps),
           "-var", "styles", args.styles]
    if args.salt is not None:
        cmd += ["-var", "salt", f"{args.salt:g}"]
    if args.cover is not None:
        cmd += ["-var", "cover", f"{args.cover:g}"]
    for k, v in args.var:
        cmd += ["-var", k, v]
    if cfg.get("procgrid"):
        cmd += ["-var", "procgrid", cfg["procgrid"]]
    if cfg["omp"]:
        cmd += ["-sf", "omp", "-pk", "omp", str(cfg["omp"])]
    if cfg["np"] > 1:
        mpirun = shutil.which("mpirun")
        if mpirun is None:
            sys.exit("run_bench: mpirun not found (install openmpi-bin) or leave out mpi2")
        extra = ["--allow-run-as-root"] if os.geteuid() == 0 else []
        cmd = [mpirun, *extra, "--oversubscribe", "-np", str(cfg["np"]), *cmd]
    env = dict(os.environ, OMP_NUM_THREADS=str(cfg["omp"] or 1), OMP_WAIT_POLICY="passive")
    print(f"run_bench: {name} ({cfg['label']}) ...", flush=True)
    proc = subprocess.run(cmd, cwd=outdir, capture_output=True, text=True, env=env,
                          timeout=args.timeout)
    text = log.read_text() if log.exists() else ""
    if proc.returncode != 0:
        err = [l for l in (text + proc.stdout + proc.stderr).splitlines() if "ERROR" in l]
        sys.exit(f"run_bench: {name} failed (rc {proc.returncode}): "
                 f"{err[0] if err else (proc.stdout + proc.stderr)[-2000:]}\nlog: {log}")
    runs = parse_log(text)
    want = args.styles.split()
    if [r["style"] for r in runs] != want:
        sys.exit(f"run_bench: {name}: expected results for {want}, found "
                 f"{[r['style'] for r in runs]} in {log}")
    cores = os.cpu_count() or 1
    for r in runs:
        r.update(config=name, ranks=cfg["np"], threads=cfg["omp"] or 1)
        # more ranks x threads than cores: the counts stand, the timings are not speed
        r["oversubscribed"] = r["ranks"] * r["threads"] > cores
    return runs


def summarise(args, runs):
    by = {(r["config"], r["style"]): r for r in runs}
    configs = [c for c in CONFIGS if any(r["config"] == c for r in runs)]
    both = [c for c in configs if (c, "saltdem") in by and (c, "stock") in by]
    ratios = {c: by[(c, "saltdem")]["rate"] / by[(c, "stock")]["rate"] for c in both}
    cpu_ratios = {c: by[(c, "saltdem")]["rate_cpu"] / by[(c, "stock")]["rate_cpu"]
                  for c in both if by[(c, "saltdem")]["rate_cpu"] and by[(c, "stock")]["rate_cpu"]}
    pair_ratios = {c: by[(c, "saltdem")]["pair_rate"] / by[(c, "stock")]["pair_rate"]
                   for c in both if by[(c, "saltdem")]["pair_rate"] and by[(c, "stock")]["pair_rate"]}
    speedup = {}
    for style in args.styles.split():
        if ("serial", style) not in by:
            continue
        base = by[("serial", style)]["rate"]
        # (an oversubscribed configuration's speed-up is listed too, flagged in the runs: it
        # measures the shared cores, not the ranks)
        speedup[style] = {c: by[(c, style)]["rate"] / base for c in configs
                          if c != "serial" and (c, style) in by}
    projection = {}
    for (c, style), r in by.items():
        hours = args.project_atoms * args.project_steps / r["rate"] / 3600.0
        projection[f"{c}/{style}"] = dict(hours=hours, days=hours / 24.0)
        if c == "serial" and r.get("rate_cpu"):
            hours = args.project_atoms * args.project_steps / r["rate_cpu"] / 3600.0
            projection[f"serial-cpu/{style}"] = dict(hours=hours, days=hours / 24.0)
    oversubscribed = sorted({r["config"] for r in runs if r.get("oversubscribed")},
                            key=list(CONFIGS).index)
    return dict(oversubscribed=oversubscribed, ratio_saltdem_over_stock=ratios, cpu_ratio_saltdem_over_stock=cpu_ratios,
                pair_time_ratio_saltdem_over_stock=pair_ratios,
                speedup_over_serial=speedup,
                projection=dict(atoms=args.project_atoms, steps=args.project_steps,
                                wall_time=projection))


def table(result):
    out = []
    m = result["machine"]
    out.append(f"SaltDEM scene benchmark, {result['date']}")
    out.append(f"machine: {m['cpu']}, {m['cores']} cores, {m.get('memory_GiB', '?')} GiB, "
               f"{m['system']}; load average before: "
               + " ".join(f"{v:.2f}" for v in m.get("load_average_before", [])))
    out.append(f"LAMMPS {result['lammps']}; command: {result['command']}")
    out.append(f"scene: {result['scene']}")
    out.append("")
    hdr = (f"{'config':<8} {'style':<8} {'atoms':>7} {'steps':>6} {'loop s':>8} "
           f"{'atom-steps/s':>13} {'CPU %':>6} {'per CPU s':>10} "
           + " ".join(f"{s:>6}" for s in SECTIONS) + f" {'builds':>6}")
    out.append(hdr + "   (breakdown: % of loop time)")
    for r in result["runs"]:
        b = r["breakdown"]
        out.append(f"{r['config']:<8} {r['style']:<8} {r['atoms']:>7} {r['steps']:>6} "
                   f"{r['loop_seconds']:>8.3f} {r['rate']:>13.4g} "
                   f"{r.get('cpu_percent', float('nan')):>6.1f} {r.get('rate_cpu') or float('nan'):>10.4g} "
                   + " ".join(f"{b.get(s, {}).get('percent', float('nan')):>6.1f}" for s in SECTIONS)
                   + f" {r.get('neighbor_builds', -1):>6}"
                   + ("  OVERSUBSCRIBED" if r.get("oversubscribed") else ""))
    out.append("")
    out.append("per rank (ave / max / min over the ranks; imbalance = max / avg of the section's time):")
    out.append(f"{'config':<8} {'style':<8} {'grid':>7} {'cutghost':>8} {'Nlocal':>22} "
               f"{'Nghost':>20} {'Neighs':>26} {'Pair imb':>8} {'Comm s':>22}")
    nan = float("nan")
    for r in result["runs"]:
        c = r.get("counts", {})
        f = lambda k: "/".join(f"{c.get(k, {}).get(q, nan):.0f}" for q in ("ave", "max", "min"))
        g = "x".join(str(v) for v in (r.get("grid") or [])[:2]) or "?"
        cm = r["breakdown"].get("Comm", {})
        comm = "/".join(f"{cm.get(q, nan):.3g}" for q in ("min_seconds", "avg_seconds", "max_seconds"))
        out.append(f"{r['config']:<8} {r['style']:<8} {g:>7} {r.get('ghost_cutoff') or nan:>8.3g} "
                   f"{f('Nlocal'):>22} {f('Nghost'):>20} {f('Neighs'):>26} "
                   f"{r['breakdown'].get('Pair', {}).get('imbalance') or nan:>8.3f} {comm:>22}"
                   + ("  OVERSUBSCRIBED" if r.get("oversubscribed") else ""))
    if result["summary"].get("oversubscribed"):
        out.append("OVERSUBSCRIBED (" + ", ".join(result["summary"]["oversubscribed"])
                   + f"): more ranks x threads than the machine's {m['cores']} cores - the counts "
                   "are valid, the timings and speed-ups are not speed")
    out.append("")
    s = result["summary"]
    for c, v in s["ratio_saltdem_over_stock"].items():
        out.append(f"ratio saltdem/stock ({c}): {v:.3f} wall, "
                   f"{s['cpu_ratio_saltdem_over_stock'].get(c, float('nan')):.3f} per CPU second "
                   f"(pair time alone: {s['pair_time_ratio_saltdem_over_stock'].get(c, float('nan')):.3f})")
    for style, d in s["speedup_over_serial"].items():
        for c, v in d.items():
            over = " (oversubscribed: not speed)" if c in s.get("oversubscribed", []) else ""
            out.append(f"speed-up {style} {c} over serial: {v:.3f}{over}")
    p = s["projection"]
    out.append(f"projected wall time, {p['atoms']:.0f} discs x {p['steps']:.3g} steps "
               "(serial-cpu: at the rate per CPU second, i.e. on an idle core):")
    for k, v in p["wall_time"].items():
        out.append(f"  {k}: {v['hours']:.1f} h ({v['days']:.2f} days)")
    return "\n".join(out) + "\n"


def main(argv=None):
    args = parse_args(argv)
    outdir = pathlib.Path(args.out).resolve()
    outdir.mkdir(parents=True, exist_ok=True)
    if not os.path.isfile(args.lmp):
        sys.exit(f"run_bench: no LAMMPS executable at {args.lmp} (build it: scripts/build.sh)")
    configs = [c.strip() for c in args.configs.split(",") if c.strip()]
    for c in configs:
        if c not in CONFIGS:
            sys.exit(f"run_bench: unknown configuration '{c}' (expected {', '.join(CONFIGS)})")
    result = dict(date=datetime.datetime.now().isoformat(timespec="seconds"),
                  machine=machine(), lammps=lammps_version(args.lmp),
                  command=" ".join(["bench/performance/run-bench.sh", *(argv if argv is not None else sys.argv[1:])]),
                  scene=dict(preset=args.preset, strip=args.strip, ncopy=args.ncopy, nlayer=args.nlayer,
                             width=args.strip * args.ncopy, nsettle=args.nsettle, nwarm=args.nwarm,
                             nsteps=args.nsteps,
                             salt=args.salt, cover=args.cover, extra_vars=dict(args.var)),
                  runs=[])
    # the scene is built by the first invocation: on one rank, so that every configuration
    # starts from the same restart file
    order = sorted(configs, key=lambda c: c != "serial")
    for c in order:
        result["runs"] += run_config(args, c, CONFIGS[c], outdir)
    result["runs"].sort(key=lambda r: (list(CONFIGS).index(r["config"]), r["style"] != "saltdem"))
    result["summary"] = summarise(args, result["runs"])
    try:
        result["machine"]["load_average_after"] = os.getloadavg()
    except OSError:
        pass
    suffix = f"-{args.tag}" if args.tag else ""
    (outdir / f"results{suffix}.json").write_text(json.dumps(result, indent=1) + "\n")
    text = table(result)
    (outdir / f"results{suffix}.txt").write_text(text)
    print(text, end="")
    print(f"run_bench: results in {outdir / f'results{suffix}.json'} and .txt")
    return 0


if __name__ == "__main__":
    sys.exit(main())
