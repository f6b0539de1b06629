"""The real scene of stable_limit.py (--scene): examples/expt1.in as it is, its frames replaced,
settled once and bisected by a dt switch on resumes of the settled scene."""
import math

import stable_run
from stable_bisect import Bisect
from stable_cases import KR_COVER, KT_COVER, ZT_COVER
from stable_run import SCENE_LIMIT_RE, run_logged

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
        DECKS = stable_run.DECKS    # (--decks)
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
        return run_logged(cmd, self.dir, self.dir / f"{name}.log", self.r.timeout)

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
