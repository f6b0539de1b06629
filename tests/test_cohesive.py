"""Tests of pair_style saltdem/cohesive (src/USER-SALTDEM/pair_saltdem_cohesive.*,
law in saltdem_contact_cohesive.h: cohesive_force).

Every test runs small LAMMPS decks through the `lmp` fixture (tests/conftest.py)
and checks numbers against the closed-form contact law:

  normal      Fn = kn*delta                        (delta = overlap > 0)
  cohesive    Fn = -kn*g                           (0 < g = -delta <= gp = tensile/kn)
              Fn = -tensile*(range-g)/(range-gp)   (gp < g < range), 0 beyond
  tangential  |Ft| <= cohesion + mu*kn*delta       (spring kt with history, touching only)
  damping     -2 zeta_n sqrt(meff kn) vn,  -2 zeta_t sqrt(meff kt) vt
  stable dt   dtfactor*sqrt(m_min/max(kn, 3 kt))   (2d)

Units SI, 2d discs (`set ... density/disc`, `fix nve/sphere disc`).
"""
import math
import random
import re

import pytest

from lmprun import assert_error, check_ok

RHO = 2200.0


def disc_mass(d, rho=RHO):
    return rho * math.pi * 0.25 * d * d


def header(boundary="f f p", box=(-50, 50, -50, 50), ntypes=1):
    return f"""units si
dimension 2
atom_style sphere
atom_modify map array
boundary {boundary}
comm_modify vel yes
region box block {box[0]} {box[1]} {box[2]} {box[3]} -0.5 0.5
create_box {ntypes} box
"""


def normal_law(g, kn, tens, rng):
    """Elastic/cohesive normal force (positive repulsive) at gap g (g < 0: overlap)."""
    if g <= 0.0:
        return -kn * g
    if tens <= 0.0 or g >= rng:
        return 0.0
    gp = tens / kn
    if g <= gp:
        return -kn * g
    return -tens * (rng - g) / (rng - gp)


def read_dump(path):
    """{id: [columns after id]} from a text dump written with 'modify sort id'."""
    text = path.read_text()
    lines = text.split("ITEM: ATOMS")[1].splitlines()[1:]
    out = {}
    for line in lines:
        s = line.split()
        if s:
            out[int(s[0])] = [float(v) for v in s[1:]]
    return out


def max_diff(a, b, cols=(0, 1)):
    assert a.keys() == b.keys()
    return max(abs(a[i][c] - b[i][c]) for i in a for c in cols)


# ---------------------------------------------------------------------------
# 1. head-on collision: energy conservation and restitution
# ---------------------------------------------------------------------------

HEADON = header() + """
create_atoms 1 single -${x0} 0 0
create_atoms 1 single ${x0} 0 0
set type 1 diameter 20.0
set type 1 density/disc 2200
neighbor 0.5 bin
pair_style saltdem/cohesive
pair_coeff 1 1 1e9 0 0 0 ${tens} ${range} damp ${z} 0
group a id 1
group b id 2
velocity a set 1 0 0
velocity b set -1 0 0
fix 1 all nve/sphere disc
fix 2 all enforce2d
compute k all ke
compute r all erotate/sphere
variable vx1 equal vx[1]
thermo_style custom step c_k c_r pe v_vx1
thermo_modify format float %.15g
thermo 1
timestep ${dt}
run ${n}
"""


def test_headon_energy_conserved(lmp):
    """No damping, with the cohesive well: KE after == KE before and KE+PE
    constant through the contact (within 1e-3)."""
    tens, rng = 1e6, 0.01
    r = lmp(HEADON, x0=10.05, tens=tens, range=rng, z=0, dt=0.0005, n=400)
    check_ok(r)
    t = r.thermo()
    ke, pe = t["c_k"], t["PotEng"]
    ke0 = ke[0]
    assert ke0 == pytest.approx(disc_mass(20.0), rel=1e-12)    # 2 * m/2 * 1^2
    # the collision happened and is over: deep compression, rebound
    assert min(ke) < 0.01 * ke0
    assert max(pe) > 0.9 * ke0
    assert pe[-1] == 0.0 and t["v_vx1"][-1] < -0.99
    assert max(t["c_r"]) == 0.0
    # energy: after/before, and KE+PE at every step
    assert abs(ke[-1] / ke0 - 1.0) < 1e-3
    worst = max(abs(k + p - ke0) for k, p in zip(ke, pe)) / ke0
    assert worst < 1e-3
    # the well depth: PE just at touching is -tensile*range/2
    assert min(pe) <= -0.5 * tens * rng * 0.99


