"""The frictional-viscous salt: pair saltdem/viscous, fluid ... yield MU C [modulus G]
(src/USER-SALTDEM/saltdem_plastic.h, the plastic pass of saltdem_sph_fields.cpp, the internal
fix SALTDEM_PLASTIC).  Its deviatoric stress is the Morris viscosity's plus a plastic stress of
strength C + MU P.

  unit        the plastic math and pass alone (tests/unit/plastic_test.cpp): the exact velocity
              gradient of a linear field, the rate, the strength, the elastic-plastic simple
              shear against its closed form
  Bingham     MU 0, C > 0 in the channel deck (tests/decks/channel.in, the paper's discs):
              plane Couette carries C more stress than the Newtonian flow; Poiseuille has the
              analytic Bingham profile with its plug
  Newtonian   a frictional strength (MU > 0) without load leaves the channel flow Newtonian
  load        under a lid pressure (examples/calibration/couette_load.in) the salt's stress
              against the contact salt's, at the scenes' calibration (docs/validation.md)
  parallel    2 MPI ranks and 2 OpenMP threads give the serial stress; restart continues
              exactly (the plastic stress goes to the restart file)
  errors      bad keywords and values
"""
import re

import numpy as np
import pytest

from lmprun import ROOT, assert_error, check_ok, run_lmp, run_unit
from saltdem_post.channel import ChannelFlow, read_params

CHANNEL = (ROOT / "tests" / "decks" / "channel.in").read_text()
PARAMS = ROOT / "potentials" / "salt_paper.params"
PACK_IN = ROOT / "tools" / "pack.in"
LOAD = ROOT / "examples" / "calibration" / "couette_load.in"
PAPER = read_params(PARAMS)
ETA, RHO, S_PAPER = PAPER["eta"], PAPER["rho"], PAPER["S"]
RMIN, RMAX = PAPER["rmin"], PAPER["rmax"]
PACK = dict(W=1000, H=500, seed=7)
NSTEPS = 10000
SALT_PAPER = dict(mu=0.085, eta=8.8e8)    # the scenes' frictional-viscous salt (examples/scene/params.in)


def test_plastic_math_alone(tmp_path):
    run_unit("plastic_test", tmp_path, ["saltdem_sph_fields.cpp"])


@pytest.fixture(scope="module")
def pack(tmp_path_factory):
    d = tmp_path_factory.mktemp("pack")
    r = run_lmp(PACK_IN.read_text(), d, rmin=RMIN, rmax=RMAX, out="pack.data", **PACK)
    check_ok(r)
    return d / "pack.data"


class Channel(ChannelFlow):
    def __init__(self, run, V=0.0, gx=0.0):
        super().__init__(run.workdir, run.out, PACK["H"], RMAX, RHO, V, gx, eta=ETA, S=S_PAPER)
        self.run = run


@pytest.fixture(scope="module")
def channel(pack, tmp_path_factory):
    cache = {}

    def get(V=0.0, gx=0.0, yopt="", nsteps=NSTEPS):
        key = (V, gx, yopt, nsteps)
        if key not in cache:
            d = tmp_path_factory.mktemp("channel")
            extra = dict(yopt=yopt) if yopt else {}
            r = run_lmp(f"include {PARAMS}\n" + CHANNEL, d, pack=pack, V=V, gx=gx, nsteps=nsteps,
                        **extra)
            check_ok(r)
            cache[key] = Channel(r, V=V, gx=gx)
        return cache[key]

    return get


# ---------------------------------------------------------------------------
# Bingham and Newtonian limits
# ---------------------------------------------------------------------------

def test_bingham_couette_carries_its_strength(channel):
    """Couette V 1 m/s with a strength C = 3e5 Pa (MU 0), about a quarter of the viscous
    stress: the wall stress is the Newtonian flow's plus C within 5 % of C, and the profile
    stays linear (the strength is uniform, so is the shear rate)."""
    C = 3e5
    a = channel(V=1.0)
    b = channel(V=1.0, yopt=f"yield 0 {C}")
    assert "SALTDEM_PLASTIC" not in a.run.out
    assert b.tau - a.tau == pytest.approx(C, rel=0.05), (a.tau, b.tau)
    assert b.fit(1)[1] > 0.99
    assert b.rate == pytest.approx(a.rate, rel=0.03)


def bingham_poiseuille(y, g, rho, eta, C, y0, y1):
    """The analytic Bingham profile between no-slip walls at y0, y1 under a body force g:
    the stress rho g (yc - y) is plastic where it exceeds C, a plug of half-width C / (rho g)
    around the centre yc moves rigidly."""
    yc, half = 0.5 * (y0 + y1), 0.5 * (y1 - y0)
    yp = C / (rho * g)
    s = np.minimum(np.abs(y - yc), half)
    s = np.maximum(s, yp)
    return rho * g / (2 * eta) * ((half - yp) ** 2 - (s - yp) ** 2)


