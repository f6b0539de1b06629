"""Reliability matrix, fast part (CI): stiff and extreme cases, bad input, restart, MPI/OpenMP
and memory.  The matrix with every case, its expected behaviour and its test is
docs/reliability.md; the long cases are tests/test_reliability_long.py (`-m long`).

Most cases run tests/decks/scene_mini.in: a small scene of the paper's kind (cover over salt
on a basement whose hanging wall moves down a 30 degree fault, the interactions of
examples/scene/laws.in, gravity) at the resolution of the scene's "quick" preset (discs 25-62.5
m, dt 0.0025 s, inertia factor S 4) or of the paper (6.25-15.625 m, dt 0.002 s, S 20), with the
material defaults of examples/scene/params.in (kn_cover = kn_wall = 1e10 N/m, eta 5e8 Pa s).

"Stable" below means: the run ends normally, every thermo value is finite (and fix
saltdem/nve checked positions and velocities every 10 steps), no atom is lost, and the energy
balance holds: the energy of the scaled dynamics E = S KE + PE (pair + gravity) minus the work
W that the moving hanging wall has done on the pack never rises above its initial value by
more than 1e-3 of the scene's M g H.  Contacts, damping and viscosity only dissipate, so
E - W cannot grow unless the integration is unstable.
"""
import math
import re
import subprocess
import time

import numpy as np
import pytest

from lmprun import ROOT, assert_error, check_ok, lmp_path, run_lmp
from reliability_lib import (PRESETS, SCENE_DECK, Scene, all_finite, heap_mb, max_rel_diff,
                             mpirun_cmd, read_dump, run_watched)

E_TOL = 1e-3          # energy may exceed its start by this fraction of M g H (integration noise)
MPI_TOL = 1e-8        # np 1 / np 2 / 2 threads: positions agree to this fraction of the box
RESTART_TOL = 1e-10   # split run vs restart: positions to this fraction of the box (one rank)


# ---------------------------------------------------------------------------------------------
# the scenes: generated, settled once per module under gravity (fix viscous damping)
# ---------------------------------------------------------------------------------------------

SETTLE = """
fix calm pack viscous $(0.5*v_rho*PI*v_rmin^2)
thermo 2000
run ${nsettle}
unfix calm
velocity pack set 0 0 0
write_data settled.data
"""


def settled_scenes(kinds, tmp_path_factory, settle):
    """get(name[, settle]) -> (Scene, settled data file) for the Scene makers in `kinds`, each
    generated and settled once (the scenes fixtures of this module and the long one)."""
    cache = {}

    def get(name, settle=settle):
        if name not in cache:
            s = kinds[name]()
            d = tmp_path_factory.mktemp(f"scene_{name}")
            s.write(d / "scene.data")
            r = run_lmp(SCENE_DECK + SETTLE, d, **s.variables(data=d / "scene.data",
                                                              nsettle=settle))
            check_ok(r)
            cache[name] = (s, d / "settled.data")
        return cache[name]

    return get


@pytest.fixture(scope="module")
def scenes(tmp_path_factory):
    """scenes(name) -> (Scene, settled data file); made once per module."""
    kinds = {
        "quick": lambda: Scene("quick"),
        "paper": lambda: Scene("paper"),
        "weld": lambda: Scene("quick", weld=True, target=62.5),
        # salt 2 rmax (125 m) thin, fault 2.5 x that along the fault (throw 156 m > 125 m)
        "thin": lambda: Scene("quick", salt=2, cover=6, target=312.5),
        # room for the hanging wall to travel 500 m (memory runs)
        "long": lambda: Scene("quick", target=500.0),
    }
    return settled_scenes(kinds, tmp_path_factory, 12000)


def run_scene(workdir, scene, data, tail, np=1, omp=0, timeout=600, args=(), **over):
    return run_lmp(SCENE_DECK + tail, workdir, np=np, omp=omp, timeout=timeout, args=args,
                   **scene.variables(data=data, **over))


# energy of the scaled dynamics (KE with the inertia factors, PE = pair + gravity) and the
# work the moving hanging wall has done on the pack (-F.v of its discs, summed over the steps)
ENERGY = """
compute kecov cover ke
compute kesalt salt ke
variable etot equal ${S_cover}*c_kecov+${S}*c_kesalt+pe
variable pwall atom fx*vx+fy*vy
compute pwall hanging reduce sum v_pwall
variable pw equal -c_pwall
fix wfault all ave/time 1 1 1 v_pw ave running
variable step0 equal $(step)
variable wfault equal f_wfault*(step-v_step0+1)*dt
variable ebal equal v_etot-v_wfault
thermo_style custom step atoms c_kepack pe f_grav v_etot v_wfault v_ebal f_fault[1]
thermo_modify format float %.15g
thermo 100
"""
FAULT = "fix fault hanging saltdem/fault dip ${dip} rate ${rate} target ${target}\n"
FINAL = "write_dump all custom final.dump id type x y vx vy radius modify sort id " \
        "format float %.17g\n"


def mgh(data):
    """M g H of the pack (types 1, 2) of a data file: the energy scale of the scene."""
    atoms = read_data(data)
    pack = atoms[atoms[:, 1] < 3]
    return pack[:, 6].sum() * 9.81 * (pack[:, 5].max() - pack[:, 5].min())


def read_data(path):
    """Atoms of a write_data file as rows [id, type, diameter, density, x, y, mass] (2d
    masses from the written 3d density, as LAMMPS writes it: rho * 4/3 pi r^3)."""
    text = path.read_text()
    block = text.split("Atoms # sphere")[1].split("Velocities")[0]
    rows = [[float(v) for v in l.split()[:6]] for l in block.strip().splitlines() if l.strip()]
    a = np.array(rows)
    mass = a[:, 3] * 4.0 / 3.0 * math.pi * (0.5 * a[:, 2]) ** 3
    return np.column_stack([a, mass])


def assert_stable(r, data, natoms=None):
    """The run is stable (see the module docstring); returns the thermo table."""
    check_ok(r)
    t = r.thermo()
    assert all_finite(t), "non-finite thermo values"
    if natoms is not None:
        assert min(t["Atoms"]) == max(t["Atoms"]) == natoms, "atoms lost"
    e = t["v_ebal"]
    rise = (max(e) - e[0]) / mgh(data)
    assert rise < E_TOL, f"energy minus the fault's work rose by {rise:.3g} M g H"
    return t


def max_wall_overlap(dump_path):
    """Largest overlap of a pack disc (type 1, 2) with a wall disc (type 3), over the smaller
    radius: a disc that tunnels through the basement shows up here."""
    d = read_dump(dump_path)
    a = np.array([d[i] for i in sorted(d)])    # type x y vx vy radius
    pack, wall = a[a[:, 0] < 3], a[a[:, 0] == 3]
    dx = pack[:, None, 1] - wall[None, :, 1]
    dy = pack[:, None, 2] - wall[None, :, 2]
    rsum = pack[:, None, 5] + wall[None, :, 5]
    rmin = np.minimum(pack[:, None, 5], wall[None, :, 5])
    return ((rsum - np.hypot(dx, dy)) / rmin).max()


def limit_and_advice(line):
    lim = float(re.search(r"stable limit ([0-9.eE+-]+)", line).group(1))
    use = float(re.search(r"Use 'timestep ([0-9.eE+-]+)'", line).group(1))
    return lim, use


