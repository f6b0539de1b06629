#!/usr/bin/env python3
"""Measured stable time step of the SaltDEM styles against the limits they report.

For each case the script bisects the time step dt = X * L, with L the stable limit the styles
report for the case (the smallest of their limits at the default factors, as logged at the case's first run with its walls static: "timestep ... of the
stable limit L (...)"; docs/performance.md's table was measured at the factors of the time,
dtfactor 0.2 and viscfactor 0.5 with the fluid constant 0.1: L is 3x and 2.8x larger since), and
finds the largest X at which the case runs N steps stably:

  stable = LAMMPS ends without error (no NaN: fix saltdem/nve check 10; no lost disc; every
           thermo value finite) and the kinetic energy never exceeds GROW times the largest of
           the nearest stable run below (nor GROW^2 times that of the first run, at X = XREF):
           the physical motion of the case, not an oscillation grown out of round-off.

The styles refuse a time step above their limit at the start of every run (viscfactor <= 1 and
dtfactor <= 0.75 raise it 1.25x only), so the runs above it are reached in exact ways
(docs/performance.md, "Measured stability limits"):

  dt switch   (cases with saltdem/viscous only) the case settles at X_SETTLE, a 'run 0' at the
              settling step passes the check, then 'timestep X*L' and 'run N pre no': 'pre no'
              skips LAMMPS's init and with it the check.  saltdem/viscous, its density update
              and fix saltdem/nve read the time step every step: this is the run at X*L.
  mass switch (cases with saltdem/cohesive, which keeps the time step of its init for its
              tangential and rolling springs; no gravity) the case settles at X_SETTLE, then
              every integrated mass is divided by Y = (X / X_SETTLE)^2 ('set mass') and the run
              goes on at the same dt with 'run N pre no'.  Springs, cohesion and a lid's load do
              not depend on the mass, the dashpots 2 zeta sqrt(m k) scale with it: this is the
              trajectory of the true masses at dt * sqrt(Y) = X * L, step for step.
  the scene   (--scene) examples/expt1.in as it is, its frames replaced: settled once, resumed
              by the deck's own resume path for each trial and driven with a dt switch; the
              cover's springs are kept right by running it with kt, kr x R and zeta_t / sqrt(R)
              and an init at X L / R (see SceneCase).

Cases (--cases; the full preset's discs, power law 6.25-15.625 m from tools/pack.in, h = 1.3
disc spacings as examples/scene/laws.in makes it; the scenes' salt, cover and wall coefficients):

  fluid      SPH salt (pair saltdem/viscous fluid) in plane Couette flow between bands of wall
             discs, the top band a lid moving at V; unloaded (lid held) or under a weighted lid
             at P (load ramped up, settled with a drag); variants of h, S, K, kn_wall and the
             quick preset's discs
  contact    the scenes' contact salt (saltlaw contact: calibration 0.5, salt-salt kn = the
             cover's) in the same flows
  cover      the cover (pair saltdem/cohesive, potentials/cover_paper.params, rough cover-wall
             contacts of kn_wall) between a fixed band and a lid at P, at rest

  PYTHONPATH=python python3 bench/validation/stable_limit.py [--cases fluid,contact,cover|NAME,...] [--table FILE]
  PYTHONPATH=python python3 bench/validation/stable_limit.py --wall-study              # what kn_wall 2.5e9 / 1e10 change
  PYTHONPATH=python python3 bench/validation/stable_limit.py --scene quick             # the real Expt 1 (quick or full;
  PYTHONPATH=python python3 bench/validation/stable_limit.py --scene full --width 625 --pack-kelim 1e-4    # a strip)
  common: [--lmp build/lmp] [--work out/stable] [--decks DIR] [--steps 3000] [--tol 0.03]

One lmp runs at a time; a component case is a few hundred discs (2-15 CPU s per case after its
pack).  Writes WORK/results.json (every run: X, dt, verdict, largest kinetic energy, error) and,
with --table, a markdown table of all cases in it.
"""
import argparse
import json
import math
import os
import pathlib
import re
import subprocess
import time

from saltdem_post.checkout import lmp_path

ROOT = pathlib.Path(__file__).resolve().parents[2]
DECKS = ROOT          # where examples/, tools/ and potentials/ come from (--decks)

# the full preset's discs and the scenes' materials (examples/scene/params.in,
# potentials/cover_paper.params)
RMIN, RMAX, DIST = 6.25, 15.625, "paper"
RHO = 2200.0
ETA = 5e8
K_SALT = 1e9
KN_WALL = 1e10
KN_COVER, KT_COVER, MU_COVER = 2.5e9, 8e8, 0.5
COH_COVER, TEN_COVER, RNG_COVER = 2.8e8, 2.8e8, 0.224
ZN_COVER, ZT_COVER, KR_COVER, MUR_COVER = 0.3, 0.3, 2.5e9, 0.16
CSALT_CAL = 0.5

XREF = 0.5          # first run: half the reported limit
X_SETTLE = 0.5      # settling (and the run 0 that passes the check) at this fraction
GROW = 10.0         # kinetic energy above GROW x the nearest stable run's largest: unstable

