"""Shared by tests/test_reliability.py and tests/test_reliability_long.py: a small SaltDEM
scene (cover over salt on a faulted basement, the interactions of examples/scene/laws.in)
written as a LAMMPS data file, the deck that loads it, and readers for dumps and memory.

The scene is deterministic (radii from a seeded generator, atom IDs independent of the number
of MPI ranks), so runs on different rank/thread counts and split runs can be compared atom by
atom.
"""
import math
import os
import random
import re
import shutil
import subprocess
import threading
import time
from types import SimpleNamespace

from lmprun import ROOT, lmp_path, run_cmd

SCENE_DECK = (ROOT / "tests" / "decks" / "scene_mini.in").read_text()

# the scene defaults of examples/scene/params.in, per resolution preset: "quick" (discs 4x the
# paper's) and "paper" (the paper's discs 6.25-15.625 m, dt 0.002 s, S 20)
PRESETS = {
    "quick": dict(rmin=25.0, rmax=62.5, dt=0.0025, S=4, rate=0.5),
    "paper": dict(rmin=6.25, rmax=15.625, dt=0.002, S=20, rate=0.05),
}
MATERIAL = dict(kn_cover=1e10, kt_cover=5e9, kn_wall=1e10, eta=5e8, K_salt=1e9, rho=2200.0)


class Scene:
    """Geometry of one scene: width, salt and cover thickness in units of rmax."""

    def __init__(self, preset="quick", width=48, salt=6, cover=6, dip=30.0, target=None,
                 seed=20170612, weld=False):
        p = PRESETS[preset]
        self.preset = preset
        self.rmin, self.rmax = p["rmin"], p["rmax"]
        self.W = width * self.rmax
        self.Hs = salt * self.rmax
        self.Hc = cover * self.rmax
        self.H = self.Hs + self.Hc
        self.dip = dip
        self.target = target if target is not None else 2 * self.rmax
        self.seed = seed
        self.weld = weld      # salt = one row of the smallest discs
        self.xf = 0.5 * self.W

    # ---- the data file ------------------------------------------------------------------------
    def _line(self, x0, y0, x1, y1, r):
        """Wall discs of radius r centred on the segment, ends included, spacing <= 2r."""
        L = math.hypot(x1 - x0, y1 - y0)
        n = max(1, math.ceil(L / (2 * r) - 1e-9)) + 1
        return [(x0 + (x1 - x0) * k / (n - 1), y0 + (y1 - y0) * k / (n - 1)) for k in range(n)]

    def atoms(self):
        """[(type, radius, x, y)] in ID order: pack (cover 1, salt 2), footwall (3), then the
        hanging wall (3) as the last, contiguous ID range."""
        rnd = random.Random(self.seed)
        rmin, rmax = self.rmin, self.rmax
        pack = []
        rows = []
        if self.weld:
            # the weld: one row of the smallest discs on the basement, the cover above it
            rows.append((rmin, 2, rmin, rmin))
            y = 2 * rmin
        else:
            y = 0.0
        while y + 2 * rmax <= self.H + 1e-9:
            typ = 2 if (y + rmax < self.Hs and not self.weld) else 1
            rows.append((y + rmax, typ, rmin, rmax))
            y += 2 * rmax
        for yc, typ, lo, hi in rows:
            x = 0.0
            while True:
                r = rnd.uniform(lo, hi)
                if x + 2 * r > self.W:
                    break
                pack.append((typ, r, x + r, yc))
                x += 2 * r
        rw = rmin
        sd, cd = math.sin(math.radians(self.dip)), math.cos(math.radians(self.dip))
        xf = self.xf
        foot = self._line(-rw, -rw, xf - rw * (1 - cd) / sd, -rw, rw)
        foot += self._line(-rw, rw, -rw, self.H + self.Hs, rw)
        lface = self.target + 4 * rw
        foot += self._line(xf - rw * sd, -rw * cd, xf - rw * sd + lface * cd,
                           -rw * cd - lface * sd, rw)
        hang = self._line(xf + rw, -rw, self.W + rw, -rw, rw)
        hang += self._line(self.W + rw, rw, self.W + rw, self.H + self.Hs, rw)
        out = pack + [(3, rw, x, y) for x, y in foot]
        self.hang_ids = (len(out) + 1, len(out) + len(hang))
        self.npack = len(pack)
        self.nsalt = sum(1 for a in pack if a[0] == 2)
        out += [(3, rw, x, y) for x, y in hang]
        return out

    def box(self):
        return (-3 * self.rmax, self.W + 3 * self.rmax + self.target,
                -self.Hs - self.target - 2 * self.rmax, self.H + 2 * self.Hs)

    def write(self, path):
        atoms = self.atoms()
        xlo, xhi, ylo, yhi = self.box()
        lines = [f"SaltDEM reliability scene {self.preset}", "", f"{len(atoms)} atoms",
                 "3 atom types", f"{xlo!r} {xhi!r} xlo xhi", f"{ylo!r} {yhi!r} ylo yhi",
                 "-1000.0 1000.0 zlo zhi", "", "Atoms # sphere", ""]
        lines += [f"{i + 1} {t} {2 * r!r} 1.0 {x!r} {y!r} 0.0" for i, (t, r, x, y) in
                  enumerate(atoms)]
        path.write_text("\n".join(lines) + "\n")
        return path

    def variables(self, **over):
        """-var NAME VALUE for scene_mini.in: the preset's and the material defaults."""
        if not hasattr(self, "hang_ids"):
            self.atoms()
        p = PRESETS[self.preset]
        rmin, rmax = self.rmin, self.rmax
        v = dict(MATERIAL)
        v.update(rmin=rmin, dt=p["dt"], S=p["S"], S_cover=p["S"], rate=p["rate"],
                 dip=self.dip, target=self.target, hang=f"{self.hang_ids[0]}:{self.hang_ids[1]}",
                 # cohesion, tensile force and range scale with the disc radius (params.in)
                 coh_cover=2e8 * rmin / 6.25, ten_cover=1e8 * rmin / 6.25,
                 rng_cover=0.05 * rmin / 6.25, kn_salt=0, check=10, newton="on")
        # SPH smoothing: 1.3 disc spacings (laws.in), from the mean squared radius
        r2 = (rmin ** 2 + rmin * rmax + rmax ** 2) / 3.0
        v["h_salt"] = 1.3 * math.sqrt(math.pi * r2 / 0.85)
        v.update(over)
        return v


