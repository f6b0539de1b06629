"""The runs of stable_limit.py: where the decks come from (--decks), one lmp at a time with its log
and CPU time, the packs of tools/pack.in, and what a log says (the trial's thermo rows, the limits
the styles report)."""
import os
import pathlib
import re
import subprocess

from stable_cases import DIST, KN_WALL, RMAX, RMIN

ROOT = pathlib.Path(__file__).resolve().parents[2]
DECKS = ROOT          # where examples/, tools/ and potentials/ come from (--decks, set by main)

LIMIT_RE = re.compile(r"Pair style (\S+): timestep (\S+) = (\S+) of the stable limit (\S+) \((.*)\)\s*$")
SCENE_LIMIT_RE = re.compile(r"saltdem/timestep: timestep (\S+) = (\S+) of the stable limit (\S+) of "
                            r"pair style (\S+) \((.*)\)\s*$")


def run_logged(cmd, cwd, log, timeout):
    """Run one lmp command line in cwd, its output to log only; return (returncode, log text, CPU
    seconds)."""
    t0 = os.times()
    try:
        rc = subprocess.run(cmd, cwd=cwd, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, timeout=timeout).returncode
    except subprocess.TimeoutExpired:
        rc = -999
    t1 = os.times()
    text = log.read_text(errors="replace") if log.exists() else ""
    return rc, text, (t1.children_user - t0.children_user) + (t1.children_system - t0.children_system)


class Runner:
    def __init__(self, lmp, work, timeout):
        self.lmp = str(lmp)
        self.work = pathlib.Path(work)
        self.work.mkdir(parents=True, exist_ok=True)
        self.timeout = timeout

    def run(self, name, deck, variables=()):
        """Run one deck; return (returncode, log text, CPU seconds)."""
        path = self.work / f"{name}.in"
        log = self.work / f"{name}.log"
        path.write_text(deck)
        cmd = [self.lmp, "-in", path.name, "-log", log.name, "-screen", "none", "-nocite"]
        for k, v in variables:
            cmd += ["-var", k, str(v)]
        return run_logged(cmd, self.work, log, self.timeout)

    def pack(self, W, H, seed=7, kn=KN_WALL, rmin=RMIN, rmax=RMAX, dist=DIST):
        """A settled pack of tools/pack.in (made once, kept in WORK)."""
        out = self.work / f"pack_{W}x{H}_{rmin}_{dist}_{seed}_{kn:g}.data"
        if not out.exists():
            cmd = [self.lmp, "-in", str(DECKS / "tools" / "pack.in"), "-log", "none", "-screen", "none", "-nocite",
                   "-var", "W", str(W), "-var", "H", str(H), "-var", "rmin", str(rmin), "-var", "rmax",
                   str(rmax), "-var", "dist", dist, "-var", "seed", str(seed), "-var", "kn", str(kn),
                   "-var", "out", out.name + ".tmp"]
            subprocess.run(cmd, cwd=self.work, check=True, stdout=subprocess.DEVNULL)
            (self.work / (out.name + ".tmp")).rename(out)
        return out


def thermo_rows(text, marker="STABLE_RUN"):
    """Thermo rows (dicts) of the run after the line 'print STABLE_RUN'."""
    i = text.rfind(marker)
    if i < 0:
        return []
    rows, header = [], None
    for line in text[i:].splitlines():
        s = line.split()
        if not s:
            continue
        if s[0] == "Step":
            header = s
            continue
        if header and (s[0].startswith("Loop") or s[0].startswith("ERROR")):
            break
        if header and len(s) == len(header):
            try:
                rows.append({k: float(v) for k, v in zip(header, s)})
            except ValueError:
                rows.append({k: float("nan") for k in header})
    return rows


def reported_limit(text):
    """The smallest limit the SaltDEM styles logged at the first run: (limit, style, why)."""
    best = None
    for line in text.splitlines():
        m = LIMIT_RE.search(line)
        if m:
            lim = float(m.group(4))
            if best is None or lim < best[0]:
                best = (lim, m.group(1), m.group(5))
        if "REPORTED_DONE" in line:
            break
    return best