@pytest.mark.parametrize("zeta", [0.1, 0.3, 0.5])
def test_headon_restitution(lmp, zeta):
    """Linear spring-dashpot: e = exp(-pi z / sqrt(1 - z^2)) within 1 %."""
    r = lmp(HEADON, x0=10.005, tens=0, range=0, z=zeta, dt=0.0001, n=1000)
    check_ok(r)
    t = r.thermo()
    assert t["PotEng"][-1] == 0.0, "discs still in contact at the end"
    e = math.sqrt(t["c_k"][-1] / t["c_k"][0])
    e_theory = math.exp(-math.pi * zeta / math.sqrt(1.0 - zeta * zeta))
    assert e == pytest.approx(e_theory, rel=0.01)


# ---------------------------------------------------------------------------
# tangential spring: a frictional contact that sticks must be elastic
# ---------------------------------------------------------------------------

TANGENT = header() + """
variable ov equal ${fn}/${kn}
variable y2 equal 20-${ov}
create_atoms 1 single 0 0 0
create_atoms 1 single 0 ${y2} 0
set type 1 diameter 20.0
set type 1 density/disc 2200
neighbor 0.5 bin
pair_style saltdem/cohesive
pair_coeff 1 1 ${kn} ${kt} 10 1e9 0 0
group top id 2
velocity top set 0.01 0 0
fix 1 top nve
fix 2 all enforce2d
fix 3 top addforce 0 -${fn} 0
fix_modify 3 energy yes
variable x2 equal x[2]
compute k all ke
thermo_style custom step v_x2 c_k pe
thermo_modify format float %.15g
thermo 5
timestep ${dt}
run ${n}
"""


def test_tangential_spring_conserves_energy(lmp):
    """A disc (no rotation: fix nve) pressed on a fixed disc and given a small
    tangential velocity oscillates on the tangential spring kt without
    sliding (mu = 10, cohesion huge).  Without damping its energy must stay
    constant (velocity Verlet: O((w dt)^2)); a tangential spring that lags
    the positions by one step acts as negative damping and makes the
    amplitude grow by exp(pi w dt) per period."""
    kt, m = 1e9, disc_mass(20.0)
    w = math.sqrt(kt / m)
    dt = 0.0005
    n = int(round(6 * 2 * math.pi / w / dt))    # six periods
    r = lmp(TANGENT, kn=1e9, kt=kt, fn=1e6, dt=dt, n=n)
    check_ok(r)
    t = r.thermo()
    ke0 = t["c_k"][0]
    assert ke0 == pytest.approx(0.5 * m * 1e-4, rel=1e-12)
    e = [k + p for k, p in zip(t["c_k"], t["PotEng"])]
    drift = max(abs(v - e[0]) for v in e) / ke0
    amp = max(abs(x) for x in t["v_x2"])
    assert drift < 0.01, f"energy of the tangential oscillation changed by {drift:.3g} x KE0"
    assert amp == pytest.approx(0.01 / w, rel=0.01), f"amplitude {amp} vs {0.01 / w}"


# ---------------------------------------------------------------------------
# 2. pull-apart: peak tension, softening, re-forming
# ---------------------------------------------------------------------------

PULL = header() + """
create_atoms 1 single 0 0 0
create_atoms 1 single 19.9995 0 0
set type 1 diameter 20.0
set type 1 density/disc 2200
neighbor 0.1 bin
pair_style saltdem/cohesive
pair_coeff 1 1 ${kn} 1e9 0.5 1e5 ${tens} ${range}
group mover id 2
fix 2 all enforce2d
variable gap equal x[2]-x[1]-20
variable f1 equal fx[1]
variable f2 equal fx[2]
thermo_style custom step v_gap v_f1 v_f2 pe
thermo_modify format float %.15g
thermo 1
timestep 0.0005
fix m mover move linear 0.002 0 0
run 12500
unfix m
fix m mover move linear -0.002 0 0
run 12500
"""


def test_pull_apart_tension_and_reform(lmp):
    """Disc 2 is pulled away from disc 1 at 2 mm/s (1 um per step) from an
    overlap of 0.5 mm to a gap of 12 mm, then pushed back.  The force on
    disc 1 must follow the law at every step; its peak equals `tensile`
    (within 1 %) at the gap tensile/kn; no force beyond `range`; the
    attraction comes back on the way in."""
    kn, tens, rng = 1e9, 1e6, 0.01
    r = lmp(PULL, kn=kn, tens=tens, range=rng)
    check_ok(r)
    out, back = r.thermo(0), r.thermo(1)
    for t in (out, back):
        for g, f1, f2 in zip(t["v_gap"], t["v_f1"], t["v_f2"]):
            # f1 is the force on disc 1 (at -x of disc 2): attraction is +x
            assert f1 == pytest.approx(-normal_law(g, kn, tens, rng), abs=1e-6 * tens)
            assert f2 == -f1
    peak = max(out["v_f1"])
    gpeak = out["v_gap"][out["v_f1"].index(peak)]
    assert peak == pytest.approx(tens, rel=0.01)
    assert gpeak == pytest.approx(tens / kn, abs=2e-6)
    assert max(out["v_gap"]) > rng and out["v_f1"][-1] == 0.0 and out["PotEng"][-1] == 0.0
    # pushed back: attraction again inside the range, the same peak, and
    # repulsion once the discs overlap
    assert max(back["v_f1"]) == pytest.approx(tens, rel=0.01)
    assert min(back["v_gap"]) < 0.0 and back["v_f1"][-1] < -0.4e6
    # the well: PE = -tensile*range/2 at touching
    i0 = min(range(len(out["v_gap"])), key=lambda i: abs(out["v_gap"][i]))
    assert out["PotEng"][i0] == pytest.approx(-0.5 * tens * rng, rel=1e-3)