# ---------------------------------------------------------------------------------------------
# 1. stiff cases: stable, or stopped before the first step with the stable dt named
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("factor", [1000, 10000])
def test_stiff_normal_stiffness(scenes, tmp_path, factor):
    """kn of the cover and of the wall contacts x1000 and x10,000 of the scene default (1e10
    N/m) at the scene's dt: the run stops before its first step, naming the limit 0.6
    sqrt(S m_min / kn) (m_min the lightest cover disc, S its inertia factor) and a dt to use;
    at that dt the scene runs stably while the fault moves."""
    s, data = scenes("quick")
    kn = 1e10 * factor
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "run 4000\n", kn_cover=kn, kn_wall=kn)
    line = assert_error(r, "saltdem/cohesive", "stable limit", f"kn = {kn:g}")
    assert "Step" not in r.out, "the run started"
    lim, use = limit_and_advice(line)
    atoms = read_data(data)
    m_min = atoms[atoms[:, 1] == 1][:, 6].min() * PRESETS["quick"]["S"]
    assert lim == pytest.approx(0.6 * math.sqrt(m_min / kn), rel=1e-5)
    assert use < lim
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "run 4000\n", kn_cover=kn, kn_wall=kn,
                  dt=use)
    assert_stable(r, data, natoms=len(atoms))


def test_stability_check_can_fail(scenes, tmp_path):
    """Control for the "stable" check: an energy source the balance does not know (fix
    viscous with a negative drag on the pack, -4e7 kg/s, in the scene's default run) makes
    E - W rise beyond the bound (measured: 1.4e-2 M g H in 2,000 steps), and assert_stable
    says so."""
    s, data = scenes("quick")
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "fix pump pack viscous -4e7\nrun 2000\n")
    with pytest.raises(AssertionError, match="energy minus the fault's work rose"):
        assert_stable(r, data, natoms=len(read_data(data)))


def test_stiff_paper_viscosity_runs(scenes, tmp_path):
    """The paper's salt (eta 5e8 Pa s, S 20) at the paper's dt 0.002 s, paper-sized discs,
    under the moving fault: stable."""
    s, data = scenes("paper")
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "run 4000\n")
    assert_stable(r, data, natoms=len(read_data(data)))


def test_stiff_viscosity_x100(scenes, tmp_path):
    """eta x100 (5e10 Pa s) at the paper's dt: stopped before the first step by the viscous
    limit, which names eta and the inertia factor needed; with that factor (salt and cover)
    it runs stably."""
    s, data = scenes("paper")
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "run 2000\n", eta=5e10)
    line = assert_error(r, "saltdem/viscous", "stable limit", "eta = 5e+10", "inertia")
    assert "Step" not in r.out
    need = float(re.search(r"S >= ([0-9.eE+-]+) times", line).group(1))
    assert need > 15    # 100 x eta needs 100 x the inertia of the limit (dt 0.002 is 0.21 of it)
    S = math.ceil(need * 1.05) * PRESETS["paper"]["S"]
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "run 2000\n", eta=5e10, S=S, S_cover=S)
    assert_stable(r, data, natoms=len(read_data(data)))


def test_stiff_smallest_radius_eighth(tmp_path):
    """The paper's discs with the smallest radius an eighth (0.78 m: 64x lighter discs) at the
    paper's dt: the cover's tangential spring limit 0.6 sqrt(S m / (3 kt)) drops below
    0.002 s, the run stops before its first step naming it; at the named dt it runs stably
    (unsettled pack falling onto the basement while the fault moves)."""
    s = Scene("paper")
    s.rmin = 0.125 * PRESETS["paper"]["rmin"]
    data = s.write(tmp_path / "half.data")
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "run 3000\n", rmin=s.rmin)
    line = assert_error(r, "stable limit", "types 1")
    assert "Step" not in r.out
    lim, use = limit_and_advice(line)
    m = 2200 * math.pi * min(a[1] for a in s.atoms() if a[0] == 1) ** 2 * PRESETS["paper"]["S"]
    assert lim == pytest.approx(0.6 * math.sqrt(m / 1.5e10), rel=1e-3)
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "run 3000\n", rmin=s.rmin, dt=use)
    check_ok(r)
    t = r.thermo()
    assert all_finite(t) and min(t["Atoms"]) == max(t["Atoms"]) == len(s.atoms())
    # falling from the generator's rows converts gravity into motion: E - W may not rise
    # above its start beyond the noise (M g H of this unsettled scene from its gravity energy)
    assert (max(t["v_ebal"]) - t["v_ebal"][0]) < E_TOL * abs(t["f_grav"][0])


# ---------------------------------------------------------------------------------------------
# 2. extreme cases
# ---------------------------------------------------------------------------------------------

def test_extreme_weld(scenes, tmp_path):
    """Salt thinned to one row of the smallest discs (a weld) between the basement and the
    cover, the hanging wall moving down 1 rmax (62.5 m) at 2.5 m/s: stable, the fault reaches
    its target, and no disc tunnels into the walls (overlap with a wall disc < 0.5 of the
    smaller radius)."""
    s, data = scenes("weld")
    assert s.nsalt == round(s.W / (2 * s.rmin))    # one row of the smallest discs
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "thermo 1000\nrun 12000\n" + FINAL,
                  rate=2.5)
    t = assert_stable(r, data, natoms=len(read_data(data)))
    assert t["f_fault[1]"][-1] == pytest.approx(s.target, rel=1e-12)
    assert max_wall_overlap(tmp_path / "final.dump") < 0.5


def test_extreme_fault_beyond_salt_thickness(scenes, tmp_path):
    """Salt 125 m thick, fault displacement 312.5 m (throw 156 m, more than the salt) at 5 m/s:
    stable, the target is reached, no disc tunnels into the walls."""
    s, data = scenes("thin")
    assert s.target * math.sin(math.radians(s.dip)) > s.Hs
    r = run_scene(tmp_path, s, data, FAULT + ENERGY + "thermo 1000\nrun 25500\n" + FINAL,
                  rate=5.0)
    t = assert_stable(r, data, natoms=len(read_data(data)))
    assert t["f_fault[1]"][-1] == pytest.approx(s.target, rel=1e-12)
    assert f"target displacement {s.target:g} m reached" in r.out
    assert max_wall_overlap(tmp_path / "final.dump") < 0.5


def test_extreme_fast_driving_reynolds_one(scenes, tmp_path):
    """The fault driven so fast that the model Reynolds number S rho V L / eta is 1: fix
    saltdem/viscosity warns (naming the number) at the start of the run, and the run itself
    stays stable."""
    s, data = scenes("quick")
    S, rho, eta, L = PRESETS["quick"]["S"], 2200.0, 5e8, s.Hs
    V = eta / (S * rho * L)
    fix = (f"fix scale all saltdem/viscosity lambda 1e9 model {eta} rate {V!r} length {L!r} "
           f"density {rho} inertia {S}\n")
    r = run_scene(tmp_path, s, data, fix + FAULT + ENERGY.replace("f_fault[1]", "f_fault[1] f_scale[1]") +
                  "run 1000\n", rate=V)
    t = assert_stable(r, data, natoms=len(read_data(data)))
    assert t["f_scale[1]"][0] == pytest.approx(1.0, rel=1e-12)
    assert re.search(r"WARNING: Fix saltdem/viscosity: the model Reynolds number 1 \(", r.out)


