"""Running the calibration decks of the SaltDEM checkout: one LAMMPS run per
job in its own directory, several at a time."""

from __future__ import annotations

import concurrent.futures
import hashlib
import os
import re
import shlex
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional, Sequence

from ..checkout import repo
from ..output import ensure_dir


class CalibrationError(RuntimeError):
    pass


def say(text: str) -> None:
    print(text, flush=True)


def note(ctx, text: str) -> None:
    if not ctx.quiet:
        print(f"saltdem-calibrate: {text}", file=sys.stderr, flush=True)


@dataclass
class Context:
    lmp: Optional[str]
    out: Path
    jobs: int = 1
    quiet: bool = False
    rerun: bool = False
    root: Optional[Path] = None     # the checkout: repo() when first needed

    @property
    def checkout(self) -> Path:
        if self.root is None:
            self.root = repo()
        return self.root


@dataclass
class Job:
    deck: Path
    workdir: Path
    variables: Dict[str, object]
    label: str
    output: str = ""
    seconds: float = 0.0
    reused: bool = False
    always: bool = False        # never reuse (e.g. a deck whose input files change)


def run_one(ctx: Context, job: Job) -> Job:
    """Run one deck in its own directory.  A directory that holds the same
    command and the log of a finished run (LAMMPS's closing 'Total wall
    time') is reused unless ctx.rerun: an interrupted calibration resumes,
    and a set repeated with the same material and packs costs nothing.  The
    deck's SHA-1 is part of the command, so an edited deck runs again."""
    ensure_dir(str(job.workdir))
    cmd = [ctx.lmp, "-in", str(job.deck), "-echo", "none", "-screen", "none", "-log", "log.lammps",
           "-var", "root", str(ctx.checkout)]
    for k, v in job.variables.items():
        cmd += ["-var", k, str(v)]
    digest = hashlib.sha1(Path(job.deck).read_bytes()).hexdigest()
    text = f"# deck sha1 {digest}\n" + " ".join(shlex.quote(c) for c in cmd) + "\n"
    cfile, log = job.workdir / "command.sh", job.workdir / "log.lammps"
    if not (ctx.rerun or job.always) and cfile.exists() and cfile.read_text() == text and log.exists():
        out = log.read_text(errors="replace")
        m = re.search(r"^Total wall time: (\d+):(\d+):(\d+)", out, re.M)
        if m:
            job.output, job.reused = out, True
            job.seconds = 3600 * int(m.group(1)) + 60 * int(m.group(2)) + int(m.group(3))
            return job
    cfile.write_text(text)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    t0 = time.monotonic()
    proc = subprocess.run(cmd, cwd=job.workdir, capture_output=True, text=True, env=env)
    job.seconds = time.monotonic() - t0
    job.output = (log.read_text(errors="replace") if log.exists() else "") + proc.stdout + proc.stderr
    if proc.returncode != 0:
        err = next((l for l in job.output.splitlines() if "ERROR" in l), job.output[-800:])
        raise CalibrationError(f"{job.label}: lmp failed (rc {proc.returncode}) in {job.workdir}: {err}")
    return job


def run_jobs(ctx: Context, jobs: Sequence[Job]) -> List[Job]:
    """Run the jobs, ctx.jobs at a time; report each as it finishes."""
    if not jobs:
        return []
    t0, done = time.monotonic(), 0
    with concurrent.futures.ThreadPoolExecutor(max(1, ctx.jobs)) as ex:
        futs = {ex.submit(run_one, ctx, j): j for j in jobs}
        for f in concurrent.futures.as_completed(futs):
            j = f.result()
            done += 1
            el = time.monotonic() - t0
            note(ctx, f"[{done}/{len(jobs)}] {j.label} (" + ("reused, " if j.reused else "") +
                 f"{j.seconds:.0f} s; elapsed {el:.0f} s, ETA {el / done * (len(jobs) - done):.0f} s)")
    return list(jobs)
