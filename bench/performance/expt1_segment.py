#!/usr/bin/env python3
"""Scene-level validation of the settings that change accuracy (time step, inertia factor),
at full resolution: segments of the full-preset Expt 1 resumed from one restart file, each with
other settings, compared with a reference segment and against the run-to-run floor.

Every segment resumes the same restart file through the deck's own resume path
(examples/expt1.in -var restart FILE) with its settings given as deck variables (-var dt: the
time step, 0 = 0.85 of the styles' stable limit; -var S and S_cover: the inertia factors), and
runs LENGTH m of fault displacement.  The fields compared are those of bench/performance/expt1_error.py over
the segment (salt thickness change per 250 m column, mean marker displacement and mean
incremental maximum shear strain per 250 m cell, from the common first frame at the restart to
each segment's last frame):

  thickness  RMS difference of the thickness change over the salt thickness (1000 m)
  marker     RMS difference of the mean displacement over the segment's fault displacement
  strain     RMS difference of the mean shear strain over the reference's RMS

and, as a reading of what the marker differences are made of, each segment's glide: the mean
horizontal displacement of the cover's discs (the cover gliding on the salt).

The floor: the same settings on 1 OpenMP thread and on 2 (round-off only, which the granular
cover turns into a different, equally valid run).  A setting whose difference from the
reference lies within the floor cannot be told from it.

  PYTHONPATH=python /usr/bin/python3 bench/performance/expt1_segment.py --restart R --work out/segments \\
      --seg paper:0.002:20:1 --seg paper-omp2:0.002:20:2 --seg new:0:20:1 --seg new-omp2:0:20:2 \\
      --ref paper --floor paper:paper-omp2 --floor new:new-omp2 [--length 50] [--table T.md]

--seg NAME:DT:S:THREADS[:SUBSTEPS[:VAR=VALUE,...]] (THREADS: OpenMP threads, or RxT for R MPI ranks of
T threads each, e.g. 2x1 - another round-off sample of the floor; SUBSTEPS: the salt's viscous sub-steps, default 1; VAR=VALUE: other deck variables, e.g. kn_cs=2.5e9; DT 0: 0.85 of the stable limit with the segment's sub-steps; S 0: the preset's; a segment already run, with its done.json, is not run again);
--run NAME runs only that segment (to spread segments over cores) and compares nothing;
--matrix adds the differences between every two segments (B against A).
"""
import argparse
import json
import os
import pathlib
import re
import resource
import shutil
import subprocess
import sys
import time

from expt1_error import ROOT, compare, fields    # the same measures (expt1_error.py next to this script)
from saltdem_post.checkout import lmp_path


def deck_args(preset, restart, extra, ranks=1):
    mpi = []
    if ranks > 1:
        if not shutil.which("mpirun"):
            sys.exit("expt1_segment: mpirun not found (install openmpi-bin) for a segment on MPI ranks")
        mpi = ["mpirun", "-np", str(ranks)] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    return mpi + [lmp_path(ROOT), "-in", str(ROOT / "examples" / "expt1.in"), "-log", "log.lammps",
            "-echo", "none", "-screen", "none", "-var", "root", str(ROOT), "-var", "preset", preset,
            "-var", "restart", str(restart)] + extra


def segments_dirs():
    """Where the kept segments' frames and restart files may lie (they are not in git,
    bench/segments/README.md): $SALTDEM_SEGMENTS, bench/segments itself, and the cache
    ($SALTDEM_CACHE or ~/.cache/saltdem, as for the LAMMPS build, then segments/)."""
    xdg = pathlib.Path(os.environ.get("XDG_CACHE_HOME", pathlib.Path.home() / ".cache"))
    cache = pathlib.Path(os.environ.get("SALTDEM_CACHE", xdg / "saltdem"))
    dirs = [os.environ.get("SALTDEM_SEGMENTS"), ROOT / "bench" / "segments", cache / "segments"]
    return [pathlib.Path(d) for d in dirs if d]