LEAVE = """units si
dimension 2
atom_style sphere
atom_modify map array
boundary f ${yb} p
comm_modify vel yes
region box block -100 100 -100 100 -10 10
create_box 1 box
create_atoms 1 single 0 0 0
create_atoms 1 single 30 0 0
create_atoms 1 single -30 0 0
set type 1 diameter 12.5
set type 1 density/disc 2200
pair_style saltdem/cohesive
pair_coeff * * 1e8 3e7 0.5 1e4 2e4 0.05 damp 0.3 0.3
neighbor 1.25 bin
fix 1 all saltdem/nve
group runner id 2
velocity runner set 1 0.5 0 units box
thermo 100000
thermo_style custom step atoms
${extra}
timestep 1e-3
run ${n}
"""


@pytest.mark.parametrize("np", [1, 2])
def test_extreme_disc_leaves_box_is_an_error(lmp, np):
    """A disc crossing a fixed ('f') boundary is deleted by LAMMPS, which by default says so
    only at the next thermo output (here after 100,000 steps).  Fix saltdem/nve stops the run
    within its check interval (100 steps) of the loss, naming the number of atoms and the
    step.  The disc crosses x = 100 at step 70,000 (from x = 30 at 1 m/s, dt 1 ms) and is
    deleted at the next neighbour rebuild (every ~540 steps at its speed)."""
    r = lmp(LEAVE, np=np, yb="f", extra="", n=200000, timeout=120)
    line = assert_error(r, "Fix saltdem/nve", "1 atom(s) lost", "original 3, current 2",
                        "boundary")
    step = int(re.search(r"lost by step (\d+)", line).group(1))
    assert 70000 <= step <= 70000 + 2000, line


def test_extreme_disc_leaves_shrink_wrapped_box(lmp):
    """With a shrink-wrapped boundary ('m') in y the box follows the disc: nothing is lost
    (the disc leaves through y, as x is still 'f': stop before it reaches x = 100)."""
    r = lmp(LEAVE.replace("velocity runner set 1 0.5 0 units box", "velocity runner set 0 5 0 units box"), yb="m",
            extra="", n=40000)
    check_ok(r)
    assert r.thermo()["Atoms"][-1] == 3


def test_extreme_disc_leaves_lost_ignore(lmp):
    """thermo_modify lost ignore: the user accepts losses; the run goes on with 2 atoms."""
    r = lmp(LEAVE, yb="f", extra="thermo_modify lost ignore", n=80000)
    check_ok(r)
    assert r.thermo()["Atoms"][-1] == 2


def test_extreme_hanging_wall_leaves_box(scenes, tmp_path):
    """A fault target beyond the box: the hanging-wall discs (integrated by no fix) would cross
    the lower boundary; the motion fix refuses to start, naming where they would go."""
    s, data = scenes("quick")
    r = run_scene(tmp_path, s, data, FAULT + "thermo 100000\nrun 20000\n", rate=100.0,
                  target=5000.0)
    assert_error(r, "Fix saltdem/fault", "the motion to the target 5000 m takes wall discs out of the box")
    assert "Step" not in r.out.split("ERROR")[0].split("Setting up Verlet run")[-1]


# ---------------------------------------------------------------------------------------------
# 3. bad input: every style and fix, in one hybrid deck
# ---------------------------------------------------------------------------------------------

BAD_BASE = """units si
dimension 2
atom_style sphere
boundary p f p
comm_modify vel yes
region box block 0 200 -100 200 -0.5 0.5
create_box 3 box
lattice sq 20
region body block 0 200 0 200 -0.5 0.5 units box
create_atoms 2 region body
region low block INF INF INF 20 INF INF units box
region high block INF INF 140 INF INF INF units box
set region low type 3
set region high type 1
set group all diameter 19
set group all density/disc 2200
group cover type 1
group salt type 2
group wall type 3
pair_style hybrid saltdem/cohesive saltdem/viscous
pair_coeff 1 1 saltdem/cohesive 1e8 3e7 0.5 1e4 2e4 0.01
pair_coeff 1 3 saltdem/cohesive 1e8 3e7 0.5 1e4 0 0
pair_coeff 2 2 saltdem/viscous 5e8 0 fluid 28 1e8
pair_coeff 1 2 saltdem/viscous 5e8 5e9 contact 0.5
pair_coeff 2 3 saltdem/viscous 5e8 5e9 contact 0.5
pair_coeff 3 3 none
neighbor 2.8 bin
neigh_modify exclude type 3 3
fix 1 cover saltdem/nve
fix 2 salt saltdem/nve inertia 20
fix 3 wall saltdem/fault dip 30 rate 0.05 target 1
fix 4 all saltdem/viscosity lambda 1e9 model 5e8 rate 0.05 length 100 density 2200 inertia 20
fix 5 all enforce2d
timestep 1e-4
thermo_style custom step atoms pe f_3[1] f_4[1]
run 2
"""
PC_COH = "pair_coeff 1 1 saltdem/cohesive 1e8 3e7 0.5 1e4 2e4 0.01"
PC_VIS = "pair_coeff 2 2 saltdem/viscous 5e8 0 fluid 28 1e8"
PC_CON = "pair_coeff 2 3 saltdem/viscous 5e8 5e9 contact 0.5"
PS = "pair_style hybrid saltdem/cohesive saltdem/viscous"
NVE = "fix 2 salt saltdem/nve inertia 20"
FLT = "fix 3 wall saltdem/fault dip 30 rate 0.05 target 1"
VSC = "fix 4 all saltdem/viscosity lambda 1e9 model 5e8 rate 0.05 length 100 density 2200 " \
      "inertia 20"


def coh(args):
    return (PC_COH, f"pair_coeff 1 1 saltdem/cohesive {args}")


def vis(args):
    return (PC_VIS, f"pair_coeff 2 2 saltdem/viscous {args}")


def con(args):
    return (PC_CON, f"pair_coeff 2 3 saltdem/viscous {args}")


def fault(args):
    return (FLT, f"fix 3 wall saltdem/fault {args}")


def visc(args):
    return (VSC, f"fix 4 all saltdem/viscosity {args}")