LIMIT_RE = re.compile(r"Pair style (\S+): timestep (\S+) = (\S+) of the stable limit (\S+) \((.*)\)\s*$")


def r2mean(rmin, rmax, dist):
    """Mean squared radius of tools/pack.in's distributions."""
    if dist == "uniform":
        return (rmax ** 3 - rmin ** 3) / (3 * (rmax - rmin))
    q = 1.7522293
    return ((rmax ** (3 - q) - rmin ** (3 - q)) / (3 - q)) / ((rmax ** (1 - q) - rmin ** (1 - q)) / (1 - q))


def h_scene(hfac=1.3, rmin=RMIN, rmax=RMAX, dist=DIST):
    """SPH smoothing length of the scenes: hfac disc spacings sqrt(pi <r^2> / 0.85)."""
    return hfac * math.sqrt(math.pi * r2mean(rmin, rmax, dist) / 0.85)


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
        t0 = os.times()
        try:
            rc = subprocess.run(cmd, cwd=self.work, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, timeout=self.timeout).returncode
        except subprocess.TimeoutExpired:
            rc = -999
        t1 = os.times()
        text = log.read_text(errors="replace") if log.exists() else ""
        return rc, text, (t1.children_user - t0.children_user) + (t1.children_system - t0.children_system)

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


# ---- decks ------------------------------------------------------------------------------------

HEAD = """# generated by bench/validation/stable_limit.py ({name})
units           si
dimension       2
atom_style      sphere
boundary        p fm p
comm_modify     vel yes
newton          off
read_data       {pack} extra/atom/types 2
# bands of 2 rmax at the bottom (fixed wall) and top (the lid), the rest is the material
region          lo block INF INF INF $(ylo+{band}) INF INF units box
region          hi block INF INF $(yhi-{band}) INF INF INF units box
group           bot region lo
group           top region hi
group           walls union bot top
group           mat subtract all walls
set             group mat type {mtype}
set             group walls type 3
set             group all density/disc {rho}
variable        Wc equal $(xhi-xlo)
variable        y0 equal $(ylo+{band})
variable        y1 equal $(yhi-{band})
change_box      all y final $(ylo-{band}) $(yhi+4*{band}) units box
"""

# the reported limit: walls static (as the scenes' walls), material integrated
REPORT = """timestep        1e-9
thermo_style    custom step
run             0
print           REPORTED_DONE
"""

# the lid: a rigid band (equal masses: fix aveforce gives equal forces), x velocity V, y free
# under P*W (P > 0, the load ramping up over tload s) or held (P = 0).  Its inertia is
# lid_scale = 3 S times its mass, enough that it sets no limit of its own: for the fluid law by
# fix saltdem/nve (the fluid law exerts no torque; the volumes, m/rho0 for a boundary particle,
# keep the true mass), for the contact laws by fix nve on a heavier mass (no spin; contact laws
# use no volumes).  Under load it settles with a critical drag on its bounce on the material
# below (stiffness E W / H, E = K for the fluid, kn for discs in contact), removed afterwards.
LID = """variable        mlid equal $(mass(top)/count(top))
set             group top mass ${{mlid}}
velocity        top set {V} 0 0 units box
{lidint}
variable        fload equal -{P}*${{Wc}}/$(count(top))*((time/{tload})*(time<{tload})+(time>={tload}))
{lidload}
fix             lidx top setforce 0 {lidy} 0
"""


TRIAL = """# settle at X_SETTLE, then the trial
timestep        {dt_settle}
compute         ke0 mat ke
variable        v2 atom vx*vx+vy*vy
compute         v2max mat reduce max v_v2
variable        vmax equal sqrt(c_v2max)
variable        ylid equal xcm(top,y)
thermo_style    custom step time c_ke0 v_vmax v_ylid
thermo_modify   norm no format float %.8g
thermo          {nthermo_settle}
run             {nsettle}
{post_settle}
run             0
{switch}
thermo          {nthermo}
print           STABLE_RUN
run             {nsteps} pre no
print           "STABLE_DONE"
"""


def lid_scale(c):
    return 3.0 * c["S"]


def lid_integrator(c):
    if c["law"] == "fluid":
        return f"fix             lidint top saltdem/nve inertia {lid_scale(c)}"
    return f"""variable        mheavy atom mass*{lid_scale(c)}
set             group top mass v_mheavy
fix             lidint top nve"""


def lid_load(c):
    """The load on the lid, and its drag while settling (P > 0)."""
    if c["P"] <= 0:
        return ""
    E = c["K"] if c["law"] == "fluid" else KN_COVER
    inertia = lid_scale(c) if c["law"] == "fluid" else 1.0    # (else already in the mass)
    return f"""fix             load top aveforce NULL v_fload NULL
variable        glid equal 2*sqrt({E}*${{Wc}}/(${{y1}}-${{y0}})*mass(top)*{inertia})/count(top)
fix             liddamp top viscous ${{glid}}"""