APPROACH = header(box=(-10, 10, -10, 10)) + """
create_atoms 1 single -0.5525 0 0
create_atoms 1 single 0.5525 0 0
set type 1 diameter 1.0
set type 1 density/disc 2200
neighbor 0.1 bin
neigh_modify every 1 delay 0 check yes
pair_style saltdem/cohesive
pair_coeff 1 1 1e8 0 0 0 2e4 0.01
group a id 1
group b id 2
fix ma a move linear 0.2 0 0
fix mb b move linear -0.2 0 0
variable gap equal x[2]-x[1]-1
variable f1 equal fx[1]
thermo_style custom step v_gap v_f1
thermo_modify format float %.12g
thermo 1
timestep 0.0005
run 540
"""


def test_attraction_felt_whatever_the_neighbor_list_age(lmp):
    """Two discs approach from a gap of 0.105 m, just outside radsum + skin
    (skin 0.1) at the first neighbor build, each moving 0.1 mm per step.
    The attraction (range 0.01) must act as soon as the gap is below the
    range, not only after the next rebuild (when an atom has moved skin/2)."""
    kn, tens, rng = 1e8, 2e4, 0.01
    r = lmp(APPROACH)
    check_ok(r)
    t = r.thermo()
    bad = [(g, f, -normal_law(g, kn, tens, rng)) for g, f in zip(t["v_gap"], t["v_f1"])
           if abs(f + normal_law(g, kn, tens, rng)) > 1e-6 * tens]
    assert not bad, (f"{len(bad)} steps with the wrong force, e.g. gap {bad[-1][0]:.4g}: "
                     f"force {bad[-1][1]:.6g}, law {bad[-1][2]:.6g}")


# ---------------------------------------------------------------------------
# 3. sliding threshold: cohesion + mu * Fn
# ---------------------------------------------------------------------------

SLIDE = header(box=(-150, 150, -150, 150)) + """
variable ov equal ${fn}/${kn}
variable y2 equal 100.5-${ov}
create_atoms 1 single 0 0 0
create_atoms 1 single 0 ${y2} 0
set atom 1 diameter 200.0
set atom 2 diameter 1.0
set type 1 density/disc 2200
neighbor 0.1 nsq
pair_style saltdem/cohesive
pair_coeff 1 1 ${kn} ${kt} ${mu} ${coh} 0 0 damp 0.3 0.3
group top id 2
fix 1 top nve
fix 2 all enforce2d
variable L equal ${coh}+${mu}*${fn}
variable rate equal 1.05*${L}/${T}
variable fpush equal v_rate*time
fix 3 top addforce v_fpush -${fn} 0
variable x2 equal x[2]
variable fx1 equal fx[1]
variable fy1 equal fy[1]
thermo_style custom step v_fpush v_x2 v_fx1 v_fy1
thermo_modify format float %.15g
thermo 1
timestep 0.0001
run ${n}
"""


@pytest.mark.parametrize("fn,mu,coh", [(1e5, 0.5, 2e4), (2e5, 0.3, 0.0), (1e5, 0.0, 5e4)])
def test_sliding_threshold(lmp, fn, mu, coh):
    """A 1 m disc (translation only: fix nve, so it cannot roll) pressed with
    Fn on a fixed 200 m disc (a nearly flat base) is pushed sideways by a
    force rising slowly (over 1000 tangential periods) to 1.05 x the
    threshold.  The contact force may not exceed cohesion + mu*Fn; the disc
    sticks (displacement F/kt) until the pushing force reaches the threshold
    and slides (far beyond the elastic displacement) after."""
    kn, kt, T = 1e9, 1e8, 4.0
    L = coh + mu * fn
    r = lmp(SLIDE, fn=fn, mu=mu, coh=coh, kn=kn, kt=kt, T=T, n=int(T / 1e-4))
    check_ok(r)
    t = r.thermo()
    F, x, ft, fnorm = t["v_fpush"], t["v_x2"], t["v_fx1"], t["v_fy1"]
    assert max(abs(v + fn) for v in fnorm) < 1e-3 * fn    # normal load as applied
    assert max(ft) == pytest.approx(L, rel=0.02)
    # onset: the first step where the contact no longer transmits the push
    onset = next(i for i in range(len(F)) if F[i] - ft[i] > 0.002 * L)
    assert F[onset] == pytest.approx(L, rel=0.02)
    # stick before (elastic displacement only), slide after
    stick = [i for i in range(len(F)) if F[i] < 0.98 * L]
    assert max(x[i] for i in stick) < 1.01 * L / kt
    assert x[-1] > 10 * L / kt


