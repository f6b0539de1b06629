"""fix saltdem/viscosity: viscosity scaling by lambda (paper section 2.1, Tables 1 and 2)."""
import re

import pytest

from lmprun import ROOT, assert_error, check_ok

TABLE_DECK = (ROOT / "examples" / "scaling" / "table1.in").read_text()

# the paper's Tables 1 and 2: model | natural
PAPER = {
    1: {"total time (days)": ("0.231", None), "total time (years)": ("0.000634", "6.34e+05"),
        "displacement rate (m/s)": ("0.05", "5e-11"), "displacement rate (m/ka)": (None, "1.58"),
        "Reynolds number": ("0.00022", "2.2e-22"), "salt viscosity (Pa s)": ("5e+08", "5e+17")},
    2: {"total time (days)": ("1.16", None), "total time (years)": ("0.00317", "3.17e+06"),
        "displacement rate (m/s)": ("0.01", "1e-11"), "displacement rate (m/ka)": (None, "0.316"),
        "Reynolds number": ("4.4e-05", "4.4e-23")},
}


@pytest.mark.parametrize("table", [1, 2])
def test_paper_tables(lmp, table):
    r = lmp(TABLE_DECK, table=table)
    check_ok(r)
    rows = {}
    for line in r.out.splitlines():
        m = re.match(rf"TABLE {table}: (.+?)\s{{2,}}(\S+) \| (\S+)", line)
        if m:
            rows[m.group(1)] = (m.group(2), m.group(3))
    for name, (model, natural) in PAPER[table].items():
        if model:
            assert float(rows[name][0]) == pytest.approx(float(model), rel=2e-3), name
        if natural:
            assert float(rows[name][1]) == pytest.approx(float(natural), rel=2e-3), name


BASE = """
units si
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
fix nve all saltdem/nve
timestep ${dt}
"""
FIX = "fix scale all saltdem/viscosity lambda 1e9 natural 5e17 rate 0.05 length 1000 density 2200"


def test_sets_the_pair_viscosity(lmp):
    """natural 5e17 / lambda 1e9: the pair now has eta 5e8, which its time step check names."""
    line = assert_error(lmp(BASE + FIX + "\nrun 1\n", dt=1.0), "saltdem/viscous", "eta = 5e+08")
    assert "types 1 1" in line


def test_natural_time_runs_and_survives_restart(lmp, tmp_path):
    deck = BASE + FIX + """
thermo_style custom step time f_scale[3] f_scale[4]
run 100
write_restart r.restart
clear
read_restart r.restart
comm_modify vel yes
fix nve all saltdem/nve
""" + FIX + """
timestep ${dt}
thermo_style custom step time f_scale[3] f_scale[4]
run 100
"""
    r = lmp(deck, dt=1e-5)
    check_ok(r)
    a, b = r.thermo(0), r.thermo(1)
    assert a["f_scale[3]"][-1] == pytest.approx(100 * 1e-5)
    year = 365.25 * 86400
    assert a["f_scale[4]"][-1] == pytest.approx(1e9 * 1e-3 / year)
    # the natural clock continues after read_restart
    assert b["f_scale[3]"][-1] == pytest.approx(200 * 1e-5)
    assert b["f_scale[4]"][-1] == pytest.approx(1e9 * 2e-3 / year)


def test_warns_when_inertia_matters(lmp):
    fast = FIX.replace("rate 0.05", "rate 50")    # Re = 2200 * 50 * 1000 / 5e8 = 0.22
    r = lmp(BASE + fast + "\nrun 0\n", dt=1e-6)
    check_ok(r)
    assert re.search(r"WARNING: Fix saltdem/viscosity: the model Reynolds number 0.22 ", r.out)
    r = lmp(BASE + FIX + "\nrun 0\n", dt=1e-6)
    assert "Reynolds number" not in (r.error() or "") and "WARNING: Fix saltdem/viscosity" not in r.out