def find_kept(rel, what):
    """A kept file by its path relative to bench/segments (e.g. paper_100to150m/start/dump...):
    the first of segments_dirs() that holds it; otherwise exit saying which file is missing and
    how to get it back."""
    for d in segments_dirs():
        if (d / rel).exists():
            return d / rel
    sys.exit(f"expt1_segment: {what} {rel} is missing (looked in "
             f"{', '.join(str(d) for d in segments_dirs())}): the kept segments' frames and restart "
             f"files are not in git; put them there (or set SALTDEM_SEGMENTS to their folder) or "
             f"regenerate them as bench/segments/README.md says")


def load_done(done):
    """A segment's done.json; its dump paths may be relative to the work directory (a reference
    segment kept in bench/segments/, copied into the work directory, is not run again).  A dump
    that the work directory lacks is looked up among the kept segments (find_kept), under
    paper_100to150m/."""
    res = json.loads(done.read_text())
    for k in ("dump", "first", "last"):
        if k in res:
            p = (done.parent.parent / res[k]).resolve()
            if not p.exists() and not pathlib.Path(res[k]).is_absolute():
                p = find_kept(pathlib.Path("paper_100to150m") / res[k], f"the frame of {done}:")
            res[k] = str(p)
    return res


def start(preset, restart, work):
    """The restart's state as a frame (resume_frame 1, no frame to run): its dump and its
    displacement and step."""
    d = work / "start"
    done = d / "done.json"
    if done.exists():
        return load_done(done)
    d.mkdir(parents=True, exist_ok=True)
    p = subprocess.run(deck_args(preset, restart, ["-var", "resume_frame", "1", "-var", "f", "0"]),
                       cwd=d, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    log = (d / "log.lammps").read_text() if (d / "log.lammps").exists() else ""
    if p.returncode != 0:
        raise RuntimeError(f"start: {[l for l in log.splitlines() if 'ERROR' in l][:1] or log[-1500:]}")
    m = re.search(r"^\s*Step\s+v_disp.*\n\s*(\d+)\s+([-0-9.eE+]+)", log, re.M)
    dumps = list(d.glob("dump.expt1.*.txt"))
    assert m and len(dumps) == 1, "start: no thermo line with the displacement, or no frame"
    res = dict(step=int(m.group(1)), disp=float(m.group(2)), dump=str(dumps[0]))
    done.write_text(json.dumps(res) + "\n")
    return res


def segment(name, dt, S, ranks, threads, substeps, more, preset, restart, st, length, work):
    d = work / name
    done = d / "done.json"
    if done.exists():
        return load_done(done)
    d.mkdir(parents=True, exist_ok=True)
    end = st["disp"] + length
    extra = ["-var", "f", f"{end:.6f}", "-var", "dt", f"{dt:g}"]
    if S > 0:    # else the preset's
        extra += ["-var", "S", f"{S:g}", "-var", "S_cover", f"{S:g}"]
    # the salt's viscous sub-steps, 1 = none, always given: a resumed run keeps the file's
    # otherwise (DT 0: the step follows the limit)
    extra += ["-var", "substeps", str(substeps)]
    for kv in more:    # other deck variables, NAME=VALUE
        k, v = kv.split("=")
        extra += ["-var", k, v]
    if threads > 1:
        extra += ["-sf", "omp", "-pk", "omp", str(threads)]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    p = subprocess.run(deck_args(preset, restart, extra, ranks), cwd=d, capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_WAIT_POLICY="passive"))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    log = (d / "log.lammps").read_text() if (d / "log.lammps").exists() else ""
    if p.returncode != 0:
        raise RuntimeError(f"{name}: {[l for l in log.splitlines() if 'ERROR' in l][:1] or log[-1500:]}")
    dumps = sorted(d.glob("dump.expt1.*.txt"), key=lambda q: int(q.name.split(".")[2]))
    step_dt = re.findall(r"time step ([0-9.eE+-]+) s, drive", log)
    res = dict(name=name, dt=float(step_dt[-1]) if step_dt else dt, S=S, ranks=ranks, threads=threads,
               substeps=substeps, more=list(more),
               steps=int(dumps[-1].name.split(".")[2]) - st["step"],
               cpu_s=(after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
               wall_s=time.time() - t0, first=st["dump"], last=str(dumps[-1]))
    done.write_text(json.dumps(res) + "\n")
    return res


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--restart", required=True, type=pathlib.Path)
    ap.add_argument("--preset", default="full", help="the preset the restart file was run with")
    ap.add_argument("--work", default=str(ROOT / "out" / "segments"))
    ap.add_argument("--length", type=float, default=50.0, help="fault displacement per segment (m)")
    ap.add_argument("--seg", action="append", default=[], help="NAME:DT:S:THREADS[:SUBSTEPS[:VAR=VALUE,...]]")
    ap.add_argument("--run", help="run only this segment")
    ap.add_argument("--ref", help="the reference segment")
    ap.add_argument("--floor", action="append", default=[], help="A:B, a pair of the same settings")
    ap.add_argument("--table", help="write the table (markdown) here too")
    ap.add_argument("--matrix", action="store_true",
                    help="also every pair of segments (the floor's and the knob's spread from more than one sample)")
    a = ap.parse_args(argv)
    work = pathlib.Path(a.work).resolve()
    restart = a.restart.resolve()
    if not restart.exists():
        sys.exit(f"expt1_segment: no restart file {a.restart}: the full Expt 1 restart at 100.36 m is "
                 f"not in git; gunzip the kept expt1_full_100m.restart.gz (SALTDEM_SEGMENTS, or "
                 f"~/.cache/saltdem/segments) or regenerate it as bench/segments/README.md says")
    segs = {}
    for s in a.seg:
        name, dt, S, th, *sub = s.split(":")
        more = tuple(sub[1].split(",")) if len(sub) > 1 and sub[1] else ()
        ranks, th = th.split("x") if "x" in th else (1, th)
        segs[name] = (float(dt), float(S), int(ranks), int(th), int(sub[0]) if sub else 1, more)
    st = start(a.preset, restart, work)
    if a.run:
        print(json.dumps(segment(a.run, *segs[a.run], a.preset, restart, st, a.length, work)))
        return 0
    res = {n: segment(n, *v, a.preset, restart, st, a.length, work) for n, v in segs.items()}
    f = {n: fields(r) for n, r in res.items()}
    g = {n: v["glide"] for n, v in f.items()}
    rows = ["| segment | dt (s) | S | threads | steps | CPU (s) | against | thickness | marker | strain | glide (m) |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    pairs = [(x, y, "floor") for x, y in (p.split(":") for p in a.floor)]
    pairs += [(a.ref, n, "") for n in res if a.ref and n != a.ref and not any(n == y for _, y, _ in pairs)]
    for x, y, kind in pairs:
        c = compare(f[x], f[y], a.length)
        r = res[y]
        par = f"{r.get('ranks', 1)}x{r['threads']}" if r.get("ranks", 1) > 1 else r["threads"]
        rows.append(f"| {y}{' (floor)' if kind else ''} | {r['dt']:.4g} | {r['S'] or 'preset'} | {par} | "
                    f"{r['steps']} | {r['cpu_s']:.0f} | {x} | {c['thickness']:.4f} | {c['marker']:.4f} | "
                    f"{c['strain']:.3f} | {g[y]:.2f} |")
    if a.matrix:
        rows += ["", "| A | B | thickness | marker | strain |", "| --- | --- | --- | --- | --- |"]
        names = list(res)
        for i, x in enumerate(names):
            for y in names[i + 1:]:
                c = compare(f[x], f[y], a.length)
                rows.append(f"| {x} | {y} | {c['thickness']:.4f} | {c['marker']:.4f} | {c['strain']:.3f} |")
    rows += ["", "glide (m): " + ", ".join(f"{n} {v:.2f}" for n, v in g.items())]
    table = "\n".join(rows)
    print(f"restart at {st['disp']:.1f} m (step {st['step']}), segments of {a.length:g} m\n{table}")
    (work / "segments.json").write_text(json.dumps(dict(start=st, runs=res), indent=1) + "\n")
    if a.table:
        pathlib.Path(a.table).write_text(table + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