# ---------------------------------------------------------------------------
# 4. domain decomposition and threads: same trajectory
# ---------------------------------------------------------------------------


def write_pack(path, nx, ny, floor, seed=7, vmax=0.5, dmin=0.92, dmax=1.0, center=False):
    """Discs on a unit square lattice with random diameters/velocities
    (deterministic: the atom IDs do not depend on the number of ranks)."""
    rnd = random.Random(seed)
    atoms, vels = [], []
    x0 = -0.5 * nx if center else 0.0
    y0 = -0.5 * ny if center else 1.0
    for j in range(ny):
        for i in range(nx):
            n = len(atoms) + 1
            atoms.append((n, 1, rnd.uniform(dmin, dmax), x0 + i + 0.5, y0 + j))
            vels.append((n, rnd.uniform(-vmax, vmax), rnd.uniform(-vmax, vmax)))
    if floor:
        for i in range(nx):
            n = len(atoms) + 1
            atoms.append((n, 2, 1.0, i + 0.5, 0.0))
            vels.append((n, 0.0, 0.0))
    if center:
        xlo, xhi, ylo, yhi = -nx, nx, -ny, ny
    else:
        xlo, xhi, ylo, yhi = 0.0, float(nx), -1.0, ny + 20.0
    lines = [f"saltdem pack {nx}x{ny}", "", f"{len(atoms)} atoms",
             f"{2 if floor else 1} atom types",
             f"{xlo!r} {xhi!r} xlo xhi", f"{ylo!r} {yhi!r} ylo yhi", "-0.5 0.5 zlo zhi", "",
             "Atoms # sphere", ""]
    lines += [f"{a[0]} {a[1]} {a[2]!r} 1.0 {a[3]!r} {a[4]!r} 0.0" for a in atoms]
    lines += ["", "Velocities", ""]
    lines += [f"{v[0]} {v[1]!r} {v[2]!r} 0.0 0.0 0.0 0.0" for v in vels]
    path.write_text("\n".join(lines) + "\n")


PACK = """units si
dimension 2
atom_style sphere
atom_modify map array
boundary p f p
comm_modify vel yes
newton ${newton}
read_data pack.data
set group all density/disc 2200
group mobile type 1
neighbor 0.1 bin
pair_style saltdem/cohesive${pstyle}
pair_coeff * * 1e8 5e7 0.5 1e4 2e4 0.01 damp 0.3 0.3
if "${usesf} > 0" then "suffix off"
fix 1 mobile nve/sphere disc
if "${usesf} > 0" then "suffix on"
fix 2 all enforce2d
fix g mobile gravity 9.81 vector 0 -1 0
compute k all ke
thermo_style custom step ke pe
thermo_modify format float %.15g
thermo 500
timestep 4e-4
run ${n}
write_dump all custom final.dump id x y vx vy omegaz modify sort id format float %.17g
"""
PACK_W = 50.0


def run_pack(lmp, tmp_path, name, n=2000, np=1, omp=0, args=(), pstyle="", usesf=0, newton="on"):
    write_pack(tmp_path / "pack.data", 50, 40, floor=True)
    r = lmp(PACK, np=np, omp=omp, args=args, n=n, pstyle=pstyle, usesf=usesf, newton=newton)
    check_ok(r)
    dump = read_dump(tmp_path / "final.dump")
    (tmp_path / "final.dump").rename(tmp_path / f"{name}.dump")
    return r, dump


@pytest.fixture
def passive_omp(monkeypatch):
    # 2 threads on a busy 2-core machine: spinning barriers cost 20x
    monkeypatch.setenv("OMP_WAIT_POLICY", "passive")