@pytest.mark.parametrize("args,words", [
    ("lambda 1e9 rate 0.05 length 1000 density 2200", ["exactly one of 'natural' and 'model'"]),
    ("lambda 1e9 natural 5e17 model 5e8 rate 0.05 length 1000 density 2200", ["exactly one"]),
    ("lambda 1e9 natural 5e17 rate 0.05 density 2200", ["'length' is required"]),
    ("lambda -1 natural 5e17 rate 0.05 length 1000 density 2200", ["lambda = -1"]),
    ("lambda 1e9 natural 5e17 rate 0.05 length 1000 density 2200 bogus 1", ["unknown keyword 'bogus'"]),
    ("lambda 1e9 natural 5e17 rate 0.05 length 1000 density 2200 inertia 0.5", ["inertia = 0.5"]),
    ("scale 1e9 natural 5e17", ["expected 'lambda'"]),
    ("lambda 1e9 natural", ["saltdem/viscosity natural"]),
    ("lambda 1e9 natural 5e17 rate 0.05 length 1000 density 2200 contrast 0", ["contrast = 0"]),
    ("lambda 1e9 natural 5e17 rate 0.05 length 1000 density 2200 gravity 9.81",
     ["'gravity' is used with 'contrast' only"]),
    ("lambda 1e9 natural 5e17 rate 0.05 length 1000 density 2200 contrast 240 gravity -1",
     ["gravity = -1"]),
])
def test_errors(lmp, args, words):
    r = lmp(BASE + f"fix scale all saltdem/viscosity {args}\nrun 0\n", dt=1e-6)
    assert_error(r, "saltdem/viscosity", *words)


def test_sets_every_viscous_substyle(lmp):
    """pair_style hybrid with two saltdem/viscous sub-styles (two salts): the fix sets the
    viscosity of both; each sub-style's stable time step (bound by the viscosity here) then
    names the new value, and without the fix neither does."""
    deck = BASE.replace("create_box 1 box", "create_box 2 box").replace(
        "set type 1 diameter 20",
        "set group all type/fraction 2 0.5 7\nset group all diameter 20").replace(
        "set type 1 density/disc 2200", "set group all density/disc 2200").replace(
        "pair_style saltdem/viscous\npair_coeff * * 1.0 0 fluid 28 1e8",
        "pair_style hybrid saltdem/viscous saltdem/viscous\n"
        "pair_coeff 1 1 saltdem/viscous 1 1.0 0 fluid 28 1e8\n"
        "pair_coeff 1 2 saltdem/viscous 1 1.0 0 fluid 28 1e8\n"
        "pair_coeff 2 2 saltdem/viscous 2 1.0 0 fluid 28 1e8")
    assert deck.count("saltdem/viscous 2 1.0") == 1
    r = lmp(deck + FIX + "\nrun 0\n", dt=1e-6)
    check_ok(r)
    assert "(set on 3 type pairs)" in r.out
    checks = [l for l in r.out.splitlines() if l.startswith("Pair style saltdem/viscous: timestep")]
    assert len(checks) == 2 and all("eta = 5e+08" in l for l in checks), checks
    r0 = lmp(deck + "\nrun 0\n", dt=1e-6)
    check_ok(r0)
    assert "eta = 5e+08" not in r0.out


def test_needs_the_viscous_pair(lmp):
    deck = BASE.replace("pair_style saltdem/viscous\npair_coeff * * 1.0 0 fluid 28 1e8",
                        "pair_style saltdem/cohesive\npair_coeff * * 1e9 0 0.5 0 0 0")
    assert_error(lmp(deck + FIX + "\nrun 0\n", dt=1e-6), "saltdem/viscosity", "saltdem/viscous")


def test_reads_the_inertia_factor_from_the_integrator(lmp):
    """S is given once, in fix saltdem/nve: the fix reads it through the salt pair style's
    extract("inertia") (also from an integrator defined after it), and the model Reynolds
    number is S rho V L / eta."""
    deck = BASE.replace("fix nve all saltdem/nve\n", "") + FIX + \
        "\nfix nve all saltdem/nve inertia 20\nthermo_style custom step f_scale[1]\nrun 0\n"
    r = lmp(deck, dt=1e-6)
    check_ok(r)
    assert r.thermo()["f_scale[1]"][0] == pytest.approx(20 * 2200 * 0.05 * 1000 / 5e8, rel=1e-12)
    assert "inertia x20 (salt's integrator)" in r.out


