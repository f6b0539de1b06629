#!/usr/bin/env python3
"""Check that a change to the SaltDEM styles leaves trajectories unchanged.

  check_trajectories.py record DIR     run the checks, keep their final dumps in DIR
  check_trajectories.py compare DIR    run them again and compare with DIR: the largest
                                       position difference over the box width must stay below
                                       --tol (default 1e-10), velocities below --vtol m/s

The checks: bench/regression/trajectory.in with the cohesive law (cohesion, tension, rolling, sliding),
the fluid law (Newtonian and frictional-viscous) and the contact law of saltdem/viscous (500 steps each on a dense pack made once
by tools/pack.in), and the Expt 1 benchmark scene (bench/performance/bench_scene.in, hybrid of both styles,
a moving hanging wall) on one thread and with the OpenMP styles on two, and fix saltdem/sediment
(bench/regression/sediment.in: deposition at a rate and to a base level, erosion, settling, a
restart in the middle, and the rate case on two MPI ranks).  Every run is deterministic, so an
optimisation that only drops exact zeros reproduces the dumps bit for bit; one that reorders
arithmetic moves them by round-off.

From the repository root: PYTHONPATH=python /usr/bin/python3 bench/regression/check_trajectories.py ...
"""
import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

from saltdem_post.checkout import lmp_path

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHECKS = {
    "cohesive": dict(deck="bench/regression/trajectory.in", vars=dict(law="cohesive"), dump="traj_cohesive.dump"),
    "fluid": dict(deck="bench/regression/trajectory.in", vars=dict(law="fluid"), dump="traj_fluid.dump"),
    "plastic": dict(deck="bench/regression/trajectory.in", vars=dict(law="plastic"), dump="traj_plastic.dump"),
    "contact": dict(deck="bench/regression/trajectory.in", vars=dict(law="contact"), dump="traj_contact.dump"),
    "scene": dict(deck="bench/performance/bench_scene.in", dump="bench_final.dump",
                  vars=dict(strip=500, ncopy=2, nlayer=5, nsettle=300, nwarm=0, nsteps=500,
                            styles="saltdem", dump=1)),
    "scene-omp2": dict(deck="bench/performance/bench_scene.in", dump="bench_final.dump", omp=2,
                       vars=dict(strip=500, ncopy=2, nlayer=5, nsettle=300, nwarm=0, nsteps=500,
                                 styles="saltdem", dump=1)),
    "sediment-rate": dict(deck="bench/regression/sediment.in", vars=dict(case="rate"),
                          dump="sediment_rate.dump"),
    "sediment-fill": dict(deck="bench/regression/sediment.in", vars=dict(case="fill"),
                          dump="sediment_fill.dump"),
    "sediment-restart": dict(deck="bench/regression/sediment.in", vars=dict(case="restart"),
                             dump="sediment_restart.dump"),
    "sediment-np2": dict(deck="bench/regression/sediment.in", vars=dict(case="rate"), np=2,
                         dump="sediment_rate.dump"),
}


def run(cmd, cwd, omp=0):
    env = dict(os.environ, OMP_NUM_THREADS=str(omp or 1), OMP_WAIT_POLICY="passive")
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        sys.exit(f"check_trajectories: {' '.join(cmd)} failed:\n{(p.stdout + p.stderr)[-3000:]}")
    return p.stdout


def ensure_pack(cache):
    pack = cache / "traj_pack.data"
    if not pack.exists():
        run([lmp_path(ROOT), "-in", str(ROOT / "tools" / "pack.in"), "-log", "none", "-echo", "none",
             "-screen", "none", "-var", "W", "1000", "-var", "H", "500", "-var", "rmin", "6.25",
             "-var", "rmax", "15.625", "-var", "seed", "7", "-var", "kn", "1e10",
             "-var", "out", str(pack)], cache)
    return pack


def run_check(name, wd, cache):
    c = CHECKS[name]
    cmd = [lmp_path(ROOT), "-in", str(ROOT / c["deck"]), "-log", "log." + name, "-echo", "none",
           "-screen", "none", "-var", "root", str(ROOT)]
    if "trajectory" in c["deck"]:
        cmd += ["-var", "pack", str(ensure_pack(cache))]
    for k, v in c["vars"].items():
        cmd += ["-var", k, str(v)]
    if c.get("omp"):
        cmd += ["-sf", "omp", "-pk", "omp", str(c["omp"])]
    if c.get("np"):
        mpirun = shutil.which("mpirun") or sys.exit("check_trajectories: mpirun not found")
        root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
        cmd = [mpirun, *root, "--oversubscribe", "-np", str(c["np"]), *cmd]
    # the scene's packs are made once in the cache and found there
    for f in cache.glob("bench_*.data"):
        if not (wd / f.name).exists():
            os.symlink(f, wd / f.name)
    run(cmd, wd, c.get("omp", 0))
    for f in wd.glob("bench_*.data"):
        if not f.is_symlink() and not (cache / f.name).exists():
            shutil.copy(f, cache / f.name)
    return wd / c["dump"]


def read_dump(path):
    lines = path.read_text().splitlines()
    box = [list(map(float, lines[k].split()[:2])) for k in (5, 6)]
    rows = {}
    for line in lines[9:]:
        s = line.split()
        if s:
            rows[int(s[0])] = [float(v) for v in s[1:]]
    return rows, box


def compare(a_path, b_path):
    a, box = read_dump(a_path)
    b, _ = read_dump(b_path)
    if a.keys() != b.keys():
        return float("inf"), float("inf")
    width = max(box[0][1] - box[0][0], box[1][1] - box[1][0])
    dx = max(abs(a[i][k] - b[i][k]) for i in a for k in (0, 1)) / width
    dv = max(abs(a[i][k] - b[i][k]) for i in a for k in (2, 3))
    return dx, dv


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("mode", choices=["record", "compare"])
    p.add_argument("dir", help="reference directory")
    p.add_argument("--only", default=",".join(CHECKS), help="comma list of checks")
    p.add_argument("--tol", type=float, default=1e-10, help="largest position change / box width")
    p.add_argument("--vtol", type=float, default=1e-8, help="largest velocity change (m/s)")
    args = p.parse_args(argv)
    ref = pathlib.Path(args.dir).resolve()
    ref.mkdir(parents=True, exist_ok=True)
    names = [n for n in args.only.split(",") if n]
    bad = 0
    for name in names:
        if name not in CHECKS:
            sys.exit(f"check_trajectories: unknown check {name}")
        with tempfile.TemporaryDirectory() as tmp:
            dump = run_check(name, pathlib.Path(tmp), ref)
            if args.mode == "record":
                shutil.copy(dump, ref / f"{name}.dump")
                print(f"{name}: recorded")
                continue
            dx, dv = compare(ref / f"{name}.dump", dump)
            ok = dx <= args.tol and dv <= args.vtol
            bad += not ok
            print(f"{name}: max |dx|/box {dx:.3g}, max |dv| {dv:.3g} m/s "
                  f"{'ok' if ok else 'CHANGED'}{' (bit-identical)' if dx == 0 and dv == 0 else ''}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