@pytest.mark.parametrize("newton", ["on", "off"])
def test_pack_np2_matches_np1(lmp, tmp_path, newton):
    """2,050 discs (2,000 free on a fixed floor row), friction, cohesion,
    damping, gravity, 2,000 steps: 2 MPI ranks (newton on or off) give the
    serial positions to 1e-8 of the box width (only the summation order
    differs: measured ~1e-13 relative)."""
    r1, a = run_pack(lmp, tmp_path, "np1")
    r2, b = run_pack(lmp, tmp_path, "np2", np=2, newton=newton)
    assert "2 by 1 by 1" in r2.out or "1 by 2 by 1" in r2.out
    assert len(a) == 2050
    assert max_diff(a, b) / PACK_W < 1e-8
    assert r2.thermo()["PotEng"][-1] == pytest.approx(r1.thermo()["PotEng"][-1], rel=1e-6)


def test_pack_omp_pair_style_matches_serial(lmp, tmp_path, passive_omp):
    """pair_style saltdem/cohesive/omp with 2 threads (package omp 2, no
    suffix): same positions as the serial style to 1e-8 of the box width."""
    r1, a = run_pack(lmp, tmp_path, "serial")
    r2, b = run_pack(lmp, tmp_path, "omp", args=("-pk", "omp", "2"), pstyle="/omp")
    assert "pair saltdem/cohesive/omp" in r2.out
    assert max_diff(a, b) / PACK_W < 1e-8


def test_pack_sf_omp_matches_serial(lmp, tmp_path, passive_omp):
    """The same with `-sf omp -pk omp 2`: everything suffixed except fix
    nve/sphere (LAMMPS' nve/sphere/omp ignores the `disc` keyword and uses
    the sphere inertia 0.4).  The suffix also turns the pair's history fix
    into NEIGH_HISTORY/omp; the trajectory must still be the serial one."""
    r1, a = run_pack(lmp, tmp_path, "serial")
    r2, b = run_pack(lmp, tmp_path, "sfomp", omp=2, usesf=1)
    assert "pair saltdem/cohesive/omp" in r2.out
    d = max_diff(a, b) / PACK_W
    assert d < 1e-8, f"-sf omp positions differ from serial by {d:.3g} of the box width"


PERIODIC_HISTORY = header(boundary="p f p", box=(0, 10, 0, 10)) + """
variable ov equal ${fn}/${kn}
variable xb equal 0.5-${ov}
variable yb equal 5.0-0.5*${ft}/${kt}
create_atoms 1 single 9.5 5.0 0
create_atoms 1 single ${xb} ${yb} 0
set group all diameter 1.0
set group all density/disc 2200
neighbor 0.1 bin
neigh_modify every 1 delay 0 check no
pair_style saltdem/cohesive
pair_coeff * * ${kn} ${kt} 0.5 0 0 0 damp 0.5 0.5
group b id 2
fix 1 b nve
fix 2 all enforce2d
fix 3 b addforce -${fn} ${ft} 0
variable dy equal (y[2]-${yb})*${kt}/${ft}
variable fy1 equal fy[1]
thermo_style custom step v_dy v_fy1
thermo_modify format float %.12g
thermo 100
timestep 1e-4
run 3000
"""


@pytest.mark.parametrize("mode", ["serial", "np2", "sf_omp"])
def test_history_survives_reneighboring_across_periodic_boundary(lmp, passive_omp, mode):
    """Disc 2 touches fixed disc 1 through the periodic x boundary and is held
    by a tangential (y) force 3e4 below the slip limit 5e4, with neighbor
    lists rebuilt every step.  Its y crosses disc 1's y while it loads the
    spring, which swaps the owner of the pair in the half neighbor list.
    The spring must keep its history: final displacement = F/kt."""
    kw = dict(kn=1e8, kt=1e8, fn=1e5, ft=3e4)
    if mode == "np2":
        r = lmp(PERIODIC_HISTORY, np=2, **kw)
    elif mode == "sf_omp":
        r = lmp(PERIODIC_HISTORY, omp=1, **kw)
    else:
        r = lmp(PERIODIC_HISTORY, **kw)
    check_ok(r)
    t = r.thermo()
    assert t["v_fy1"][-1] == pytest.approx(3e4, rel=1e-4)    # static: holds the push
    assert t["v_dy"][-1] == pytest.approx(1.0, abs=0.01), \
        f"displacement {t['v_dy'][-1]:.4f} x F/kt: tangential history was lost"


# ---------------------------------------------------------------------------
# 5. restart with shear history
# ---------------------------------------------------------------------------

RESTART_A = PACK.replace("${pstyle}", "").replace("newton ${newton}\n", "").replace(
    'if "${usesf} > 0" then "suffix off"\n', "").replace(
    'if "${usesf} > 0" then "suffix on"\n', "").replace(
    "damp 0.3 0.3", "damp 0.3 0.3 ${roll}").replace(
    "thermo 500", "thermo 250").replace(
    "run ${n}\n", "run 1000\nwrite_restart r.restart\nrun 1000\n")