@pytest.mark.parametrize("given,ok", [(20, True), (10, False)])
def test_inertia_keyword_must_agree_with_the_integrator(lmp, given, ok):
    deck = BASE.replace("saltdem/nve\n", "saltdem/nve inertia 20\n") + FIX + \
        f" inertia {given}\nrun 0\n"
    r = lmp(deck, dt=1e-6)
    if ok:
        check_ok(r)
    else:
        assert_error(r, "saltdem/viscosity", "inertia 10 differs from the inertia factor 20",
                     "drop the keyword")


def test_buoyancy_stress_against_the_viscous_stress(lmp):
    """contrast 240 kg/m^3 over 1000 m: drho g L = 2.3544e6 Pa against eta V / L = 5e8 x 0.05 /
    1000 = 2.5e4 Pa (ratio 94.18), buoyancy time eta/(drho g L) = 212.4 s (natural: lambda x that,
    6730 years), Re_b = S rho drho g L^3 / eta^2 = 2160 x 2.3544e6 x 1e6 / 2.5e17 = 0.02034 (S 1);
    a denser salt (contrast -240) reports the same magnitudes with the stress's sign; without
    contrast 8, 10-12 are 0 and 9 is still the viscous stress"""
    vals = "f_scale[8] f_scale[9] f_scale[10] f_scale[11] f_scale[12]"
    fix = ("fix scale all saltdem/viscosity lambda 1e9 model 5e8 rate 0.05 length 1000 "
           "density 2160 contrast {}\nthermo_style custom step " + vals + "\nrun 0\n")
    r = lmp(BASE + fix.format(240), dt=1e-6)
    check_ok(r)
    t = r.thermo(0)
    got = [t[k][-1] for k in vals.split()]
    assert got == pytest.approx([2.3544e6, 2.5e4, 94.176, 212.3683, 0.0203420], rel=1e-4)
    assert re.search(r"buoyancy: density contrast 240 .* stress drho g L 2\.354e\+06 against "
                     r"the viscous stress eta V/L 2\.5e\+04 \(Pa\), ratio 94\.18", r.out)
    assert "6730 years (natural)" in r.out
    r = lmp(BASE + fix.format(-240), dt=1e-6)
    check_ok(r)
    t = r.thermo(0)
    assert [t[k][-1] for k in vals.split()] == pytest.approx(
        [-2.3544e6, 2.5e4, -94.176, 212.3683, 0.0203420], rel=1e-4)
    r = lmp(BASE + fix.format("").replace(" contrast ", ""), dt=1e-6)
    check_ok(r)
    t = r.thermo(0)
    assert [t[k][-1] for k in vals.split()] == [0.0, pytest.approx(2.5e4), 0.0, 0.0, 0.0]
    assert "buoyancy:" not in r.out


def test_buoyancy_needs_gravity_outside_si(lmp):
    """under units cgs the default 9.81 m/s^2 would be wrong: the fix asks for 'gravity'"""
    deck = BASE.replace("units si", "units cgs").replace("density/disc 2200", "density/disc 2.2")
    fix = ("fix scale all saltdem/viscosity lambda 1e9 model 5e9 rate 5 length 1e5 density 2.16 "
           "contrast 0.24{}\nrun 0\n")
    assert_error(lmp(deck + fix.format(""), dt=1e-6), "saltdem/viscosity", "'gravity g'", "cgs")
    r = lmp(deck + fix.format(" gravity 981") + "thermo_style custom step f_scale[8] f_scale[10]\nrun 0\n",
            dt=1e-9)
    check_ok(r)
    t = r.thermo(-1)
    # cgs: 0.24 g/cm^3 x 981 cm/s^2 x 1e5 cm = 2.3544e7 dyn/cm^2 (= 2.3544e6 Pa), over
    # eta V / L = 5e9 x 5 / 1e5 = 2.5e5 dyn/cm^2
    assert t["f_scale[8]"][-1] == pytest.approx(2.3544e7, rel=1e-6)
    assert t["f_scale[10]"][-1] == pytest.approx(94.176, rel=1e-4)