# (id, [(old, new) replacements in BAD_BASE], words the ERROR line must hold).  Cases that
# the style test modules already hold (test_cohesive.py, test_viscous.py, test_fault_fix.py,
# test_viscosity_fix.py, test_build.py) are not repeated here: docs/reliability.md counts both.
BAD = [
    # pair_style saltdem/cohesive (as a hybrid sub-style)
    ("coh-style-nonnumeric", [(PS, "pair_style hybrid saltdem/cohesive dtfactor abc saltdem/viscous")],
     ["abc"]),
    ("coh-style-extra-token", [(PS, "pair_style hybrid saltdem/cohesive dtfactor 0.1 0.2 saltdem/viscous")],
     ["saltdem/cohesive", "'0.2'"]),
    # pair_coeff saltdem/cohesive
    ("coh-kn0", [coh("0 3e7 0.5 1e4 2e4 0.01")], ["saltdem/cohesive", "kn = 0", "> 0"]),
    ("coh-range<0", [coh("1e8 3e7 0.5 1e4 0 -0.01")], ["saltdem/cohesive", "range = -0.01"]),
    ("coh-mur<0", [coh("1e8 3e7 0.5 1e4 2e4 0.01 rolling 1e7 -0.1")], ["saltdem/cohesive", "mu_r"]),
    ("coh-zetat>=1", [coh("1e8 3e7 0.5 1e4 2e4 0.01 damp 0.1 1.0")], ["saltdem/cohesive", "damping"]),
    ("coh-zetan<0", [coh("1e8 3e7 0.5 1e4 2e4 0.01 damp -0.1 0.1")], ["saltdem/cohesive", "damping"]),
    ("coh-damp-nonnumeric", [coh("1e8 3e7 0.5 1e4 2e4 0.01 damp x 0.1")], ["'x'"]),
    ("coh-rolling-nonnumeric", [coh("1e8 3e7 0.5 1e4 2e4 0.01 rolling 1e7 y")], ["'y'"]),
    ("coh-type0", [(PC_COH, "pair_coeff 0 1 saltdem/cohesive 1e8 3e7 0.5 1e4 2e4 0.01")],
     ["Invalid range string: 0"]),
    ("coh-type-nonnumeric", [(PC_COH, "pair_coeff a 1 saltdem/cohesive 1e8 3e7 0.5 1e4 2e4 0.01")],
     ["a"]),
    ("coh-missing-cross", [("pair_coeff 1 3 saltdem/cohesive 1e8 3e7 0.5 1e4 0 0", "")],
     ["pair coeffs"]),
    ("coh-rolling-after-run", [("run 2", "run 2\n" + PC_COH + " rolling 1e7 0.1\nrun 2")],
     ["saltdem/cohesive", "rolling resistance was switched on"]),
    # pair_style saltdem/viscous
    ("vis-correction0", [(PS, PS + " correction 0")], ["saltdem/viscous", "correction 0 must be > 0"]),
    ("vis-correction-nonnumeric", [(PS, PS + " correction abc")], ["abc"]),
    ("vis-dtfactor0", [(PS, PS + " dtfactor 0")], ["saltdem/viscous", "dtfactor 0"]),
    ("vis-viscfactor0", [(PS, PS + " viscfactor 0")], ["saltdem/viscous", "viscfactor 0"]),
    ("vis-viscfactor-novalue", [(PS, PS + " viscfactor")], ["saltdem/viscous viscfactor"]),
    # pair_coeff saltdem/viscous
    ("vis-h0", [vis("5e8 0 fluid 0 1e8")], ["saltdem/viscous", "h = 0"]),
    ("vis-h-nonnumeric", [vis("5e8 0 fluid x 1e8")], ["'x'"]),
    ("vis-K-nonnumeric", [vis("5e8 0 fluid 28 y")], ["'y'"]),
    ("vis-kn-nonnumeric", [vis("5e8 z fluid 28 1e8")], ["'z'"]),
    ("vis-gap-nonnumeric", [con("5e8 5e9 contact g")], ["'g'"]),
    ("vis-tangential-nonnumeric", [con("5e8 5e9 contact 0.5 tangential t")], ["'t'"]),
    ("vis-type0", [(PC_VIS, "pair_coeff 2 0 saltdem/viscous 5e8 0 fluid 28 1e8")],
     ["Invalid range string: 0"]),
    ("vis-missing-type", [(PC_VIS, "")], ["pair coeffs"]),
    # fix saltdem/nve
    ("nve-inertia-nonnumeric", [(NVE, "fix 2 salt saltdem/nve inertia many")], ["'many'"]),
    ("nve-check-noninteger", [(NVE, "fix 2 salt saltdem/nve inertia 20 check 2.5")], ["2.5"]),
    ("nve-check-novalue", [(NVE, "fix 2 salt saltdem/nve inertia 20 check")], ["saltdem/nve check"]),
    ("nve-empty-group", [(NVE, "group nobody id 100000\nfix 2 nobody saltdem/nve inertia 20")],
     ["Fix saltdem/nve 2", "group nobody has no atoms"]),
    ("nve-zero-radius", [("fix 5 all enforce2d", "fix 5 all enforce2d\nset atom 50 diameter 0")],
     ["Fix saltdem/nve 2", "1 atom(s) of group salt", "atom 50", "radius or mass"]),
    # fix saltdem/viscosity
    ("visc-noargs", [visc("")], ["saltdem/viscosity"]),
    ("visc-lambda-nonnumeric", [visc("lambda big model 5e8 rate 0.05 length 100 density 2200")],
     ["'big'"]),
    ("visc-natural0", [visc("lambda 1e9 natural 0 rate 0.05 length 100 density 2200")],
     ["saltdem/viscosity", "natural = 0"]),
    ("visc-model<0", [visc("lambda 1e9 model -1 rate 0.05 length 100 density 2200")],
     ["saltdem/viscosity", "model = -1"]),
    ("visc-rate0", [visc("lambda 1e9 model 5e8 rate 0 length 100 density 2200")],
     ["saltdem/viscosity", "rate = 0"]),
    ("visc-no-rate", [visc("lambda 1e9 model 5e8 length 100 density 2200")],
     ["saltdem/viscosity", "'rate' is required"]),
    ("visc-no-density", [visc("lambda 1e9 model 5e8 rate 0.05 length 100")],
     ["saltdem/viscosity", "'density' is required"]),
    ("visc-density<0", [visc("lambda 1e9 model 5e8 rate 0.05 length 100 density -2200")],
     ["saltdem/viscosity", "density = -2200"]),
    ("visc-warn0", [visc("lambda 1e9 model 5e8 rate 0.05 length 100 density 2200 warn 0")],
     ["saltdem/viscosity", "warn = 0"]),
    ("visc-density-novalue", [visc("lambda 1e9 model 5e8 rate 0.05 length 100 density")],
     ["saltdem/viscosity density"]),
    ("visc-before-coeffs", [(PC_COH, VSC + "\n" + PC_COH), (VSC + "\nfix 5", "fix 5")],
     ["saltdem/viscosity", "coefficients set before the fix"]),
    # fix saltdem/fault (its documented interface, docs/fix_saltdem_fault.rst)
    ("fault-dip0", [fault("dip 0 rate 0.05 target 1")], ["saltdem/fault", "dip = 0"]),
    ("fault-dip<0", [fault("dip -30 rate 0.05 target 1")], ["saltdem/fault", "dip = -30"]),
    ("fault-no-dip", [fault("rate 0.05 target 1")], ["saltdem/fault", "dip"]),
    ("fault-no-rate", [fault("dip 30 target 1")], ["saltdem/fault", "rate = 0"]),
    ("fault-no-target", [fault("dip 30 rate 0.05")], ["saltdem/fault", "target = 0"]),
    ("fault-rate-nonnumeric", [fault("dip 30 rate fast target 1")], ["'fast'"]),
    ("fault-noargs", [fault("")], ["saltdem/fault"]),
    ("fault-toward", [fault("dip 30 rate 0.05 target 1 toward up")],
     ["saltdem/fault", "toward 'up' must be right or left"]),
]


def test_bad_input_base_deck_runs(lmp):
    """The deck every bad-input case modifies runs as given (all five styles together)."""
    r = lmp(BAD_BASE)
    check_ok(r)
    assert "ERROR" not in r.out and "WARNING" not in r.out
    assert "reference density of fluid type 2" in r.out


@pytest.mark.parametrize("repl,words", [c[1:] for c in BAD], ids=[c[0] for c in BAD])
def test_bad_input(lmp, repl, words):
    """Each bad input stops lmp with a LAMMPS ERROR (non-zero exit, no crash) that names the
    offending style, keyword or value."""
    deck = BAD_BASE
    for old, new in repl:
        assert old in deck, old
        deck = deck.replace(old, new, 1)
    assert_error(lmp(deck), *words)