RESTART_B = """read_restart r.restart
comm_modify vel yes
neighbor 0.1 bin
if "${recreate} > 0" then "pair_style none" "pair_style saltdem/cohesive" &
  "pair_coeff * * 1e8 5e7 0.5 1e4 2e4 0.01 damp 0.3 0.3 ${roll}"
group mobile type 1
fix 1 mobile nve/sphere disc
fix 2 all enforce2d
fix g mobile gravity 9.81 vector 0 -1 0
thermo_style custom step ke pe
thermo_modify format float %.15g
thermo 250
timestep 4e-4
run 1000
write_dump all custom final.dump id x y vx vy omegaz modify sort id format float %.17g
"""


@pytest.mark.parametrize("roll", ["", "rolling 1e7 0.1"], ids=["friction", "friction+rolling"])
def test_restart_continues_identically(lmp, tmp_path, roll):
    """run 1000; write_restart; run 1000  ==  read_restart; run 1000 (one
    rank, positions within 1e-10 of the box width).  The pair style,
    coefficients and the shear (and rolling) history come from the restart
    file.  Control: re-creating the pair after read_restart (history lost)
    must change the result, so the comparison is sensitive to it."""
    write_pack(tmp_path / "pack.data", 20, 20, floor=True)
    ra = lmp(RESTART_A, roll=roll)
    check_ok(ra)
    a = read_dump(tmp_path / "final.dump")
    rb = lmp(RESTART_B, recreate=0, roll=roll)
    check_ok(rb)
    assert "Resetting peratom fix info from restart file" in rb.out
    b = read_dump(tmp_path / "final.dump")
    ta, tb = ra.thermo(1), rb.thermo()
    # the stored elastic energy (incl. tangential springs) is restored
    assert tb["PotEng"][0] == pytest.approx(ta["PotEng"][0], rel=1e-12)
    assert max_diff(a, b) / 20.0 < 1e-10
    assert max_diff(a, b, cols=(2, 3)) < 1e-8

    rc = lmp(RESTART_B, recreate=1, roll=roll)
    check_ok(rc)
    c = read_dump(tmp_path / "final.dump")
    assert abs(rc.thermo()["PotEng"][0] - ta["PotEng"][0]) > 1e-6 * abs(ta["PotEng"][0])
    assert max_diff(a, c) / 20.0 > 1e-6


# ---------------------------------------------------------------------------
# 6. errors
# ---------------------------------------------------------------------------

ERRDECK = """units si
dimension 2
atom_style ${astyle}
boundary f f p
comm_modify vel yes
region box block -10 10 -10 10 -0.5 0.5
create_box 2 box
create_atoms 1 single -0.5 0 0
create_atoms 2 single 0.5 0 0
${setline}
neighbor 0.1 bin
pair_style saltdem/cohesive ${ps}
pair_coeff ${pc1}
pair_coeff ${pc2}
fix 1 all ${integ}
timestep ${dt}
run 0
"""
GOOD = "1 1 1e8 3e7 0.5 1e4 2e4 0.01"
M1 = disc_mass(1.0)


def run_err(lmp, np=1, **kw):
    v = dict(astyle="sphere", setline="set group all density/disc 2200", ps="",
             integ="nve/sphere disc", pc1="* * 1e8 3e7 0.5 1e4 2e4 0.01", pc2=GOOD, dt=1e-4)
    v.update(kw)
    return lmp(ERRDECK, np=np, **v)


def test_good_deck_runs(lmp):
    check_ok(run_err(lmp))


