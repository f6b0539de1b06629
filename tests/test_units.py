"""Units: which SaltDEM styles assume SI and what they do under other units.

- saltdem/wall (default density 2200 kg/m^3) and fix saltdem/tiltwall (default g 9.81 m/s^2):
  the defaults under units si only, an error naming the keyword otherwise;
- fix saltdem/viscosity: reports SI numbers (Reynolds numbers, years, m/ka, 1/s) under any
  physical unit system, through LAMMPS's unit constants; units lj is an error;
- the pair styles: their damping ratios and stable time step limits use force->ftm2v, so a
  collision is the same in metal units as in SI.
"""
import math

import pytest

from lmprun import assert_error, check_ok

# ---------------------------------------------------------------------------------------------
# saltdem/wall and fix saltdem/tiltwall: the SI defaults
# ---------------------------------------------------------------------------------------------

HEAD = """units {units}
dimension 2
atom_style sphere
atom_modify map array
boundary f f p
comm_modify vel yes
region box block -100 100 -100 100 -1 1
create_box 1 box
"""


@pytest.mark.parametrize("units,extra,ok", [("si", "", True), ("cgs", "", False),
                                            ("cgs", " density 2.2", True)])
def test_wall_default_density_is_si_only(lmp, units, extra, ok):
    r = lmp(HEAD.format(units=units) + f"saltdem/wall 1 -50 0 50 0 5{extra}\n"
            "variable m equal mass[1]\nprint \"MASS $(v_m:%.10g)\"\n")
    if not ok:
        assert_error(r, "saltdem/wall", "default density 2200", "kg/m^3", "units cgs",
                     "density RHO")
        return
    check_ok(r)
    rho = 2.2 if extra else 2200.0
    assert float(r.out.split("MASS ")[1].split()[0]) == pytest.approx(rho * math.pi * 25, rel=1e-9)


TILT = HEAD + """create_atoms 1 single 0 0 0
create_atoms 1 single 50 -20 0
set type 1 diameter 2
set type 1 density/disc 2.2
group free id 1
group wall id 2
pair_style saltdem/cohesive
pair_coeff * * 100 0 0.5 0 0 0
fix nve free saltdem/nve
fix tw wall saltdem/tiltwall tilt 30 rate 2 target 2.5 gravity free{extra}
timestep 0.01
thermo_style custom step f_tw[2] f_tw[3]
thermo_modify format float %.17g
run 1
"""


@pytest.mark.parametrize("units,extra,g", [("si", "", 9.81), ("cgs", "", None),
                                           ("cgs", " g 981", 981.0)])
def test_tiltwall_default_g_is_si_only(lmp, units, extra, g):
    r = lmp(TILT.format(units=units, extra=extra))
    if g is None:
        assert_error(r, "saltdem/tiltwall", "default g = 9.81", "m/s^2", "units cgs", "'g G'")
        return
    check_ok(r)
    t = r.thermo()
    assert t["f_tw[2]"][-1] == pytest.approx(g * 0.5, rel=1e-12)
    assert t["f_tw[3]"][-1] == pytest.approx(-g * math.cos(math.radians(30)), rel=1e-12)


# ---------------------------------------------------------------------------------------------
# fix saltdem/viscosity: SI numbers from any physical unit system
# ---------------------------------------------------------------------------------------------