# ---------------------------------------------------------------------------------------------
# 4. restart
# ---------------------------------------------------------------------------------------------

SCALE = ("fix scale all saltdem/viscosity lambda 1e9 model ${eta} rate ${rate} length 375 "
         "density ${rho} inertia ${S}\n")
RST_THERMO = ("thermo_style custom step atoms c_kepack pe f_fault[1] f_scale[3]\n"
              "thermo_modify format float %.15g\nthermo 500\n")
DUMP = "write_dump all custom {} id x y vx vy omegaz modify sort id format float %.17g\n"
SPLIT = FAULT + SCALE + RST_THERMO + "run ${n}\nwrite_restart split.restart\nrun ${n}\n" + \
    DUMP.format("split.dump")
PRENO = FAULT + SCALE + RST_THERMO + "restart ${n} preno.restart\nrun ${n}\nrun ${n} pre no\n" + \
    DUMP.format("preno.dump")
MIDRUN = FAULT + SCALE + RST_THERMO + "restart ${n} mid.restart\nrun ${n2}\n"

# a fresh process: read_restart, then what a hybrid pair style needs again (LAMMPS writes no
# coefficients of hybrid sub-styles) and the fixes (fix saltdem/nve writes nothing)
CONTINUE = """read_restart ${file}
comm_modify vel yes
${pairstyle}
pair_coeff      1 1 saltdem/cohesive ${kn_cover} ${kt_cover} 0.5 ${coh_cover} ${ten_cover} ${rng_cover} damp 0.3 0.3
pair_coeff      2 2 saltdem/viscous ${eta} ${kn_salt} fluid ${h_salt} ${K_salt}
pair_coeff      1 2 saltdem/viscous ${eta} ${kn_wall} fluid ${h_salt} ${K_salt}
pair_coeff      2 3 saltdem/viscous ${eta} ${kn_wall} fluid ${h_salt} ${K_salt}
pair_coeff      1 3 saltdem/cohesive ${kn_wall} ${kt_cover} 1.0 ${coh_cover} 0 0
pair_coeff      3 3 none
neighbor        $(0.2*v_rmin) bin
neigh_modify    exclude type 3 3
group           cover type 1
group           salt type 2
group           pack union cover salt
group           hanging id ${hang}
fix             icover cover saltdem/nve inertia ${S_cover} check ${check}
fix             isalt salt saltdem/nve inertia ${S} check ${check}
fix             grav pack gravity 9.81 vector 0 -1 0
fix_modify      grav energy yes
fix             2d all enforce2d
fix             ${faultid} hanging saltdem/fault dip ${dip} rate ${rate} target ${target}
variable        fdisp equal f_${faultid}[1]
fix             scale all saltdem/viscosity lambda 1e9 model ${eta} rate ${rate} length 375 density ${rho} inertia ${S}
timestep        ${dt}
compute         kepack pack ke
thermo_style    custom step atoms c_kepack pe v_fdisp f_scale[3]
thermo_modify   format float %.15g
thermo          500
run             ${n}
write_dump all custom ${out} id x y vx vy omegaz modify sort id format float %.17g
"""


@pytest.fixture(scope="module")
def restart_runs(scenes, tmp_path_factory):
    """The quick scene faulting at 2 m/s: 'run N; write_restart; run N' (split), a single
    'run 2N' with the 'restart' command writing at step N (as the example decks do), and
    'run N; run N pre no'.  N = 3000; the fault stops at its target, 20 m, at step 4000."""
    s, data = scenes("quick")
    d = tmp_path_factory.mktemp("restart")
    kw = dict(rate=2.0, target=20.0, n=3000, n2=6000)
    out = {}
    r = run_scene(d, s, data, SPLIT, **kw)
    check_ok(r)
    out["split"] = r
    r = run_scene(d, s, data, MIDRUN + DUMP.format("single.dump"), **kw)
    check_ok(r)
    out["single"] = r
    r = run_scene(d, s, data, PRENO, **kw)
    check_ok(r)
    out["preno"] = r
    return s, data, d, out, kw


def continue_from(d, s, data, kw, file, out, pairstyle="", faultid="fault"):
    r = run_lmp(CONTINUE, d, **s.variables(data=data, file=file, out=out, pairstyle=pairstyle,
                                           faultid=faultid, **kw))
    check_ok(r)
    return r


def test_restart_reproduces_split_run(restart_runs):
    """'run N; write_restart; run N' == 'read_restart (fresh lmp); run N' on one rank, for the
    hybrid scene with everything that carries state: the cover's shear history (pair
    saltdem/cohesive), the salt's continuity density and reference density (pair
    saltdem/viscous: pair_coeff given again, as pair hybrid requires, keeps the reference
    density of the file), the fault displacement (fix saltdem/fault) and the natural clock
    (fix saltdem/viscosity): positions within 1e-10 of the box width, velocities within
    1e-8 m/s, fault displacement and model time exactly.  Control: a fault defined under
    another ID starts again from 0 and overshoots the target (30 m instead of 20 m), which the
    comparison sees."""
    s, data, d, runs, kw = restart_runs
    r = continue_from(d, s, data, kw, "split.restart", "cont.dump")
    assert "(from the restart file)" in r.out and "WARNING" not in r.out
    assert "All restart file peratom fix info was re-assigned" in r.out
    a, b = read_dump(d / "split.dump"), read_dump(d / "cont.dump")
    W = s.box()[1] - s.box()[0]
    assert max_rel_diff(a, b, W) < RESTART_TOL
    assert max_rel_diff(a, b, 1.0, cols=(2, 3)) < 1e-8
    ta, tb = runs["split"].thermo(1), r.thermo()
    assert tb["PotEng"][0] == pytest.approx(ta["PotEng"][0], rel=1e-12)    # history restored
    assert tb["v_fdisp"][-1] == ta["f_fault[1]"][-1] == 20.0
    assert tb["f_scale[3]"][-1] == pytest.approx(ta["f_scale[3]"][-1], rel=1e-12)
    # control: a fault under another ID does not get the displacement back
    r = continue_from(d, s, data, kw, "split.restart", "ctl.dump", faultid="other")
    assert r.thermo()["v_fdisp"][-1] == pytest.approx(2.0 * 3000 * 0.0025)
    assert max_rel_diff(a, read_dump(d / "ctl.dump"), W) > 1e-8


def test_restart_midrun_file_is_complete(restart_runs):
    """The restart file that the 'restart N' command writes during a single run (what the
    example decks do) holds the same state as write_restart between two runs: continuing
    from either gives the same trajectory (positions within 1e-10 of the box width)."""
    s, data, d, runs, kw = restart_runs
    continue_from(d, s, data, kw, "split.restart", "from_split.dump")
    continue_from(d, s, data, kw, "mid.restart.3000", "from_mid.dump")
    W = s.box()[1] - s.box()[0]
    assert max_rel_diff(read_dump(d / "from_split.dump"), read_dump(d / "from_mid.dump"),
                        W) < RESTART_TOL