@pytest.mark.parametrize("kw,words", [
    (dict(pc2="1 1 -1e8 3e7 0.5 1e4 2e4 0.01"), ["saltdem/cohesive", "kn", "-1"]),
    (dict(pc2="1 1 1e8 -3e7 0.5 1e4 2e4 0.01"), ["saltdem/cohesive", "kt"]),
    (dict(pc2="1 1 1e8 3e7 -0.5 1e4 2e4 0.01"), ["saltdem/cohesive", "mu"]),
    (dict(pc2="1 1 1e8 3e7 0.5 -1e4 2e4 0.01"), ["saltdem/cohesive", "cohesion"]),
    (dict(pc2="1 1 1e8 3e7 0.5 1e4 -2e4 0.01"), ["saltdem/cohesive", "tensile"]),
    (dict(pc2="1 1 1e8 3e7 0.5 1e4 2e4 0.01 rolling -1 0.1"), ["saltdem/cohesive", "kr"]),
    (dict(pc2="1 1 1e8 3e7 0.5 1e4 2e4"), ["saltdem/cohesive", "8 or more", "got 7"]),
    (dict(pc2="1 1 1e8 3e7 0.5 1e4 2e4 0.01 damp 0.1"), ["saltdem/cohesive", "damp"]),
    (dict(pc2="1 1 1e8 3e7 0.5 1e4 2e4 0.01 rolling 1e7"), ["saltdem/cohesive", "rolling"]),
    (dict(pc2="1 1 1e8 3e7 0.5 1e4 2e4 0.01 damp 1.0 0.1"), ["saltdem/cohesive", "damping"]),
    (dict(pc2="1 1 1e8 3e7 0.5 1e4 2e4 0.01 bogus 1 2"), ["saltdem/cohesive", "bogus"]),
    (dict(pc2="1 1 1e8 3e7 0.5 1e4 2e4 1e-5"), ["saltdem/cohesive", "range"]),
    (dict(pc2="1 1 1e8 3e7 0.5 1e4 2e4 0.5"), ["saltdem/cohesive", "skin"]),
    (dict(ps="bogus"), ["saltdem/cohesive", "bogus"]),
    (dict(ps="dtfactor"), ["saltdem/cohesive", "dtfactor"]),
    (dict(ps="dtfactor 2"), ["saltdem/cohesive", "dtfactor"]),
    (dict(ps="dtfactor 0"), ["saltdem/cohesive", "dtfactor"]),
    (dict(pc2="1 1 1e8 abc 0.5 1e4 2e4 0.01"), ["abc"]),
    (dict(pc2="1 3 1e8 3e7 0.5 1e4 2e4 0.01"), ["3"]),
    (dict(astyle="atomic", setline="mass * 1.0", integ="nve"),
     ["saltdem/cohesive", "atom_style sphere"]),
], ids=["kn<0", "kt<0", "mu<0", "coh<0", "tens<0", "kr<0", "7args", "damp1", "rolling1",
        "zeta>=1", "coeff-kw", "range<gp", "range>skin", "style-kw", "dtfactor-noarg",
        "dtfactor>0.8", "dtfactor0", "nonnumeric", "type-range", "atomic"])
def test_error(lmp, kw, words):
    assert_error(run_err(lmp, **kw), *words)


def test_error_missing_coefficients(lmp):
    """Type 2 has no coefficients (and 1-2 cannot be mixed)."""
    r = run_err(lmp, pc1=GOOD, pc2=GOOD)
    assert_error(r, "pair coeffs")


def test_error_no_ghost_velocities(lmp):
    deck = ERRDECK.replace("comm_modify vel yes\n", "")
    r = lmp(deck, astyle="sphere", setline="set group all density/disc 2200", ps="",
            integ="nve/sphere disc", pc1="* * 1e8 3e7 0.5 1e4 2e4 0.01", pc2=GOOD, dt=1e-4)
    assert_error(r, "saltdem/cohesive", "comm_modify vel yes")


def limit_in(line):
    m = re.search(r"stable limit ([0-9.eE+-]+)", line)
    assert m, line
    return float(m.group(1))


@pytest.mark.parametrize("np", [1, 2])
def test_error_timestep_names_limit_kn(lmp, np):
    """kn dominates (kn > 3 kt): limit dtfactor sqrt(m/kn), default dtfactor 0.6."""
    line = assert_error(run_err(lmp, np=np, dt=0.01), "saltdem/cohesive", "timestep 0.01",
                        "kn = 1e+08", "types 1 1")
    assert limit_in(line) == pytest.approx(0.6 * math.sqrt(M1 / 1e8), rel=1e-5)


def test_error_timestep_names_limit_kt(lmp):
    """3 kt dominates, custom dtfactor: limit dtfactor sqrt(m/(3 kt))."""
    pc = "* * 1e8 1e8 0.5 1e4 2e4 0.01"
    line = assert_error(run_err(lmp, ps="dtfactor 0.5", pc1=pc, pc2=pc, dt=0.01),
                        "saltdem/cohesive", "kt = 1e+08")
    assert limit_in(line) == pytest.approx(0.5 * math.sqrt(M1 / 3e8), rel=1e-5)


def test_timestep_just_below_limit_runs(lmp):
    check_ok(run_err(lmp, dt=0.99 * 0.6 * math.sqrt(M1 / 1e8)))


def test_stable_dt_uses_mixed_cross_coefficients(lmp):
    """Type 1: light, kn 1e8; type 2: 1000x heavier, kn 1e10; 1-2 mixed
    (springs in series: kn12 = 1.98e8).  The 1-2 contact with the light disc
    limits dt to 0.6 sqrt(m1/kn12) = 1.77e-3 < 0.6 sqrt(m1/kn11) = 2.5e-3;
    dt = 2.1e-3 must be refused."""
    kn12 = 2 * 1e8 * 1e10 / (1e8 + 1e10)
    deck = ERRDECK.replace("${setline}",
                           "set type 1 density/disc 2200\nset type 2 density/disc 2200000")
    r = lmp(deck, astyle="sphere", ps="", integ="nve/sphere disc", pc1="1 1 1e8 0 0 0 0 0",
            pc2="2 2 1e10 0 0 0 0 0", dt=2.1e-3)
    line = assert_error(r, "saltdem/cohesive", "types 1 2")
    assert limit_in(line) == pytest.approx(0.6 * math.sqrt(M1 / kn12), rel=1e-5)