def fluid_deck(c, dt_settle, x, limit):
    """SPH or contact salt in Couette flow (c: case parameters)."""
    h = c["h"]
    if c["law"] == "fluid":
        # as examples/scene/laws.in: the walls are boundary particles (3 3 none), not fluid
        pair = f"""pair_style      hybrid saltdem/viscous {c.get('extra', '')}
pair_coeff      * * none
pair_coeff      2 2 saltdem/viscous {ETA} 0 fluid {h} {c['K']}
pair_coeff      2 3 saltdem/viscous {ETA} {c['kn_wall']} fluid {h} {c['K']}
pair_coeff      3 3 none
neighbor        {0.1 * h} bin"""
    else:
        pair = f"""pair_style      hybrid saltdem/viscous calibration {CSALT_CAL}
pair_coeff      * * none
pair_coeff      2 2 saltdem/viscous {ETA} {KN_COVER} contact 0
pair_coeff      2 3 saltdem/viscous {ETA} {c['kn_wall']} contact 0
pair_coeff      3 3 none
neighbor        {0.2 * c['rmin']} bin"""
    deck = HEAD.format(name=c["name"], pack=c["pack"], band=2 * c["rmax"], mtype=2, rho=RHO)
    deck += pair + f"""
neigh_modify    exclude type 3 3
neigh_modify    every 1 delay 0 check yes
fix             integ mat saltdem/nve inertia {c['S']} check 10
""" + REPORT
    P = c["P"]
    deck += LID.format(V=c["V"], P=P, tload=c.get("tload", 1e-9), lidload=lid_load(c),
                       lidy="NULL" if P > 0 else "0", lidint=lid_integrator(c))
    ramp = f"velocity        mat ramp vx 0 {c['V']} y ${{y0}} ${{y1}} units box"
    post_settle = ""
    if P > 0:
        # loaded: the load ramps up over tload while a drag (as the scenes settle) calms the
        # salt; then the shear starts from the linear profile
        deck += f"velocity        top set 0 0 0\n"
        deck += f"fix             calm mat viscous {0.5 * RHO * math.pi * c['rmin'] ** 2 * c['S']}\n"
        post_settle = (f"unfix           calm\nunfix           liddamp\n{ramp}\n"
                       f"velocity        top set {c['V']} 0 0 units box")
    else:
        deck += ramp + "\n"
    ns = c["nsettle"]
    switch = f"timestep        {x * limit}"
    deck += TRIAL.format(dt_settle=dt_settle, nsettle=ns, nthermo_settle=max(1, ns // 5),
                         post_settle=post_settle, switch=switch, nthermo=max(1, c["nsteps"] // 40),
                         nsteps=c["nsteps"])
    return deck


def cover_deck(c, dt_settle, x, limit):
    """The cover between a fixed band and a weighted lid; the trial by the mass switch."""
    kw = c["kn_wall"]
    deck = HEAD.format(name=c["name"], pack=c["pack"], band=2 * c["rmax"], mtype=1, rho=RHO)
    deck += f"""pair_style      hybrid saltdem/cohesive
pair_coeff      * * none
pair_coeff      1 1 saltdem/cohesive {KN_COVER} {KT_COVER} {MU_COVER} {COH_COVER} {TEN_COVER} {RNG_COVER} damp {ZN_COVER} {ZT_COVER} rolling {KR_COVER} {MUR_COVER}
pair_coeff      1 3 saltdem/cohesive {kw} {KT_COVER} 1.0 {COH_COVER} 0 0
pair_coeff      3 3 none
neighbor        {0.2 * c['rmin']} bin
neigh_modify    exclude type 3 3
fix             integ mat saltdem/nve inertia {c['S']} check 10
""" + REPORT
    P = c["P"]
    deck += LID.format(V=c["V"], P=P, tload=c["tload"], lidload=lid_load(c),
                       lidy="NULL" if P > 0 else "0", lidint=lid_integrator(c))
    Y = (x / X_SETTLE) ** 2
    # settled under the load with a drag (as the scenes settle) and at rest; then the mass
    # switch: every integrated mass / Y (the lid's too), same dt: the run at dt * sqrt(Y) =
    # x * limit with the true masses
    deck += f"fix             calm mat viscous {0.5 * RHO * math.pi * c['rmin'] ** 2 * c['S']}\n"
    post_settle = """unfix           calm
unfix           liddamp
velocity        mat set 0 0 0
velocity        top set 0 0 0"""
    switch = f"""variable        mnew atom mass/{Y}
set             group mat mass v_mnew
set             group top mass v_mnew"""
    deck += TRIAL.format(dt_settle=dt_settle, nsettle=c["nsettle"],
                         nthermo_settle=max(1, c["nsettle"] // 5), post_settle=post_settle, switch=switch,
                         nthermo=max(1, c["nsteps"] // 40), nsteps=c["nsteps"])
    return deck


# ---- measurement ------------------------------------------------------------------------------

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


# ---- the real scene ---------------------------------------------------------------------------
# examples/expt1.in as it is, with examples/scene/frames.in (the drive to the frames) replaced:
# 'settle' writes the settled scene to a restart file, 'trial' resumes it (the scene's own
# resume path) and drives the fault for nsteps at X * L.  The trial is a dt switch; the cover's
# saltdem/cohesive keeps the time step of its init (dt0) for its tangential and rolling springs,
# so the scene settles and runs with kt, kr x R and zeta_t / sqrt(R) (the same dashpot 2 zeta_t
# sqrt(m kt)) and the trial's init is at dt0 = X L / R: after the switch the springs are those of
# the scene (kt x R x dt0 / dt = kt) and their forces carry on from the settled state.  The
# settling is therefore that of a cover with R times stiffer tangential and rolling springs, at
# the scene's own time step (0.85 L); the pair styles get dtfactor 0.75 and viscfactor 1 so that
# their check accepts it.

SCENE_PROBE = """# stable_limit.py: the scene's reported limit (laws.in has logged it): stop here
print           PROBE_DONE
"""

SCENE_TRIAL = """# stable_limit.py: settle (write the settled scene) or trial (the drive at xtrial x Lrep)
if "${slmode} == settle" then "write_restart ${settled}" "jump SELF sl_end"
thermo_style    custom step time c_kec c_kes f_fault[1]
thermo_modify   norm no format float %.8g
timestep        $(v_xtrial*v_Lrep/v_R)
run             0
timestep        $(v_xtrial*v_Lrep)
thermo          $(ceil(v_nsteps/40))
print           STABLE_RUN
run             ${nsteps} pre no
print           STABLE_DONE
label           sl_end
"""

SCENE_LIMIT_RE = re.compile(r"saltdem/timestep: timestep (\S+) = (\S+) of the stable limit (\S+) of "
                            r"pair style (\S+) \((.*)\)\s*$")


class SceneCase(Bisect):
    ke_keys = ("c_kec", "c_kes")

    def __init__(self, runner, preset, nsteps, tol, R=8.0, width=None, nsettle=None,
                 pack_kelim=None, extra=()):
        super().__init__(runner, f"expt1_{preset}", nsteps, tol)
        self.preset, self.R = preset, R
        self.dir = runner.work / f"scene_{preset}"
        self.dir.mkdir(parents=True, exist_ok=True)
        self.base = [("preset", preset), ("target", 20)] + list(extra)
        if width:
            self.base.append(("width", width))
        self.nsettle = nsettle
        self.roots = {m: self.make_root(m, pack_kelim) for m in ("probe", "trial")}

    def make_root(self, mode, pack_kelim):
        """A copy of the repository's scene files (links) with frames.in (and laws.in) replaced."""
        root = self.dir / f"root_{mode}"
        scene = root / "examples" / "scene"
        scene.mkdir(parents=True, exist_ok=True)
        (root / "tools").mkdir(exist_ok=True)
        for f in [DECKS / "examples" / "expt1.in"] + sorted((DECKS / "examples" / "scene").glob("*.in")):
            link = root / f.relative_to(DECKS)
            if f.name not in ("laws.in", "frames.in") and not link.exists():
                link.symlink_to(f)
        if not (root / "potentials").exists():
            (root / "potentials").symlink_to(DECKS / "potentials")
        laws = (DECKS / "examples/scene/laws.in").read_text()
        pack = (DECKS / "tools" / "pack.in").read_text()
        if pack_kelim:   # a looser settling criterion of the pack (the scene settles it further)
            pack = pack.replace("equal 1e-6*count(all)", f"equal {pack_kelim}*count(all)")
        if mode == "trial":
            if "hybrid saltdem/cohesive saltdem/viscous" not in laws:
                raise RuntimeError("examples/scene/laws.in: no 'hybrid saltdem/cohesive saltdem/viscous' "
                                   "pair style to give dtfactor/viscfactor to")
            laws = laws.replace('"hybrid saltdem/cohesive saltdem/viscous',
                                '"hybrid saltdem/cohesive dtfactor 0.75 saltdem/viscous viscfactor 1 dtfactor 0.75')
            laws = laws.replace("'hybrid saltdem/cohesive saltdem/viscous",
                                "'hybrid saltdem/cohesive dtfactor 0.75 saltdem/viscous viscfactor 1 dtfactor 0.75")
        (scene / "laws.in").write_text(laws)
        (root / "tools" / "pack.in").write_text(pack)
        (scene / "frames.in").write_text(SCENE_PROBE if mode == "probe" else SCENE_TRIAL)
        return root

    def lmp(self, mode, name, variables):
        root = self.roots[mode]
        cmd = [self.r.lmp, "-in", str(root / "examples" / "expt1.in"), "-log", f"{name}.log",
               "-screen", "none", "-nocite", "-var", "root", str(root)]
        for k, v in self.base + list(variables):
            cmd += ["-var", k, str(v)]
        t0 = os.times()
        try:
            rc = subprocess.run(cmd, cwd=self.dir, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                timeout=self.r.timeout).returncode
        except subprocess.TimeoutExpired:
            rc = -999
        t1 = os.times()
        log = self.dir / f"{name}.log"
        text = log.read_text(errors="replace") if log.exists() else ""
        return rc, text, (t1.children_user - t0.children_user) + (t1.children_system - t0.children_system)

    def compensated(self):
        R = self.R
        return [("kt_cover", KT_COVER * R), ("kr_cover", KR_COVER * R), ("zt_cover", ZT_COVER / math.sqrt(R))]

    def probe_limit(self):
        rc, text, cpu = self.lmp("probe", "probe", [("nsettle", 0)])
        m = None
        for line in text.splitlines():
            m = SCENE_LIMIT_RE.search(line) or m
        if rc != 0 or not m:
            raise RuntimeError(f"{self.name}: no limit (rc {rc}), see {self.dir}/probe.log")
        self.limit, self.style, self.why = float(m.group(3)), m.group(4), m.group(5)
        self.dt_scene = float(m.group(1))
        print(f"  {self.name}: reported limit {self.limit:.5g} s ({self.style}: {self.why}); "
              f"the scene's dt {self.dt_scene:.5g} s ({cpu:.0f} CPU s with the pack)", flush=True)
        return self.limit

    def settle(self):
        self.settled = self.dir / "settled.restart"
        if self.settled.exists():
            return
        extra = [("nsettle", self.nsettle)] if self.nsettle else []
        rc, text, cpu = self.lmp("trial", "settle", [("slmode", "settle"), ("dt", self.dt_scene),
                                                     ("settled", "settled.restart.tmp")]
                                 + self.compensated() + extra)
        if rc != 0:
            raise RuntimeError(f"{self.name}: settling failed (rc {rc}), see {self.dir}/settle.log")
        (self.dir / "settled.restart.tmp").rename(self.settled)
        print(f"  {self.name}: settled ({cpu:.0f} CPU s)", flush=True)

    def run_x(self, x):
        return self.lmp("trial", f"trial_x{x:.4f}",
                        [("slmode", "trial"), ("restart", "settled.restart"), ("xtrial", x),
                         ("Lrep", self.limit), ("R", self.R), ("nsteps", self.nsteps)]
                        + self.compensated())


# ---- what kn_wall changes ---------------------------------------------------------------------
# A small settled scene with the scenes' own laws (examples/scene/params.in and laws.in, the full
# preset): a salt layer and a cover on a basement line of wall discs (saltdem/wall, radius rmin,
# as the scenes), x periodic, under gravity and a weighted lid (a rigid line of wall discs) that
# brings the salt's base to about Pbase.  After settling the lid moves at V in x and drags the
# cover, which shears the salt over the basement.  Measured: the overlaps of salt and cover with
# the wall discs, how deep discs reach below the basement's top (y = 0) or above the lid's
# bottom, the no-slip offset of the salt's velocity profile at the basement and the limit the
# styles report.

WALL_DECK = """# generated by bench/validation/stable_limit.py (kn_wall study, kn_wall {knw:g})
variable        root index {root}
variable        preset index full
variable        kn_wall index {knw}
variable        nsettle index {nsettle}
include         ${{root}}/examples/scene/params.in
units           si
dimension       2
atom_style      sphere
boundary        p f p
comm_modify     vel yes
newton          on
atom_modify     map array
read_data       {pack} extra/atom/types 2
variable        Wc equal $(xhi-xlo)
variable        ytop equal $(bound(all,ymax)+{rmax})
change_box      all y final $(-4*v_rmin) $(v_ytop+8*v_rmax) units box
group           pack type 1
region          rsalt block INF INF INF {hsalt} INF INF units box
group           salt region rsalt
group           cover subtract pack salt
set             group salt type 2
set             group pack density/disc ${{rho}}
variable        r2salt equal mass(salt)/(count(salt)*${{rho}}*PI)
fix             mark all property/atom i_marker ghost yes
variable        rw equal ${{rmin}}
saltdem/wall    3 ${{rw}} $(-v_rw) $(v_Wc-v_rw) $(-v_rw) ${{rw}} group base
saltdem/wall    3 ${{rw}} $(v_ytop+v_rw) $(v_Wc-v_rw) $(v_ytop+v_rw) ${{rw}} group lid
fix             grav pack gravity 9.81 vector 0 -1 0
include         ${{root}}/examples/scene/laws.in
# the lid: rigid, heavy (no limit of its own), loaded to P over tload, then the scene's calm
variable        mheavy atom mass*{slid}
set             group lid mass v_mheavy
fix             lidint lid nve
variable        fload equal -{plid}*${{Wc}}/$(count(lid))*((time/{tload})*(time<{tload})+(time>={tload}))
fix             load lid aveforce NULL v_fload NULL
fix             lidx lid setforce 0 NULL 0
fix             calm pack viscous $(0.5*v_rho*PI*v_rmin^2)
reset_timestep  0
thermo          1000
run             {nload}
unfix           calm
velocity        pack set 0 0 0
write_dump      all custom wall_{knw:g}_settled.txt id type x y radius modify sort id
# shear: the lid (and the cover it carries) at V in x, the salt from the linear profile
velocity        lid set {V} 0 0 units box
velocity        cover set {V} 0 0 units box
velocity        salt ramp vx 0 {V} y 0 {hsalt} units box
compute         layers salt chunk/atom bin/1d y 0 {dy} units box
fix             prof salt ave/chunk 10 $(floor({nshear}/10)) {nshear} layers vx file wall_{knw:g}_profile.txt
compute         vcov cover reduce ave vx
fix             vc all ave/time 10 $(floor({nshear}/10)) {nshear} c_vcov file wall_{knw:g}_vcover.txt
run             $({nshear}*{nblock})
write_dump      all custom wall_{knw:g}_sheared.txt id type x y radius modify sort id
print           WALL_DONE
"""


def read_dump(path):
    """The box width and the id type x y radius rows of a write_dump file."""
    lines = pathlib.Path(path).read_text().splitlines()
    b = next(k for k, ln in enumerate(lines) if ln.startswith("ITEM: BOX"))
    xlo, xhi = (float(v) for v in lines[b + 1].split()[:2])
    i = next(k for k, ln in enumerate(lines) if ln.startswith("ITEM: ATOMS"))
    return xhi - xlo, [tuple(float(v) for v in ln.split()) for ln in lines[i + 1:] if ln.strip()]


def wall_contacts(rows, box_w, walls, movers):
    """Overlaps (m) of the discs of types movers with the wall discs (ids in walls)."""
    wl = [r for r in rows if int(r[0]) in walls]
    out = []
    for a in rows:
        if int(a[1]) not in movers:
            continue
        for w in wl:
            dx = a[2] - w[2]
            dx -= box_w * round(dx / box_w)
            d = math.hypot(dx, a[3] - w[3])
            ov = a[4] + w[4] - d
            if ov > 0:
                out.append((ov, a[4]))
    return out


def chunk_blocks(path):
    """The blocks of a fix ave/chunk file: a list of lists of rows."""
    rows = [[float(x) for x in ln.split()] for ln in pathlib.Path(path).read_text().splitlines()
            if ln.strip() and not ln.startswith("#")]
    heads = [k for k, v in enumerate(rows) if len(v) == 3]
    return [rows[h + 1:h + 1 + int(rows[h][1])] for h in heads]


def line_fit(pts):
    n = len(pts)
    my = sum(p[0] for p in pts) / n
    mv = sum(p[1] for p in pts) / n
    slope = sum((p[0] - my) * (p[1] - mv) for p in pts) / sum((p[0] - my) ** 2 for p in pts)
    return my, mv, slope


def wall_study(runner, knws, nsettle=10000, nload=10000, nshear=5000, nblock=7, V=0.05, hsalt=250.0,
               hcover=250.0, pbase=2e7):
    pack = runner.pack(500, int(hsalt + hcover), kn=KN_COVER)
    rho_eff = RHO * 0.85
    plid = pbase - rho_eff * 9.81 * (hsalt + hcover)
    res = {}
    for knw in knws:
        deck = WALL_DECK.format(root=DECKS, knw=knw, nsettle=nsettle, pack=pack.name, rmax=RMAX,
                                hsalt=hsalt, slid=60.0, plid=plid, tload=10.0, nload=nload, V=V,
                                dy=RMAX, nshear=nshear, nblock=nblock)
        name = f"wall_{knw:g}"
        rc, text, cpu = runner.run(name, deck)
        if rc != 0 or "WALL_DONE" not in text:
            raise RuntimeError(f"{name}: failed (rc {rc}), see {runner.work}/{name}.log")
        m = [SCENE_LIMIT_RE.search(ln) for ln in text.splitlines()]
        m = [x for x in m if x][0]
        r = {"limit": float(m.group(3)), "why": m.group(5), "cpu_s": round(cpu, 1), "plid": plid}
        for stage in ("settled", "sheared"):
            W, rows = read_dump(runner.work / f"wall_{knw:g}_{stage}.txt")
            base = {int(x[0]) for x in rows if int(x[1]) == 3 and x[3] < 0}
            lid = {int(x[0]) for x in rows if int(x[1]) == 3 and x[3] > 0}
            ylid = min(x[3] - x[4] for x in rows if int(x[0]) in lid)
            s_ov = wall_contacts(rows, W, base, {2})
            c_ov = wall_contacts(rows, W, lid, {1})
            r[stage] = {
                "salt_base_overlap_mean": sum(o for o, _ in s_ov) / max(1, len(s_ov)),
                "salt_base_overlap_max": max((o for o, _ in s_ov), default=0.0),
                "salt_base_overlap_max_per_r": max((o / a for o, a in s_ov), default=0.0),
                "salt_base_contacts": len(s_ov),
                "salt_lowest_bottom": min(x[3] - x[4] for x in rows if int(x[1]) == 2),
                "salt_lowest_centre": min(x[3] for x in rows if int(x[1]) == 2),
                "cover_lid_overlap_mean": sum(o for o, _ in c_ov) / max(1, len(c_ov)),
                "cover_lid_overlap_max": max((o for o, _ in c_ov), default=0.0),
                "cover_lid_overlap_max_per_r": max((o / a for o, a in c_ov), default=0.0),
                "cover_top_above_lid_bottom": max(x[3] + x[4] for x in rows if int(x[1]) == 1) - ylid,
            }
        # the no-slip plane of the base in each block of the shear (the first left out: start-up)
        blocks = chunk_blocks(runner.work / f"wall_{knw:g}_profile.txt")
        vcov = [float(ln.split()[1]) for ln in (runner.work / f"wall_{knw:g}_vcover.txt").read_text()
                .splitlines() if ln.strip() and not ln.startswith("#")]
        y0s, y1s, slopes = [], [], []
        for blk, vc in list(zip(blocks, vcov))[1:]:
            my, mv, slope = line_fit([(y, vx) for _, y, n, vx in blk
                                      if n > 0 and 3 * RMAX < y < hsalt - 3 * RMAX])
            y0s.append(my - mv / slope)
            y1s.append(my + (vc - mv) / slope)
            slopes.append(slope)
        mean = lambda v: sum(v) / len(v)
        sd = lambda v: math.sqrt(sum((x - mean(v)) ** 2 for x in v) / max(1, len(v) - 1))
        y0 = mean(y0s)
        r.update({"vcover": vcov, "slopes": slopes, "noslip_base_y": y0s, "noslip_cover_y": y1s,
                  "noslip_base_mean": y0, "noslip_base_sd": sd(y0s),
                  "noslip_cover_mean": mean(y1s), "noslip_cover_sd": sd(y1s)})
        res[f"{knw:g}"] = r
        print(f"  kn_wall {knw:g}: limit {r['limit']:.4g} s; salt-base overlap mean "
              f"{r['settled']['salt_base_overlap_mean']:.3g} m max {r['settled']['salt_base_overlap_max']:.3g} m; "
              f"no-slip plane of the base at y = {y0:.2f} +- {r['noslip_base_sd']:.2f} m ({cpu:.0f} CPU s)", flush=True)
    return res


def component_cases():
    """The component cases: name, law, parameters and the pack they need (made when run)."""
    h = h_scene()
    base = dict(K=K_SALT, kn_wall=KN_WALL, S=20, V=0.05, P=0.0, nsettle=500, h=round(h, 3),
                rmin=RMIN, rmax=RMAX)
    salt_pack = (500, 350, {})
    cases = []
    for name, over in [
            ("fluid", {}),
            ("fluid_P20", {"P": 2e7, "tload": 2.0, "nsettle": 10000}),
            ("fluid_h1.1", {"h": round(h_scene(1.1), 3)}),
            ("fluid_h1.6", {"h": round(h_scene(1.6), 3)}),
            ("fluid_S5", {"S": 5}),
            ("fluid_S80", {"S": 80}),
            ("fluid_K1e8", {"K": 1e8}),
            ("fluid_K1e10", {"K": 1e10}),
            ("fluid_P20_knw2.5e9", {"P": 2e7, "tload": 2.0, "nsettle": 10000, "kn_wall": 2.5e9}),
            # large S: the viscous limit (~ S) meets the sound limit (~ sqrt(S)); the salt-wall
            # core, which the load presses into the walls, far below both
            ("fluid_P20_S200", {"P": 2e7, "tload": 6.0, "nsettle": 10000, "S": 200}),
            ("fluid_P20_S2000", {"P": 2e7, "tload": 20.0, "nsettle": 10000, "S": 2000}),
            # the no-slip plane at the wall discs' surfaces (the wall pairs' viscosity up to
            # 1 + NOSLIP_MAX times stronger), and with the boundary fill (up to 8x more)
            ("fluid_noslip", {"extra": "noslip surface"}),
            ("fluid_P20_noslip", {"P": 2e7, "tload": 2.0, "nsettle": 10000,
                                  "extra": "noslip surface"}),
            ("fluid_noslip_fill8", {"extra": "noslip surface fill 8"}),
    ]:
        cases.append(dict(base, name=name, law="fluid", pack_spec=salt_pack, **over))
    # the quick preset's discs (uniform 25-62.5 m) and inertia (S 4)
    cases.append(dict(base, name="fluid_quickdiscs", law="fluid", rmin=25.0, rmax=62.5, S=4,
                      h=round(h_scene(1.3, 25.0, 62.5, "uniform"), 3),
                      pack_spec=(2000, 1400, {"rmin": 25.0, "rmax": 62.5, "dist": "uniform"})))
    for name, over in [
            ("contact", {}),
            ("contact_P20", {"P": 2e7, "tload": 2.0, "nsettle": 10000}),
    ]:
        cases.append(dict(base, name=name, law="contact", pack_spec=salt_pack, **over))
    for name, over in [
            ("cover_P20", {"kn_wall": KN_WALL}),
            ("cover_P20_knw2.5e9", {"kn_wall": 2.5e9}),
    ]:
        cases.append(dict(base, name=name, law="cover", pack_spec=(400, 300, {"kn": KN_COVER}),
                          P=2e7, tload=4.0, nsettle=3000, V=0.0, **over))
    return cases


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lmp", default=lmp_path(ROOT))
    ap.add_argument("--work", default=str(ROOT / "out" / "stable"))
    ap.add_argument("--cases", default="fluid,contact,cover",
                    help="comma list of fluid, contact, cover, or case names")
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--tol", type=float, default=0.03, help="bisection: hi/lo - 1 at the end")
    ap.add_argument("--timeout", type=float, default=3600)
    ap.add_argument("--table", default=None)
    ap.add_argument("--scene", choices=["quick", "full"], help="bisect the real Expt 1 scene instead")
    ap.add_argument("--width", type=float, help="scene: section width (m), default the deck's")
    ap.add_argument("--nsettle", type=int, help="scene: settling steps, default the preset's")
    ap.add_argument("--R", type=float, default=8.0, help="scene: dt switch factor of the cover springs")
    ap.add_argument("--wall-study", action="store_true",
                    help="what kn_wall 2.5e9 and 1e10 change in a small settled scene")
    ap.add_argument("--pack-kelim", type=float, help="scene: settling criterion of tools/pack.in "
                    "(kinetic energy per disc / m g r, default the tool's 1e-6)")
    ap.add_argument("--decks", default=str(ROOT), help="where examples/, tools/ and potentials/ "
                    "come from (default: this repository)")
    args = ap.parse_args()
    global DECKS
    DECKS = pathlib.Path(args.decks).resolve()

    runner = Runner(args.lmp, args.work, args.timeout)
    resfile = pathlib.Path(args.work) / "results.json"
    results = json.loads(resfile.read_text()) if resfile.exists() else {}
    if args.wall_study:
        results["wall_study"] = wall_study(runner, [2.5e9, 1e10])
        resfile.write_text(json.dumps(results, indent=1))
        return
    if args.scene:
        sc = SceneCase(runner, args.scene, args.steps, args.tol, R=args.R, width=args.width,
                       nsettle=args.nsettle, pack_kelim=args.pack_kelim)
        t0 = time.time()
        sc.probe_limit()
        sc.settle()
        lo, hi = sc.measure(xmax=args.R)
        results[sc.name] = {"params": {"preset": args.scene, "width": args.width, "nsettle": args.nsettle,
                                       "R": args.R, "steps": args.steps},
                            "limit": sc.limit, "style": sc.style, "why": sc.why, "dt_scene": sc.dt_scene,
                            "x_stable": lo, "x_unstable": hi, "runs": sc.runs,
                            "wall_s": round(time.time() - t0)}
        resfile.write_text(json.dumps(results, indent=1))
        print(f"{sc.name}: reported limit {sc.limit:.5g} s; stable up to X {lo:.3f}, unstable at "
              f"{hi if hi else '-'}", flush=True)
        if args.table:
            pathlib.Path(args.table).write_text(table(results))
        return
    which = args.cases.split(",")
    sel = [c for c in component_cases() if c["law"] in which or c["name"] in which]
    for c in sel:
        W, H, kw = c.pop("pack_spec")
        c["pack"] = runner.pack(W, H, **kw).name
        case = Case(runner, c, args.steps, args.tol)
        t0 = time.time()
        case.probe_limit()
        lo, hi = case.measure()
        results[c["name"]] = {"params": c, "limit": case.limit, "style": case.style, "why": case.why,
                              "x_stable": lo, "x_unstable": hi, "runs": case.runs,
                              "wall_s": round(time.time() - t0)}
        resfile.write_text(json.dumps(results, indent=1))
        print(f"{c['name']}: reported limit {case.limit:.5g} s ({case.why}); stable up to X {lo:.3f}, "
              f"unstable at {hi if hi else '-'}", flush=True)
    if args.table:
        pathlib.Path(args.table).write_text(table(results))


def what_sets(why):
    """A short name for the limit a log line names."""
    types = re.search(r"of types (\d+) (\d+)", why)
    t = f" {types.group(1)}-{types.group(2)}" if types else ""
    if "h^2" in why:
        return "fluid viscosity" + t
    if "calibration" in why:
        return "contact dashpots" + t
    if "sound" in why:
        return "sound" + t
    m = re.match(r"(kn|kt) = (\S+)", why)
    if m:
        return f"elastic {m.group(1)} {float(m.group(2)):g}" + t
    return why[:40]


def table(results):
    lines = ["| case | reported limit L (s) | set by | stable up to X | unstable at X | "
             "measured limit (s) |", "| --- | --- | --- | --- | --- | --- |"]
    for name, r in results.items():
        if "limit" not in r or "x_stable" not in r:
            continue
        hi = f"{r['x_unstable']:.2f}" if r["x_unstable"] else f"> {r['x_stable']:.2f}"
        lines.append(f"| {name} | {r['limit']:.4g} | {what_sets(r['why'])} | {r['x_stable']:.2f} | {hi} | "
                     f"{r['x_stable'] * r['limit']:.4g} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
