"""A mutation engine for LAMMPS input lines, and the runner and classifier of the decks it makes
(used by test_fuzz.py; reusable for any style).

A `Line` is a valid command split into tokens, each with a kind that says how it may be
mutated (`num`, `word`, `type`, `group`, `style`, or `fixed`).  `mutations(line)` yields
(label, text) for every mutation of every token - dropped, repeated, 0, negative, nan, inf,
1e300, -1e300, 1e-300, text for numbers; dropped, repeated, an unknown keyword for words;
invalid type indices and ranges; unknown and unrelated groups and sub-styles - and of the line
(an extra value, an unknown keyword, no arguments).  A `Case` is a deck in which one line was
mutated; `run_cases` runs them (one lmp each, `jobs` at a time) and `classify` sorts each
outcome into

  error      a clean LAMMPS error: non-zero exit and an ERROR line
  accepted   exit 0 (the deck's run completed); `nonfinite` if a thermo value was not finite
  crash      a signal, abort, uncaught exception, segmentation fault, exit without an ERROR
             line, or a hang (time limit)
  infra      Open MPI failed to start, so lmp never ran (mpistart.py): retried with a back-off
             by `run_case`, and reported as an infrastructure failure if it persists
"""
import math
import os
import re
import shutil
import subprocess
import tempfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import mpistart

NUM_MUTATIONS = [("0", "0"), ("neg", None), ("nan", "nan"), ("inf", "inf"), ("1e300", "1e300"),
                 ("-1e300", "-1e300"), ("1e-300", "1e-300"), ("text", "abc")]
TYPE_MUTATIONS = [("type0", "0"), ("type-beyond", "{ntypes1}"), ("type-neg", "-1"),
                  ("type-text", "abc"), ("type-float", "1.5"), ("type-range-reversed", "3*1")]
GROUP_MUTATIONS = [("group-unknown", "nosuch"), ("group-all", "all")]

# what a crash looks like in the output (besides a signal or an exit without an ERROR line)
CRASH_MARKERS = ["Segmentation fault", "terminate called", "Aborted", "core dumped",
                 "double free", "corrupted", "stack smashing", "Floating point exception",
                 "Assertion", "Caught signal", "Signal:", "Bus error", "Illegal instruction",
                 "std::bad_alloc"]


@dataclass
class Line:
    """tokens: [(text, kind)]; kind: fixed (not mutated), num, word, type, group, style
    (a pair hybrid sub-style name; `alt` gives a valid other one)."""
    tokens: list
    alt_style: str = "none"

    @staticmethod
    def parse(text, fixed=1, types=(), groups=(), styles=(), alt_style="none"):
        """Split a command: the first `fixed` tokens are not mutated (except a group among them); tokens at the indices in
        types/groups/styles have those kinds; the rest are num (if they read as a float) or
        word."""
        toks = []
        for k, t in enumerate(text.split()):
            if k in groups:    # a fix's own group lies among its fixed tokens
                kind = "group"
            elif k < fixed:
                kind = "fixed"
            elif k in types:
                kind = "type"
            elif k in styles:
                kind = "style"
            else:
                try:
                    float(t)
                    kind = "num"
                except ValueError:
                    kind = "word"
            toks.append((t, kind))
        return Line(toks, alt_style)

    def text(self, toks=None):
        return " ".join(t for t, _ in (self.tokens if toks is None else toks))


def negative(v):
    return v[1:] if v.startswith("-") else "-" + v


def mutations(line, ntypes=3):
    """(label, text) for every mutation of the line; labels name the token position."""
    toks = line.tokens
    out = []
    for k, (t, kind) in enumerate(toks):
        if kind == "fixed":
            continue
        pos = f"{k}:{t}"

        def put(v):
            return line.text(toks[:k] + [(v, kind)] + toks[k + 1:])

        if kind in ("num", "word", "style"):
            out.append((f"{pos} drop", line.text(toks[:k] + toks[k + 1:])))
            out.append((f"{pos} repeat", line.text(toks[:k + 1] + [(t, kind)] + toks[k + 1:])))
        if kind == "num":
            for label, v in NUM_MUTATIONS:
                out.append((f"{pos} {label}", put(negative(t) if v is None else v)))
        elif kind == "word":
            out.append((f"{pos} unknown", put("bogus")))
        elif kind == "type":
            for label, v in TYPE_MUTATIONS:
                out.append((f"{pos} {label}", put(v.format(ntypes1=ntypes + 1))))
        elif kind == "group":
            for label, v in GROUP_MUTATIONS:
                out.append((f"{pos} {label}", put(v)))
        elif kind == "style":
            out.append((f"{pos} style-unknown", put("saltdem/bogus")))
            out.append((f"{pos} style-other", put(line.alt_style)))
    base = line.text()
    out.append(("line extra-value", base + " 1"))
    out.append(("line unknown-keyword", base + " bogus 1"))
    out.append(("line keyword-without-value", base + " bogus"))
    nfixed = max((k + 1 for k, (_, kind) in enumerate(toks) if kind == "fixed"), default=0)
    out.append(("line no-arguments", line.text(toks[:nfixed])))
    return out