VISC = """units {units}
dimension 2
atom_style sphere
boundary p p p
comm_modify vel yes
region box block 0 200 0 200 -100 100
create_box 1 box
lattice sq 20
create_atoms 1 box
set type 1 diameter 20
set type 1 density/disc 2200
pair_style saltdem/viscous
pair_coeff * * 1.0 0 fluid 28 1e8
fix nve all saltdem/nve inertia 20
fix scale all saltdem/viscosity lambda 1e9 natural {eta} rate {rate} length {length} density {rho}
timestep 1e-7
thermo_style custom step f_scale[1] f_scale[2] f_scale[3] f_scale[4] f_scale[5] f_scale[6] f_scale[7]
thermo_modify format float %.17g
run 100
"""
# the paper's natural salt in SI and in cgs (1 Pa s = 10 P, m -> 100 cm, kg/m^3 -> 1e-3 g/cm^3);
# the time step, 1e-7 in both, is a second in both
SI = dict(units="si", eta=5e17, rate=0.05, length=1000, rho=2200)
CGS = dict(units="cgs", eta=5e18, rate=5.0, length=1e5, rho=2.2)


def test_viscosity_fix_reports_si_numbers_in_cgs(lmp):
    a = lmp(VISC.format(**SI))
    check_ok(a)
    b = lmp(VISC.format(**CGS))
    check_ok(b)
    ta, tb = a.thermo(), b.thermo()
    for k in range(1, 8):
        col = f"f_scale[{k}]"
        assert tb[col][-1] == pytest.approx(ta[col][-1], rel=1e-12), col
    # the numbers themselves: S rho V L / eta, model time 1e-5 s, 1.58 m/ka
    assert ta["f_scale[1]"][-1] == pytest.approx(20 * 2200 * 0.05 * 1000 / 5e8, rel=1e-12)
    assert ta["f_scale[3]"][-1] == pytest.approx(1e-5, rel=1e-9)
    assert ta["f_scale[5]"][-1] == pytest.approx(1.5779, rel=1e-4)


def test_viscosity_fix_refuses_lj(lmp):
    deck = VISC.format(**SI).replace("units si", "units lj")
    assert_error(lmp(deck), "saltdem/viscosity", "units lj", "no physical time")


# ---------------------------------------------------------------------------------------------
# the pair styles: damping ratio and stable limit with force->ftm2v
# ---------------------------------------------------------------------------------------------

COLLIDE = """units {units}
dimension 2
atom_style sphere
atom_modify map array
boundary f f p
comm_modify vel yes
region box block -10 10 -10 10 -1 1
create_box 1 box
create_atoms 1 single -1 0 0
create_atoms 1 single 1 0 0
set type 1 diameter 2
set type 1 mass {mass}
velocity all set 0 0 0
set atom 1 vx {v}
set atom 2 vx -{v}
pair_style saltdem/cohesive
pair_coeff * * {kn} 0 0 0 0 0 damp 0.3 0.3
fix nve all saltdem/nve
saltdem/timestep 0.05
variable v1 equal vx[1]
thermo_style custom step v_v1
thermo_modify format float %.17g
run 3000
"""


def test_cohesive_collision_is_the_same_in_metal_and_si(lmp):
    """Two discs collide head on with a normal damping ratio of 0.3.  The restitution
    coefficient depends on that ratio only, and saltdem/timestep takes the same fraction of the
    contact period in both unit systems, so metal units (force x time / mass = 9648.5 times a
    velocity) give SI's coefficient; before, the damping and the limit left ftm2v out: the
    metal collision was overdamped."""
    e = {}
    for units, mass, kn, v in [("si", 1727.9, 1e7, 0.1), ("metal", 1000.0, 1.0, 0.001)]:
        r = lmp(COLLIDE.format(units=units, mass=mass, kn=kn, v=v))
        check_ok(r)
        e[units] = -r.thermo()["v_v1"][-1] / v
        ftm2v = 1.0 if units == "si" else 1.0 / 1.0364269e-4
        lim = float(r.out.split("of the stable limit ")[1].split()[0])
        assert lim == pytest.approx(0.6 * math.sqrt(mass / (kn * ftm2v)), rel=1e-5)
    zeta = 0.3
    assert e["si"] == pytest.approx(math.exp(-math.pi * zeta / math.sqrt(1 - zeta ** 2)), rel=0.05)
    assert e["metal"] == pytest.approx(e["si"], rel=1e-9)