def test_restart_vs_single_uninterrupted_run(restart_runs):
    """A single 'run 2N' differs from any run split at N (restart or not) because the setup of
    every run recomputes the velocity-dependent forces (damping, viscosity) with the full-step
    velocities, where the uninterrupted run used the half-step ones; 'run N pre no', which
    skips that setup, reproduces the single run bit for bit.  So a restart adds nothing
    beyond the difference of a run boundary: continuing from the restart file differs from the
    single run exactly as much as 'run N; run N' does (docs/reliability.md gives the size)."""
    s, data, d, runs, kw = restart_runs
    W = s.box()[1] - s.box()[0]
    single = read_dump(d / "single.dump")
    assert max_rel_diff(single, read_dump(d / "preno.dump"), W) == 0.0
    continue_from(d, s, data, kw, "split.restart", "cont2.dump")
    split, cont = read_dump(d / "split.dump"), read_dump(d / "cont2.dump")
    d_split, d_cont = max_rel_diff(single, split, W), max_rel_diff(single, cont, W)
    assert d_split > 0.0
    assert d_cont == pytest.approx(d_split, rel=1e-3, abs=1e-12)


def test_restart_pair_style_given_again(restart_runs):
    """After read_restart a deck that gives 'pair_style hybrid ...' again creates new
    sub-styles: the shear history is still restored (the history fix ID does not depend on
    the pair instance), and so are the salt's densities and reference density (the state of
    the density fix, whose ID does not depend on the pair instance either): the run continues
    as if the pair style had not been given again."""
    s, data, d, runs, kw = restart_runs
    r = continue_from(d, s, data, kw, "split.restart", "again.dump",
                      pairstyle="pair_style hybrid saltdem/cohesive saltdem/viscous")
    assert "All restart file peratom fix info was re-assigned" in r.out
    assert r.thermo()["PotEng"][0] == pytest.approx(runs["split"].thermo(1)["PotEng"][0],
                                                    rel=1e-12)
    assert "(from the restart file)" in r.out and "WARNING" not in r.out
    W = s.box()[1] - s.box()[0]
    assert max_rel_diff(read_dump(d / "split.dump"), read_dump(d / "again.dump"), W) < RESTART_TOL


ROLL_A = """units si
dimension 2
atom_style sphere
boundary p f p
comm_modify vel yes
read_data pack.data
set group all density/disc 2200
group mobile type 1
neighbor 0.1 bin
pair_style saltdem/cohesive
pair_coeff * * 1e8 5e7 0.5 1e4 2e4 0.01 damp 0.3 0.3 rolling 1e7 0.1
fix 1 mobile nve/sphere disc
fix 2 all enforce2d
fix g mobile gravity 9.81 vector 0 -1 0
timestep 4e-4
run 1000
write_restart r.restart
"""
ROLL_B = """read_restart r.restart
comm_modify vel yes
neighbor 0.1 bin
${drop}
pair_coeff * * 1e8 5e7 0.5 1e4 2e4 0.01 damp 0.3 0.3 ${roll}
group mobile type 1
fix 1 mobile nve/sphere disc
fix 2 all enforce2d
fix g mobile gravity 9.81 vector 0 -1 0
timestep 4e-4
run 500
write_dump all custom ${out} id x y vx vy omegaz modify sort id format float %.17g
"""


def test_restart_switching_rolling_drops_history(lmp, tmp_path):
    """A restart whose coefficients switch rolling resistance off (6 history values per contact
    in the file, 3 now) drops the history, exactly as the documented way of discarding it
    ('pair_style none' and the pair style again) does, instead of reading 6-value records as
    3-value ones.  Control: keeping rolling restores the history and gives another result."""
    from test_cohesive import write_pack
    write_pack(tmp_path / "pack.data", 20, 20, floor=True)
    check_ok(lmp(ROLL_A))
    r = lmp(ROLL_B.replace("${drop}", ""), roll="", out="switched.dump")
    check_ok(r)
    assert "Unused restart file peratom fix info" in r.out
    check_ok(lmp(ROLL_B.replace("${drop}", "pair_style none\npair_style saltdem/cohesive"),
                 roll="", out="dropped.dump"))
    check_ok(lmp(ROLL_B.replace("${drop}", ""), roll="rolling 1e7 0.1", out="kept.dump"))
    a, b, c = (read_dump(tmp_path / f) for f in ("switched.dump", "dropped.dump", "kept.dump"))
    assert max_rel_diff(a, b, 20.0) < RESTART_TOL
    assert max_rel_diff(a, c, 20.0) > 1e-6


# ---------------------------------------------------------------------------------------------
# 5. MPI ranks and OpenMP threads
# ---------------------------------------------------------------------------------------------

PAR = FAULT + SCALE + RST_THERMO + "run 3000\n" + DUMP.format("final.dump") + "info fixes\n"


@pytest.fixture(scope="module")
def par_serial(scenes, tmp_path_factory):
    s, data = scenes("quick")
    d = tmp_path_factory.mktemp("par1")
    r = run_scene(d, s, data, PAR, rate=2.0)
    check_ok(r)
    return s, data, r, read_dump(d / "final.dump")


@pytest.mark.parametrize("mode", ["np2", "np2-newton-off", "omp2", "np2xomp2"])
def test_parallel_scene_agrees(par_serial, tmp_path, mode):
    """The faulting scene (hybrid cover/salt, 3,000 steps): 2 MPI ranks (newton on, as the
    scenes run, or off), 2 OpenMP threads (-sf omp) and both give the serial positions within
    1e-8 of the box width and the serial kinetic and potential energy within 1e-6 (only
    summation orders differ)."""
    s, data, r1, a = par_serial
    kw = {"np2": dict(np=2), "np2-newton-off": dict(np=2, newton="off"), "omp2": dict(omp=2),
          "np2xomp2": dict(np=2, omp=2)}[mode]
    r = run_scene(tmp_path, s, data, PAR, rate=2.0, **kw)
    check_ok(r)
    if "omp" in mode:    # hybrid sub-styles keep their names; their lists are the /omp ones
        assert "Last active /omp style is pair_style saltdem/viscous" in r.out
        assert "size, history, omp" in r.out
        assert re.search(r"icover,\s+style = saltdem/nve/omp", r.out), "threaded integrator"
    else:
        assert re.search(r"icover,\s+style = saltdem/nve,", r.out)
    b = read_dump(tmp_path / "final.dump")
    W = s.box()[1] - s.box()[0]
    assert max_rel_diff(a, b, W) < MPI_TOL
    t1, t2 = r1.thermo(), r.thermo()
    assert t2["c_kepack"][-1] == pytest.approx(t1["c_kepack"][-1], rel=1e-6)
    assert t2["PotEng"][-1] == pytest.approx(t1["PotEng"][-1], rel=1e-6)


