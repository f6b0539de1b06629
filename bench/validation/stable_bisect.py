"""The bisection of stable_limit.py: X = dt / L between a stable and an unstable run, the verdict
on each run (stable_limit.py's docstring), and a component case: a bisection of generated decks."""
import math

from stable_cases import X_SETTLE, cover_deck, fluid_deck
from stable_run import reported_limit, thermo_rows

XREF = 0.5          # first run: half the reported limit
GROW = 10.0         # kinetic energy above GROW x the nearest stable run's largest: unstable


class Bisect:
    """Bisection of X = dt / L between a stable and an unstable run (subclasses: limit, run_x)."""
    ke_keys = ("c_ke0",)

    def __init__(self, runner, name, nsteps, tol):
        self.r, self.name, self.nsteps, self.tol = runner, name, nsteps, tol
        self.limit = self.style = self.why = None
        self.runs = []

    def trial(self, x):
        rc, text, cpu = self.run_x(x)
        rows = thermo_rows(text)
        ke = [sum(r.get(k, 0.0) for k in self.ke_keys) for r in rows]
        finite = bool(rows) and all(math.isfinite(v) for r in rows for v in r.values())
        done = "STABLE_DONE" in text and rc == 0
        kemax = max(ke) if ke and finite else float("inf")
        err = next((ln.strip()[:160] for ln in text.splitlines() if ln.startswith("ERROR")), "")
        # against the largest kinetic energy of the nearest stable run below (a longer run at a
        # larger dt covers more of the physical motion, e.g. a scene still settling)
        below = [r for r in self.runs if r["stable"] and r["x"] < x]
        ref = max(below, key=lambda r: r["x"])["ke_max"] if below else None
        first = self.runs[0]["ke_max"] if self.runs else None
        ok = (done and finite and (ref is None or kemax <= GROW * max(ref, 1e-300))
              and (first is None or kemax <= GROW ** 2 * max(first, 1e-300)))
        self.runs.append({"x": x, "dt": x * self.limit, "stable": ok, "ke_max": kemax, "rc": rc,
                          "error": err, "cpu_s": round(cpu, 2)})
        print(f"  {self.name}: X {x:.4f} dt {x * self.limit:.5g} s -> "
              f"{'stable' if ok else 'UNSTABLE'} (KE max {kemax:.3g}{', ' + err if err else ''}; "
              f"{cpu:.1f} CPU s)", flush=True)
        return ok, kemax

    def measure(self, xmax=64.0, xstart=1.0):
        """Largest stable X (lo) and smallest unstable X (hi, None if none up to xmax)."""
        ok, ke = self.trial(XREF)
        if not ok:
            raise RuntimeError(f"{self.name}: unstable at the reference X {XREF}")
        lo, hi, x = XREF, None, xstart
        while x <= xmax:
            if self.trial(x)[0]:
                lo, x = x, x * 1.6
            else:
                hi = x
                break
        if hi is None:
            return lo, None
        while hi / lo > 1 + self.tol:
            mid = math.sqrt(lo * hi)
            if self.trial(mid)[0]:
                lo = mid
            else:
                hi = mid
        return lo, hi


class Case(Bisect):
    """A component case: one generated deck per run."""

    def __init__(self, runner, params, nsteps, tol):
        super().__init__(runner, params["name"], nsteps, tol)
        self.c = dict(params)
        self.c["nsteps"] = nsteps

    def deck(self, x):
        dt_settle = X_SETTLE * self.limit if self.limit else 1e-9
        maker = cover_deck if self.c["law"] == "cover" else fluid_deck
        return maker(self.c, dt_settle, x, self.limit or 1.0)

    def probe_limit(self):
        """The reported limit: the deck up to its first run 0."""
        deck = self.deck(1.0).split("print           REPORTED_DONE")[0] + "print REPORTED_DONE\n"
        rc, text, cpu = self.r.run(f"{self.name}_limit", deck)
        lim = reported_limit(text)
        if rc != 0 or lim is None:
            raise RuntimeError(f"{self.name}: no reported limit (rc {rc}), see "
                               f"{self.r.work}/{self.name}_limit.log")
        self.limit, self.style, self.why = lim
        return lim

    def run_x(self, x):
        return self.r.run(f"{self.name}_x{x:.4f}", self.deck(x))