def test_bingham_poiseuille_has_its_plug(channel):
    """Body force 12 m/s^2, C = 0.3 of the wall stress: the interior profile is the analytic
    Bingham profile (plug of 0.3 of the half-width, parabolic flanks) within 5 % of its
    maximum, whose value is 0.49 of the Newtonian one; the Newtonian run is parabolic."""
    g = 12.0
    a = channel(gx=g)
    p, r2 = a.fit(2)
    y0, y1 = sorted(np.roots(p).real)
    tau_w = a.rhob * g * 0.5 * (y1 - y0)
    C = 0.3 * tau_w
    b = channel(gx=g, yopt=f"yield 0 {C:.6g}")
    y, n, vx = b.profile()
    m = b.interior(y)
    # the Newtonian run sets the effective channel (y0, y1) and the viscosity it flows with
    eta_eff = a.rhob * g * (y1 - y0) ** 2 / (8 * (p[2] - p[1] ** 2 / (4 * p[0])))
    want = bingham_poiseuille(y[m], g, b.rhob, eta_eff, C, y0, y1)
    err = np.abs(vx[m] - want).max() / want.max()
    assert want.max() == pytest.approx(0.49 * a.rhob * g * (y1 - y0) ** 2 / (8 * eta_eff), rel=1e-9)
    assert err < 0.05, (np.c_[y[m], vx[m], want])
    # the plug: the layers within it move together (spread < 2 % of the maximum)
    plug = np.abs(y[m] - 0.5 * (y0 + y1)) < 0.8 * C / (b.rhob * g)
    assert plug.sum() >= 2
    assert np.ptp(vx[m][plug]) < 0.02 * want.max()


def test_frictional_strength_without_load_is_newtonian(channel):
    """MU 0.1 (the scenes' frictional-viscous salt) without overburden: the salt carries
    next to no pressure, so the Couette stress stays the Newtonian one within 3 %."""
    a = channel(V=1.0)
    b = channel(V=1.0, yopt=f"yield {SALT_PAPER['mu']} 0")
    assert "SALTDEM_PLASTIC" in b.run.out or b.tau != a.tau
    assert b.tau == pytest.approx(a.tau, rel=0.03)


# ---------------------------------------------------------------------------
# under load, against the contact salt
# ---------------------------------------------------------------------------

def load_run(tmp_path, name, P, rate, **vars_):
    d = tmp_path / f"{name}_{P}_{rate}"
    d.mkdir()
    deck = LOAD.read_text()
    r = run_lmp(deck, d, root=ROOT, P=P, rate=rate, strain=2, **vars_)
    check_ok(r)
    m = re.search(r"couette_load: result law \S+ P \S+ rate (\S+) tau (\S+) Pa", r.out)
    assert m, r.out[-2000:]
    return float(m.group(2))


@pytest.mark.parametrize("P", ["5e6", "1e7", "2e7"])
def test_loaded_couette_matches_the_contact_salt(tmp_path, P):
    """Under a lid at 5, 10 and 20 MPa sheared at 5e-4 1/s, the frictional-viscous salt of the
    scenes carries the contact salt's stress within 10 % (both measured here on the same
    deck; docs/validation.md lists both at the scenes' rate too)."""
    contact = load_run(tmp_path, "contact", P, "5e-4", law="contact", cal=0.5)
    fv = load_run(tmp_path, "fv", P, "5e-4", law="sph", mu_y=SALT_PAPER["mu"], eta=SALT_PAPER["eta"])
    assert fv == pytest.approx(contact, rel=0.10), (P, fv, contact)


# ---------------------------------------------------------------------------
# MPI, OpenMP, restart
# ---------------------------------------------------------------------------

YOPT = "yield 0.1 3e5"
SHORT = f"include {PARAMS}\n" + CHANNEL + \
    "write_dump all custom final.dump id x y vx vy modify sort id format float %.17g\n"


def read_dump(path):
    lines = path.read_text().split("ITEM: ATOMS")[1].splitlines()[1:]
    return {int(s[0]): [float(v) for v in s[1:]] for s in (l.split() for l in lines) if s}


def max_diff(a, b, cols=(0, 1)):
    assert a.keys() == b.keys()
    return max(abs(a[i][c] - b[i][c]) for i in a for c in cols)


@pytest.fixture(scope="module")
def short_serial(pack, tmp_path_factory):
    d = tmp_path_factory.mktemp("short")
    r = run_lmp(SHORT, d, pack=pack, V=1.0, nsteps=1000, yopt=YOPT)
    check_ok(r)
    return Channel(r, V=1.0), read_dump(d / "final.dump")