@dataclass
class Case:
    target: str      # what was mutated (style and line)
    label: str       # the mutation
    deck: str        # the whole input
    line: str = ""   # the mutated line


@dataclass
class Outcome:
    kind: str        # error, accepted, nonfinite, crash
    detail: str      # the ERROR line, the non-finite thermo row, or what crashed
    rc: int = 0
    seconds: float = 0.0
    tail: str = field(default="", repr=False)


def thermo_rows(out):
    """Every thermo row (list of tokens) of every run in the output."""
    rows, cols = [], None
    for line in out.splitlines():
        s = line.split()
        if s and s[0] == "Step":
            cols = len(s)
        elif cols and line.startswith("Loop time"):
            cols = None
        elif cols and s and re.fullmatch(r"-?\d+", s[0]) and len(s) == cols:
            rows.append(s)
    return rows


def finite(tok):
    try:
        return math.isfinite(float(tok))
    except ValueError:
        return False


def classify(rc, out, timed_out=False):
    """The outcome of one lmp run (rc as subprocess reports it: negative for a signal)."""
    tail = out[-3000:]
    if rc != 0 and not timed_out and mpistart.start_failed(out):
        return Outcome("infra", "Open MPI failed to start: lmp never ran", rc, tail=tail)
    if timed_out:
        return Outcome("crash", "hang: time limit reached", rc, tail=tail)
    for m in CRASH_MARKERS:
        if m in out:
            return Outcome("crash", f"'{m}' in the output", rc, tail=tail)
    if rc < 0 or rc > 128:
        return Outcome("crash", f"killed by a signal (rc {rc})", rc, tail=tail)
    err = next((l for l in out.splitlines() if l.startswith("ERROR")), None)
    if rc != 0:
        if err is None:
            return Outcome("crash", f"exit {rc} without an ERROR line", rc, tail=tail)
        return Outcome("error", err, rc, tail=tail)
    if err is not None:
        return Outcome("crash", f"exit 0 after an ERROR line: {err}", rc, tail=tail)
    rows = thermo_rows(out)
    if not rows:
        return Outcome("crash", "exit 0 without thermo output (the run did not happen)", rc, tail=tail)
    for r in rows:
        if not all(finite(t) for t in r):
            return Outcome("nonfinite", "thermo row " + " ".join(r), rc, tail=tail)
    return Outcome("accepted", "thermo " + " ".join(rows[-1]), rc, tail=tail)


def lmp_env():
    """One-rank runs start faster with Open MPI's singleton kept to itself (no daemon, no
    network transports): ~0.25 s instead of ~1 s per lmp."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    for k, v in (("OMPI_MCA_ess_singleton_isolated", "1"), ("OMPI_MCA_btl", "self"),
                 ("OMPI_MCA_pml", "ob1"), ("OMPI_MCA_mtl", "^ofi"), ("OMPI_MCA_osc", "^ucx")):
        env.setdefault(k, v)
    return env


def run_case(lmp, case, timeout=30.0):
    """Run one case in a temporary directory (its deck on standard input)."""
    import time
    d = tempfile.mkdtemp(prefix="saltdem-fuzz-")
    t0 = time.monotonic()
    try:
        proc, _, _ = mpistart.run([lmp, "-echo", "none", "-log", "none", "-nocite"],
                                  input=case.deck, cwd=d, capture_output=True, text=True,
                                  timeout=timeout, env=lmp_env(), errors="replace")
        o = classify(proc.returncode, proc.stdout + proc.stderr)
    except subprocess.TimeoutExpired:
        o = classify(0, "", timed_out=True)
    finally:
        shutil.rmtree(d, ignore_errors=True)
    o.seconds = time.monotonic() - t0
    return o


def run_cases(lmp, cases, jobs=2, timeout=30.0):
    """Outcomes of all cases, in order, `jobs` lmp processes at a time."""
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        return list(pool.map(lambda c: run_case(lmp, c, timeout), cases))