# ---------------------------------------------------------------------------
# 7. invariants: linear and angular momentum of an isolated pack
# ---------------------------------------------------------------------------

MOMENTUM = """units si
dimension 2
atom_style sphere
atom_modify map array
boundary f f p
comm_modify vel yes
read_data pack.data
set group all density/disc 2200
velocity all zero linear
velocity all zero angular
neighbor 0.1 bin
pair_style saltdem/cohesive
pair_coeff * * 1e8 5e7 0.4 1e4 2e4 0.01 damp 0.2 0.2 rolling 1e7 0.1
fix 1 all nve/sphere disc
fix 2 all enforce2d
compute om all property/atom omegaz
variable px atom mass*vx
variable py atom mass*vy
variable pa atom mass*(abs(vx)+abs(vy))
variable lz atom mass*(x*vy-y*vx)+0.5*mass*radius*radius*c_om
variable la atom mass*(abs(x*vy)+abs(y*vx))+0.5*mass*radius*radius*abs(c_om)
compute p all reduce sum v_px v_py v_pa v_lz v_la
compute r all erotate/sphere
thermo_style custom step ke c_r pe c_p[1] c_p[2] c_p[3] c_p[4] c_p[5]
thermo_modify format float %.15g
thermo 50
timestep 4e-4
run 1000
"""


@pytest.mark.parametrize("np", [1, 2])
def test_momentum_conserved(lmp, tmp_path, np):
    """400 overlapping discs flying apart / sticking (cohesion, friction,
    rolling, damping), no gravity, no walls: total linear momentum and total
    angular momentum (orbital + 0.5 m r^2 spin) stay zero to round-off."""
    write_pack(tmp_path / "pack.data", 20, 20, floor=False, vmax=1.0, dmin=0.95, dmax=1.05,
               center=True)
    r = lmp(MOMENTUM, np=np)
    check_ok(r)
    t = r.thermo()
    assert max(t["c_r"]) > 0.0 and t["PotEng"][0] > 0.0    # spins and overlaps: not trivial
    for i in range(len(t["Step"])):
        assert abs(t["c_p[1]"][i]) < 1e-13 * t["c_p[3]"][i]
        assert abs(t["c_p[2]"][i]) < 1e-13 * t["c_p[3]"][i]
        assert abs(t["c_p[4]"][i]) < 1e-13 * t["c_p[5]"][i]


HEADON_DIM = """units si
dimension {dim}
atom_style sphere
atom_modify map array
boundary f f {zb}
comm_modify vel yes
region box block -50 50 -50 50 {zlo} {zhi}
create_box 1 box
create_atoms 1 single -10.004 0 0
create_atoms 1 single 10.004 0 0
set type 1 diameter 20.0
set type 1 mass {mass}
neighbor 0.5 bin
pair_style saltdem/cohesive
pair_coeff 1 1 1e9 0 0 0 1e6 0.01 damp 0.3 0
velocity all set 0 0 0
velocity all set 1 0 0 sum no units box
group a id 1
group b id 2
velocity b set -1 0 0
fix 1 all nve/sphere {disc}
{fix2d}
variable vx1 equal vx[1]
variable x1 equal x[1]
thermo_style custom step v_x1 v_vx1 pe
thermo_modify format float %.15g
thermo 10
timestep 0.0002
run 1500
"""


def test_headon_3d_spheres_match_discs(lmp, tmp_path):
    """The normal contact law does not depend on the dimension: two spheres of the discs' mass
    collide head-on (spring, dashpot, cohesive well) exactly as the discs do."""
    m = disc_mass(20.0)
    runs = {}
    for dim in (2, 3):
        deck = HEADON_DIM.format(dim=dim, zb="p" if dim == 2 else "f", zlo=-0.5 if dim == 2 else -50,
                                 zhi=0.5 if dim == 2 else 50, mass=m, disc="disc" if dim == 2 else "",
                                 fix2d="fix 2 all enforce2d" if dim == 2 else "")
        r = lmp(deck)
        check_ok(r)
        runs[dim] = r.thermo()
    a, b = runs[2], runs[3]
    assert min(a["v_vx1"]) < -0.3 and a["PotEng"][-1] == 0.0    # rebounded (e ~ 0.37), apart
    for k in ("v_x1", "v_vx1", "PotEng"):
        assert b[k] == pytest.approx(a[k], rel=1e-12, abs=1e-12)