@pytest.mark.parametrize("mode", ["np2", "omp2"])
def test_parallel_same_stress(short_serial, pack, tmp_path, mode):
    """2 x 1,000 Couette steps with a plastic strength on 2 MPI ranks or 2 OpenMP threads: the
    serial wall stress within 1e-6 and positions within 1e-8 of the box width."""
    a, da = short_serial
    kw = dict(np=2) if mode == "np2" else dict(omp=2)
    r = run_lmp(SHORT, tmp_path, pack=pack, V=1.0, nsteps=1000, yopt=YOPT, **kw)
    check_ok(r)
    b = Channel(r, V=1.0)
    assert b.tau == pytest.approx(a.tau, rel=1e-6)
    assert max_diff(da, read_dump(tmp_path / "final.dump")) / PACK["W"] < 1e-8


RESTART_A = f"include {PARAMS}\n" + CHANNEL.replace(
    "run             $(v_nsteps)\nrun             $(v_nsteps)\n",
    "run 400\nwrite_restart r.restart\nrun 400\n"
    "write_dump all custom final.dump id x y vx vy modify sort id format float %.17g\n")

RESTART_B = """read_restart r.restart
comm_modify vel yes
neighbor 2.8 bin
neigh_modify exclude type 3 3
neigh_modify every 1 delay 0 check yes
fix integ salt saltdem/nve inertia 20
fix drive top move linear 1 0 0 units box
fix 2d all enforce2d
run 400
write_dump all custom final.dump id x y vx vy modify sort id format float %.17g
"""


def test_restart_continues_identically(pack, tmp_path):
    """run 400; write_restart; run 400 == read_restart; run 400 with a plastic strength: the
    plastic stress and the strength come back from the restart file (positions within 1e-10
    of the box width).  Control: continued without the strength, it differs."""
    ra = run_lmp(RESTART_A, tmp_path, pack=pack, V=1.0, nsteps=400, yopt=YOPT)
    check_ok(ra)
    a = read_dump(tmp_path / "final.dump")
    rb = run_lmp(RESTART_B, tmp_path)
    check_ok(rb)
    b = read_dump(tmp_path / "final.dump")
    assert max_diff(a, b) / PACK["W"] < 1e-10
    rc = run_lmp(RESTART_B.replace("run 400", "pair_coeff 2 2 5e8 0 fluid 28 1e8\nrun 400", 1),
                 tmp_path)
    check_ok(rc)
    assert max_diff(a, read_dump(tmp_path / "final.dump")) / PACK["W"] > 1e-8


# ---------------------------------------------------------------------------
# errors and the stable step
# ---------------------------------------------------------------------------

BASE = """units si
dimension 2
atom_style sphere
boundary p f p
comm_modify vel yes
region box block 0 200 0 200 -0.5 0.5
create_box 2 box
lattice sq 20
create_atoms 1 box
region low block INF INF INF 25 INF INF units box
set region low type 2
set group all diameter 19
set group all density/disc 2200
group salt type 1
neighbor 2.8 bin
pair_style saltdem/viscous
pair_coeff * * 5e8 1e7 fluid 28 1e8
pair_coeff 1 1 {coeff}
neigh_modify exclude type 2 2
fix 1 salt saltdem/nve inertia 20
fix 2 all enforce2d
timestep {dt}
run 10
"""


@pytest.mark.parametrize("coeff,words", [
    ("5e8 0 fluid 28 0 yield 0.1 0", "yield needs a fluid that carries pressure (K > 0"),
    ("5e8 0 fluid 28 1e8 modulus 1e8", "modulus G is the elastic part of a plastic strength"),
    ("5e8 0 fluid 28 1e8 yield -0.1 0", "yield MU = -0.1 and C = 0 must be >= 0"),
    ("5e8 0 fluid 28 1e8 yield 0.1", "unexpected or incomplete 'yield' after 'fluid h K'"),
    ("5e8 0 fluid 28 1e8 yield 0.1 0 modulus 0", "modulus G = 0 must be > 0"),
    ("5e8 0 fluid 28 1e8 friction 0.1", "unexpected or incomplete 'friction'"),
])
def test_error(lmp, coeff, words):
    assert_error(lmp(BASE.format(coeff=coeff, dt=0.001)), words)


def test_plastic_modulus_sets_the_sound_limit(lmp):
    """The plastic stress is elastic below yield: the sound limit follows K + 4G/3, and a step
    beyond it is refused naming G."""
    r = lmp(BASE.format(coeff="5e8 0 fluid 28 1e9 yield 0.1 0 modulus 3e10", dt=0.001))
    check_ok(r)
    m = re.search(r"stable limit ([0-9.eE+-]+) \(K = 1e\+09 and plastic modulus G = 3e\+10", r.out)
    assert m, r.out[-3000:]
    c = np.sqrt((1e9 + 4 * 3e10 / 3) / (0.7 * 20 * 2200))
    assert float(m.group(1)) == pytest.approx(0.25 * 28 / c, rel=1e-3)
    assert_error(lmp(BASE.format(coeff="5e8 0 fluid 28 1e9 yield 0.1 0 modulus 3e10",
                                 dt=2 * float(m.group(1)))), "plastic modulus G")