# ---- dumps, energies ---------------------------------------------------------------------------

def read_dump(path):
    """{id: [columns after id]} of a text dump written with 'modify sort id'."""
    lines = path.read_text().split("ITEM: ATOMS")[1].splitlines()[1:]
    return {int(s[0]): [float(v) for v in s[1:]] for s in (l.split() for l in lines) if s}


def max_rel_diff(a, b, scale, cols=(0, 1)):
    """Largest difference of columns `cols` between two dumps, relative to `scale`."""
    assert a.keys() == b.keys(), f"atom sets differ: {len(a)} vs {len(b)}"
    return max(abs(a[i][c] - b[i][c]) for i in a for c in cols) / scale


def all_finite(table):
    return all(math.isfinite(v) for col in table.values() for v in col)


# ---- memory --------------------------------------------------------------------------------

def vmrss_kb(pid):
    """Resident set size of a process in kB (0 once it has gone)."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except (FileNotFoundError, ProcessLookupError):
        pass
    return 0


def run_watched(deck, workdir, timeout=600, period=0.05, **variables):
    """Run lmp on a deck while a watcher thread samples its VmRSS every `period` s.
    The deck marks its phases by writing files 'phase.K' (shell-free: 'print ... file');
    returns (returncode, output, samples [(t, rss_kB, phase)])."""
    (workdir / "in.deck").write_text(deck)
    cmd = [lmp_path(), "-in", "in.deck", "-log", "log.lammps", "-echo", "none"]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    # run_cmd retries a start that Open MPI failed and fails the test as infrastructure
    proc = run_cmd(cmd, runner=lambda c, **kw: _watched(c, workdir, env, timeout, period))
    return proc.returncode, proc.stdout, proc.samples


def _watched(cmd, workdir, env, timeout, period):
    """One watched run: its return code, output (stdout) and samples."""
    proc = subprocess.Popen(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, env=env)
    samples = []
    done = threading.Event()

    def watch():
        t0 = time.time()
        while not done.is_set():
            rss = vmrss_kb(proc.pid)
            phase = max((int(p.name.split(".")[1]) for p in workdir.glob("phase.*")), default=-1)
            if rss:
                samples.append((time.time() - t0, rss, phase))
            time.sleep(period)

    th = threading.Thread(target=watch, daemon=True)
    th.start()
    try:
        out, _ = proc.communicate(timeout=timeout)
    finally:
        done.set()
        th.join()
        if proc.poll() is None:
            proc.kill()
    return SimpleNamespace(returncode=proc.returncode, stdout=out, stderr="", samples=samples)


def heap_mb(out):
    """'Current reserved memory pool size' (glibc heap in use, MB) of each `info memory`."""
    return [float(v) for v in re.findall(r"Current reserved memory pool size: ([0-9.eE+-]+)", out)]


def mpirun_cmd(np):
    mpirun = shutil.which("mpirun")
    extra = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    return [mpirun, *extra, "--oversubscribe", "-np", str(np)]