EMPTY_RANK = """units si
dimension 2
atom_style sphere
atom_modify map array
processors ${px} 1 1
boundary f f p
comm_modify vel yes
region box block -400 400 -100 300 -1000 1000
create_box 3 box
lattice sq 20
region body block -199 -19 0 200 -0.5 0.5 units box
create_atoms 2 region body
region low block INF INF INF 20 INF INF units box
region high block INF INF 140 INF INF INF units box
set region low type 3
set region high type 1
set group all diameter 19
set group all density/disc 2200
group cover type 1
group salt type 2
group wall type 3
group runner id 1
pair_style hybrid saltdem/cohesive saltdem/viscous
pair_coeff 1 1 saltdem/cohesive 1e8 3e7 0.5 1e4 2e4 0.01
pair_coeff 1 3 saltdem/cohesive 1e8 3e7 0.5 1e4 0 0
pair_coeff 2 2 saltdem/viscous 5e8 0 fluid 28 1e8
pair_coeff 1 2 saltdem/viscous 5e8 5e9 contact 0.5
pair_coeff 2 3 saltdem/viscous 5e8 5e9 contact 0.5
pair_coeff 3 3 none
neighbor 2.8 bin
neigh_modify exclude type 3 3
fix 1 cover saltdem/nve inertia 20
fix 2 salt saltdem/nve inertia 20
fix 3 wall saltdem/fault dip 30 rate 1 target 5
fix 4 all saltdem/viscosity lambda 1e9 model 5e8 rate 0.05 length 100 density 2200 inertia 20
fix 5 all enforce2d
fix 6 cover gravity 9.81 vector 0 -1 0
velocity salt set ${vx} 0 0 units box
timestep 2e-3
thermo_style custom step atoms ke pe f_3[1]
thermo_modify format float %.15g
thermo 1000
run 3000
write_dump all custom final.dump id x y vx vy modify sort id format float %.17g
"""


@pytest.mark.parametrize("case", ["idle", "gains-atoms", "omp"])
def test_rank_without_atoms(lmp, tmp_path, case):
    """Every atom starts in the left half of the box, so with 'processors 2 1 1' rank 1 owns
    none (idle: it never gets any; gains-atoms: the salt moves right at 5 m/s and enters its
    domain within the 6 s run; omp: idle with 2 threads per rank).  The runs end normally within the time limit
    (no hang, no crash) and match the serial run: positions within 1e-8 of the box width."""
    vx = 5.0 if case == "gains-atoms" else 0.0
    r1 = lmp(EMPTY_RANK, px=1, vx=vx, timeout=120)
    check_ok(r1)
    a = read_dump(tmp_path / "final.dump")
    r2 = lmp(EMPTY_RANK, np=2, omp=2 if case == "omp" else 0, px=2, vx=vx, timeout=120)
    check_ok(r2)
    assert "2 by 1 by 1 MPI processor grid" in r2.out
    b = read_dump(tmp_path / "final.dump")
    assert max_rel_diff(a, b, 800.0) < MPI_TOL
    if case == "gains-atoms":
        assert max(v[0] for v in b.values()) > 0.0    # the salt crossed into rank 1's half


NAN2 = """units si
dimension 2
atom_style sphere
processors 2 1 1
boundary p p p
comm_modify vel yes
region box block -50 50 -50 50 -0.5 0.5
create_box 1 box
create_atoms 1 single 20 0 0
create_atoms 1 single -20 0 0
set type 1 diameter 10
set type 1 density/disc 2200
group blow id 1
${neigh}
fix 1 all saltdem/nve check 10
fix 2 blow viscous 1e15
fix 3 all enforce2d
velocity all set 1 0 0
timestep 1e-3
thermo 100000
run 100000
"""


@pytest.mark.parametrize("case", ["nan", "blowup"])
def test_blowup_on_one_rank_ends_the_run(lmp, case):
    """A drag far beyond its stability limit (no pair style checks fix viscous) blows up one
    atom on one of two ranks.  nan: without neighbour rebuilds the atom stays in place until
    its velocity is NaN, and fix saltdem/nve names it on the rank that owns it; blowup: with
    the usual rebuilds the atom jumps farther than a sub-domain and LAMMPS drops it, which
    fix saltdem/nve reports as a blow-up (the box is periodic).  Either way the whole MPI job
    ends with a non-zero exit within seconds, no hang."""
    t0 = time.time()
    neigh = "neigh_modify every 1000000 delay 0 check no" if case == "nan" else ""
    r = lmp(NAN2, np=2, timeout=60, neigh=neigh)
    assert r.rc != 0
    if case == "nan":
        assert "non-finite" in r.out and "atom 1 (type 1)" in r.out
    else:
        line = assert_error(r, "Fix saltdem/nve", "1 atom(s) lost", "blow-up")
        assert "non-periodic" not in line
    assert time.time() - t0 < 60


# ---------------------------------------------------------------------------------------------
# 6. memory
# ---------------------------------------------------------------------------------------------

MEMLOOP = """neighbor ${skin} bin
neigh_modify every 1 delay 0 check yes
""" + FAULT + """
thermo_style custom step atoms c_kepack
thermo 100000
variable k loop ${nloop}
label loop
${body}
run ${nrun}
print "phase" file phase.$k
info memory
next k
jump SELF loop
"""
# create and destroy the pair styles and fixes in every loop as well
REDEFINE = """pair_style hybrid saltdem/cohesive saltdem/viscous
pair_coeff 1 1 saltdem/cohesive ${kn_cover} ${kt_cover} 0.5 ${coh_cover} ${ten_cover} ${rng_cover} damp 0.3 0.3
pair_coeff 2 2 saltdem/viscous ${eta} ${kn_salt} fluid ${h_salt} ${K_salt}
pair_coeff 1 2 saltdem/viscous ${eta} ${kn_wall} fluid ${h_salt} ${K_salt}
pair_coeff 2 3 saltdem/viscous ${eta} ${kn_wall} fluid ${h_salt} ${K_salt}
pair_coeff 1 3 saltdem/cohesive ${kn_wall} ${kt_cover} 1.0 ${coh_cover} 0 0
pair_coeff 3 3 none
unfix icover
fix icover cover saltdem/nve inertia ${S_cover} check ${check}"""
# the control grows on purpose in every loop: a row of 800 wall discs high above the scene
# (atom arrays fill) and one more per-atom store of 4 values
GROW = """region r$k block INF INF $(1000+v_k*20) $(1010+v_k*20) INF INF units box
create_atoms 3 random 800 $(v_k+100) r$k overlap 1 maxtry 100
set region r$k diameter 2
set region r$k density/disc ${rho}
fix s$k all store/state 0 x y vx vy"""


def memory_run(scene, data, workdir, body, nloop, nrun, rate=10.0, skin=0.5, timeout=600):
    deck = SCENE_DECK + MEMLOOP.replace("${body}", body)
    rc, out, samples = run_watched(deck, workdir, timeout=timeout, **scene.variables(
        data=data, nloop=nloop, nrun=nrun, rate=rate, skin=skin))
    assert rc == 0, out[-3000:]
    builds = sum(int(b) for b in re.findall(r"Neighbor list builds = (\d+)", out))
    return out, samples, builds


def growth(out, samples, nloop, warm=2):
    """Heap in use (MB, from `info memory` after every loop) and peak VmRSS (MB, the watcher's
    samples) of the loops after `warm` loops: increase from the first of them to the last.  The
    peak resident size at loop K is the largest sample taken up to the end of loop K, so a loop
    shorter than the 50 ms sampling period (as fast as these are) still has one."""
    heap = heap_mb(out)
    assert len(heap) == nloop
    assert samples, "the watcher never saw the process"

    def peak_upto(k):
        seen = [kb / 1024.0 for _, kb, phase in samples if phase <= k]
        assert seen, f"no VmRSS sample up to loop {k}"
        return max(seen)

    return heap[nloop - 1] - heap[warm - 1], peak_upto(nloop - 1) - peak_upto(warm)


HEAP_TOL = 0.25      # MB the heap in use may grow over the measured loops
RSS_TOL = 2.0        # MB the peak resident size may grow (glibc keeps freed pages: coarser)


@pytest.mark.parametrize("body", ["", REDEFINE], ids=["runs", "redefine"])
def test_memory_does_not_grow(scenes, tmp_path, body):
    """10 x 1,500 steps of the faulting scene (hanging wall at 10 m/s for 375 m, skin 0.5 m:
    about 1,000 neighbour rebuilds), with `info memory` after every loop and the process's VmRSS sampled
    every 50 ms: from loop 2 to loop 10 the heap in use grows by less than 0.25 MB and the
    peak resident size by less than 2 MB ('redefine': the pair styles, their coefficients and
    an integrator are created anew in every loop as well)."""
    s, data = scenes("long")
    out, samples, builds = memory_run(s, data, tmp_path, body, nloop=10, nrun=1500)
    assert builds > 500, builds
    dheap, drss = growth(out, samples, 10)
    assert dheap < HEAP_TOL, f"heap grew by {dheap:.3f} MB over 8 loops"
    assert drss < RSS_TOL, f"resident size grew by {drss:.3f} MB over 8 loops"


def test_memory_check_can_fail(scenes, tmp_path):
    """Control: the same measurement on a run that grows on purpose (800 more discs and one
    more per-atom store per loop) reports a growth beyond both tolerances, so the test above
    would see a leak of that size."""
    s, data = scenes("long")
    out, samples, builds = memory_run(s, data, tmp_path, GROW, nloop=10, nrun=300)
    dheap, drss = growth(out, samples, 10)
    assert dheap > HEAP_TOL and drss > RSS_TOL, (dheap, drss)


# ---------------------------------------------------------------------------------------------
# restart files of another layout
# ---------------------------------------------------------------------------------------------

FORMAT_DECK = """units si
dimension 2
atom_style sphere
boundary p p p
comm_modify vel yes
region box block 0 200 0 200 -100 100
create_box 2 box
lattice sq 20
create_atoms 1 box
set group all type/fraction 2 0.5 7
set group all diameter 20
set group all density/disc 2200
pair_style ${pstyle}
pair_coeff 1 1 saltdem/cohesive 1e9 3e8 0.5 0 0 0
pair_coeff 2 2 saltdem/viscous 5e8 0 fluid 28 1e8
pair_coeff 1 2 saltdem/viscous 5e8 1e9 fluid 28 1e8
fix nve all saltdem/nve inertia 1000
timestep 1e-4
run 10
write_restart r.restart
"""


MARK = -20261214.0    # SaltDEM::RESTART_MARK


def format_file(lmp, tmp_path):
    """A restart file of the hybrid deck; its bytes and the offsets of the two pair sub-styles'
    restart settings (written in the order of pair_style hybrid, before any fix's data)."""
    import struct
    deck = FORMAT_DECK.replace("${pstyle}", "hybrid saltdem/cohesive saltdem/viscous")
    check_ok(lmp(deck))
    check_ok(lmp("read_restart r.restart\n"))
    raw = (tmp_path / "r.restart").read_bytes()
    mark = struct.pack("d", MARK)
    first = raw.index(mark)
    second = raw.index(mark, first + 8)
    # the pair sub-styles, then the density fix's global data: each begins with the mark
    assert raw.count(mark) == 3
    return raw, {"saltdem/cohesive": first, "saltdem/viscous": second}


@pytest.mark.parametrize("style", ["saltdem/cohesive", "saltdem/viscous"])
def test_restart_of_another_format_stops(lmp, tmp_path, style):
    """A restart file whose SaltDEM restart mark differs from this build's (an older layout:
    raw coefficient structs) stops read_restart with a message that names the style and both
    formats; the unaltered file reads back."""
    import struct
    raw, at = format_file(lmp, tmp_path)
    at = at[style]
    (tmp_path / "r.restart").write_bytes(raw[:at] + struct.pack("d", -20261123.0) + raw[at + 8:])
    r = lmp("read_restart r.restart\n")
    line = assert_error(r, f"Pair style {style}", "restart format -20261123",
                        "restart format -20261214")
    assert "data file" in line


@pytest.mark.parametrize("style", ["saltdem/cohesive", "saltdem/viscous"])
def test_restart_names_its_fields_and_version(lmp, tmp_path, style):
    """Each pair style writes its own layout version, its settings by name and value and the
    names of its coefficients (derived values are not written: init_one() computes them).  A
    file of another version, or whose list of names differs from the style's, stops
    read_restart naming both."""
    import struct
    raw, at = format_file(lmp, tmp_path)
    for name in (b"dtfactor", b"zeta_n", b"mu_r", b"calibration", b"viscfactor", b"tangential"):
        assert name in raw, name
    for derived in (b"kfac", b"ih2"):
        assert derived not in raw
    at = at[style]
    version = struct.unpack("i", raw[at + 8:at + 12])[0]
    # saltdem/viscous: 3 added the settings fill and substeps, 4 noslip, 5 the plastic strength
    # coefficients, 6 the implicit step's settings (it still reads 1, 3, 4 and 5; 2, fill
    # alone, was never released)
    current, reads = {"saltdem/cohesive": (1, "reads layout 1"),
                      "saltdem/viscous": (6, "reads layouts 1, 3, 4, 5 and 6")}[style]
    assert version == current
    for bad in (7, 2) if style == "saltdem/viscous" else (7,):
        (tmp_path / "r.restart").write_bytes(raw[:at + 8] + struct.pack("i", bad) + raw[at + 12:])
        assert_error(lmp("read_restart r.restart\n"), f"Pair style {style}",
                     f"layout version {bad}", reads)
    # a setting renamed in the file (same length): the lists differ
    old, new = (b"dtfactor", b"dtFACTOR")
    k = raw.index(old, at)
    (tmp_path / "r.restart").write_bytes(raw[:k] + new + raw[k + len(old):])
    line = assert_error(lmp("read_restart r.restart\n"), f"Pair style {style}", "settings are",
                        "dtFACTOR")
    assert "this version of the style has" in line and "dtfactor" in line


def test_restart_of_an_unmarked_fix_stops(lmp, tmp_path):
    """The SaltDEM fixes with restart data write the mark and their layout version too: data
    of an older layout (the displacement alone) stop the run instead of being misread."""
    import struct
    deck = """units si
dimension 2
atom_style sphere
boundary f f p
comm_modify vel yes
region box block -100 100 -100 100 -1 1
create_box 1 box
create_atoms 1 single 0 0 0
create_atoms 1 single 20 0 0
set type 1 diameter 10
set type 1 density/disc 2200
group hw id 2
pair_style saltdem/cohesive
pair_coeff * * 1e9 0 0.5 0 0 0
fix fault hw saltdem/fault dip 60 rate 2 target 10
timestep 0.1
run 3
write_restart r.restart
"""
    check_ok(lmp(deck))
    cont = "read_restart r.restart\ncomm_modify vel yes\n" \
        "fix fault hw saltdem/fault dip 60 rate 2 target 10\nrun 1\n"
    check_ok(lmp(cont))
    raw = (tmp_path / "r.restart").read_bytes()
    mark = struct.pack("d", MARK)
    at = raw.index(mark, raw.index(mark) + 8)    # after the pair style's: the fault's
    assert struct.unpack("d", raw[at + 16:at + 24])[0] == pytest.approx(0.6)
    (tmp_path / "r.restart").write_bytes(raw[:at] + struct.pack("d", 0.6) + raw[at + 8:])
    assert_error(lmp(cont), "Fix saltdem/fault fault", "another SaltDEM version")
