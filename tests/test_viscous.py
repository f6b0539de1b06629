"""Tests of pair_style saltdem/viscous and fix saltdem/nve
(src/USER-SALTDEM/pair_saltdem_viscous.*, fix_saltdem_nve.*, law in
saltdem_contact_viscous.h: viscous_fluid_force, viscous_contact_force).

The salt is a linear Newtonian fluid of viscosity eta.  Its discs interact by
the Morris SPH viscosity (Wendland C2 kernel, support 2h, volumes m/rho from a
kernel-density pass), an SPH pressure P = K (rho/rho0 - 1) and a soft elastic
hard core kn; they are integrated by fix saltdem/nve with an inertia factor S
(forces divided by S m).  The flows run in tests/decks/channel.in: a random
dense pack of the paper's discs (tools/pack.in, W 1000 m x H 500 m, radii
6.25-15.625 m), x periodic, between two no-slip wall bands of 2 rmax.

  plane Couette (top band moves at V):  tau = eta_eff * dv/dy, v linear
  plane Poiseuille (body force gx):     v parabolic, v_max = rho g H^2 / (8 eta)

Measures (the same in every test):
  tau       the x force on the top band per unit width (channel_stress.txt),
            averaged over the second half of each of the deck's two runs of
            nsteps: the value used is that of steps 1.5-2 x nsteps
  profile   salt vx in 20 layers, averaged likewise (channel_profile.txt);
            fits use the layers whose centres lie more than 3 rmax inside the
            salt, i.e. beyond 2 rmax + 3 rmax from the box edges (the band edge is the SPH boundary: the wall particles'
            volumes fill the band, the fluid's begin at its edge)
  eta_eff   tau / (slope of the linear fit)
  rho       (Poiseuille) the salt mass per area printed by the deck

The paper's parameters come from potentials/salt_paper.params, included
before the deck.  Runs shared by several tests are made once per module.
Section 0 checks the forces against an independent numpy implementation of
the equations of docs/pair_saltdem_viscous.rst.
"""
import math
import re

import numpy as np
import pytest

from lmprun import ROOT, assert_error, check_ok, run_lmp
from saltdem_post.channel import ChannelFlow, read_params

CHANNEL = (ROOT / "tests" / "decks" / "channel.in").read_text()
PARAMS = ROOT / "potentials" / "salt_paper.params"
PACK_IN = ROOT / "tools" / "pack.in"

PAPER = read_params(PARAMS)
ETA, RHO, S_PAPER, DT = PAPER["eta"], PAPER["rho"], PAPER["S"], PAPER["dt"]
CORRECTION = 1.047    # the style's default fluid viscosity correction (pair_style ... correction)
RMIN, RMAX = PAPER["rmin"], PAPER["rmax"]
PACK = dict(W=1000, H=500, seed=7)
NSTEPS = 10000            # the channel deck runs 2 x NSTEPS, averages the second half
REYNOLDS_MAX = 0.05       # rho S V H / eta: above it inertia changes the flow


# ---------------------------------------------------------------------------
# running LAMMPS (module-scoped runs; the `lmp` fixture of conftest.py is
# function-scoped)
# ---------------------------------------------------------------------------

def read_dump(path):
    """{id: [columns after id]} from a text dump written with 'modify sort id'."""
    lines = path.read_text().split("ITEM: ATOMS")[1].splitlines()[1:]
    return {int(s[0]): [float(v) for v in s[1:]] for s in (l.split() for l in lines) if s}


def max_diff(a, b, cols=(0, 1)):
    assert a.keys() == b.keys()
    return max(abs(a[i][c] - b[i][c]) for i in a for c in cols)


# ---------------------------------------------------------------------------
# the channel flows
# ---------------------------------------------------------------------------

class Channel(ChannelFlow):
    """The channel flow of a test run (an lmprun Run) at the paper's disc size and density."""

    def __init__(self, run, H, V=0.0, gx=0.0, eta=ETA, S=S_PAPER):
        super().__init__(run.workdir, run.out, H, RMAX, RHO, V, gx, eta=eta, S=S)
        self.run = run


@pytest.fixture(scope="module")
def pack(tmp_path_factory):
    """The dense random pack of the paper's discs, made once per module (~10 s)."""
    d = tmp_path_factory.mktemp("pack")
    r = run_lmp(PACK_IN.read_text(), d, rmin=RMIN, rmax=RMAX, out="pack.data", **PACK)
    check_ok(r)
    m = re.search(r"pack: (\d+) discs, .*packing fraction ([0-9.]+)", r.out)
    assert m, r.out[-2000:]
    n, phi = int(m.group(1)), float(m.group(2))
    assert n > 900 and 0.80 < phi < 0.90, (n, phi)
    return d / "pack.data"


@pytest.fixture(scope="module")
def channel(pack, tmp_path_factory):
    """channel(V=, gx=, eta=, S=, nsteps=) runs the channel deck once per set of
    arguments with the paper's parameters (potentials/salt_paper.params)."""
    cache = {}

    def get(V=0.0, gx=0.0, eta=ETA, S=S_PAPER, nsteps=NSTEPS):
        key = (V, gx, eta, S, nsteps)
        if key not in cache:
            d = tmp_path_factory.mktemp("channel")
            r = run_lmp(f"include {PARAMS}\n" + CHANNEL, d, pack=pack, V=V, gx=gx, eta=eta, S=S,
                        nsteps=nsteps)
            check_ok(r)
            cache[key] = Channel(r, PACK["H"], V=V, gx=gx, eta=eta, S=S)
        return cache[key]

    return get


def test_params_file_is_includable(lmp):
    """potentials/salt_paper.params is valid LAMMPS and holds the paper's salt;
    a -var on the command line overrides it."""
    deck = (f"include {PARAMS}\n"
            'print "P eta=${eta} rho=${rho} rmin=${rmin} rmax=${rmax} kn_salt=${kn_salt} '
            'kn_wall=${kn_wall} K_salt=${K_salt} h_salt=${h_salt} S=${S} dt=${dt}"\n')
    r = lmp(deck)
    check_ok(r)
    line = next(l for l in r.out.splitlines() if l.startswith("P eta="))
    got = {k: float(v) for k, v in (w.split("=") for w in line.split()[1:])}
    assert got == dict(eta=5e8, rho=2200, rmin=6.25, rmax=15.625, kn_salt=0, kn_wall=5e9,
                       K_salt=1e8, h_salt=28, S=20, dt=0.002)
    assert got == {k: PAPER[k] for k in got}
    r = lmp(deck, eta="1e9")
    assert "P eta=1e9 " in r.out


# ---------------------------------------------------------------------------
# 0. the law itself: an independent implementation of the documented
#    equations (docs/pair_saltdem_viscous.rst) reproduces the forces
# ---------------------------------------------------------------------------

def wendland(r, h):
    """2D Wendland C2 kernel and |dW/dr|/r."""
    q = r / h
    s = np.clip(1.0 - 0.5 * q, 0.0, None)
    a = 7.0 / (4.0 * math.pi * h * h)
    return a * s ** 4 * (1.0 + 2.0 * q), 35.0 / (4.0 * math.pi * h ** 4) * s ** 3


class Snapshot:
    """A channel dump (id type x y vx vy radius mass fx fy f_SALTDEM_DENSITY) and the SPH fields
    computed from it in numpy: kernel densities over all pairs within 2h
    except wall-wall (excluded from the neighbour list by the deck)."""

    def __init__(self, path, W, h=PAPER["h_salt"]):
        d = read_dump(path)
        a = np.array([d[i] for i in sorted(d)])
        self.type = a[:, 0].astype(int)
        self.x, self.v = a[:, 1:3], a[:, 3:5]
        self.radius, self.m, self.f = a[:, 5], a[:, 6], a[:, 7:9]
        self.rhoc = a[:, 9]    # the continuity density the style carries per atom
        self.h = h
        dx = self.x[:, None, 0] - self.x[None, :, 0]
        dx -= W * np.round(dx / W)
        dy = self.x[:, None, 1] - self.x[None, :, 1]
        self.r = np.hypot(dx, dy)
        n = len(self.m)
        walls = self.type == 3
        self.pair = (self.r < 2 * h) & ~np.eye(n, dtype=bool) & ~(walls[:, None] & walls[None, :])
        r = np.where(self.pair, self.r, 1.0)
        self.n = np.stack([dx / r, dy / r], axis=-1)
        self.W, self.gradr = (np.where(self.pair, w, 0.0) for w in wendland(self.r, h))
        # mu_ij: the mass of j counted as i's material, m_i r_j^2 / r_i^2 (m_j for one density;
        # the salt's radii x 1.02 at the same masses make the salt 4 % lighter than the walls)
        self.mu = self.m[:, None] * (self.radius[None, :] / self.radius[:, None]) ** 2
        self.rho = self.m * wendland(0.0, h)[0] + (self.W * self.mu).sum(1)
        self.salt = self.type == 2
        # a full kernel: the kernel-weighted first moment |sum_j mu_ij w d| below 0.1 of
        # sum_j mu_ij w |d| (w = |W'|/r up to a constant); the reference density is the mean
        # kernel density of a type's particles with a full kernel
        g = self.gradr * self.mu
        first = np.hypot((g * dx).sum(1), (g * dy).sum(1))
        self.full = first < 0.1 * (g * self.r).sum(1)

    def rho0(self, t):
        """over all of the type's particles where none has a full kernel (the walls)"""
        k = (self.type == t) & self.full
        return self.rho[k if k.any() else self.type == t].mean()

    def forces(self, eta, K, kn, knw, rho0, wall_fluid=True, fill_max=1.0):
        """Force on each particle: Morris viscosity + SPH pressure + elastic core.
        Salt (type 2) is FLUID; walls (type 3) are FLUID too (wall_fluid) or have
        a 'contact' law of their own, with a FLUID salt-wall pair: then they
        carry no pressure (the salt's is mirrored) and their volume beside a
        salt disc i is mu_ij / rho0 of the salt."""
        fluid = self.salt | ((self.type == 3) & wall_fluid)     # FLUID law of their own
        carries = fluid & (K > 0)                                 # ... with a pressure
        r0 = np.array([rho0.get(t, 0.0) for t in self.type])
        rho = np.where(fluid, self.rhoc, rho0[2])
        P = np.where(carries, K * (rho / np.where(carries, r0, 1.0) - 1.0), 0.0)
        a = self.m * P / rho ** 2
        # the boundary fill of a fluid particle: (1 - wf / rho) rho0_i / wb in [1, fill_max], wf
        # and wb its kernel sums sum_j mu_ij W over its fluid (itself included) and its boundary
        # partners; a boundary partner counts fill times its mass mu_ij, and has the volume
        # fill mu_ij / rho0_i, in the pair
        fi, fj = fluid[:, None], fluid[None, :]
        mu = self.mu
        wf = self.m * wendland(0.0, self.h)[0] + (self.W * fj * mu).sum(1)
        wb = (self.W * ~fj * mu).sum(1)
        fill = np.where(fluid & (wb > 0),
                        np.clip((1 - wf / rho) * r0 / np.where(wb > 0, wb, 1.0), 1.0, fill_max),
                        1.0)
        c = np.where(fi & ~fj, fill[:, None], np.where(fj & ~fi, fill[None, :], 1.0))
        vol = self.m / rho
        mj = mu * np.where(fj, 1.0, c)          # j in i's sums
        mi = mu.T * np.where(fi, 1.0, c)        # i in j's sums
        ir0 = np.where(r0 > 0, 1.0 / np.where(r0 > 0, r0, 1.0), 0.0)
        voli = np.where(fj & ~fi, mi * ir0[None, :], vol[:, None])
        volj = np.where(fi & ~fj, mj * ir0[:, None], vol[None, :])
        ci, cj = carries[:, None], carries[None, :]
        # the pressure matrix A = a L, L = (S / rho)^-1 with the kernel moment
        # S_i = sum_j m_j |W'|/r d d (d = x_i - x_j, boundary partners with the fill), the
        # plain a I where det(S / rho) < 0.1
        d = self.n * self.r[..., None]
        S = np.einsum("ij,ij,ija,ijb->iab", self.gradr, mj, d, d) / rho[:, None, None]
        det = np.linalg.det(S)
        ok = det >= 0.1
        L = np.where(ok[:, None, None], np.linalg.inv(np.where(ok[:, None, None], S, np.eye(2))),
                     np.eye(2))
        A = a[:, None, None] * L
        Ai, Aj = A[:, None], A[None, :]
        mi4, mj4 = mi[..., None, None], mj[..., None, None]
        pm = np.where((ci & cj)[..., None, None], mj4 * Ai + mi4 * Aj,
                      np.where(ci[..., None, None], 2 * mj4 * Ai,
                               np.where(cj[..., None, None], 2 * mi4 * Aj, 0.0)))
        fp = self.gradr[..., None] * np.einsum("ijab,ijb->ija", pm, d)
        knij = np.where((self.type[:, None] == 3) | (self.type[None, :] == 3), knw, kn)
        delta = self.radius[:, None] + self.radius[None, :] - self.r
        fel = np.where(self.pair & (delta > 0), knij * delta, 0.0)
        g = 2.0 * CORRECTION * eta * voli * volj * self.gradr
        dv = self.v[:, None, :] - self.v[None, :, :]
        return (fp + fel[..., None] * self.n - g[..., None] * dv).sum(axis=1)


def rho0_in(out, t):
    return float(re.search(rf"reference density of fluid type {t} = ([0-9.eE+-]+)", out).group(1))


SNAP = f"include {PARAMS}\n" + CHANNEL.replace(
    "run             $(v_nsteps)\nrun             $(v_nsteps)\n",
    "variable vxs atom 1e-3*y+0.2*sin(x/37.0)\n"
    "variable vys atom 0.1*cos(y/23.0+x/51.0)\n"
    "velocity salt set v_vxs v_vys 0\n"
    "run ${nrun}\n"
    "run 0\n"    # forces again with the dumped (full-step) velocities; run 0 does not advance rho
    "write_dump all custom snap.dump id type x y vx vy radius mass fx fy f_SALTDEM_DENSITY modify sort id "
    "format float %.17g\n")
assert "snap.dump" in SNAP


@pytest.mark.parametrize("case", ["paper", "K0", "contact-walls", "fill"])
def test_law_matches_equations(pack, tmp_path, case):
    """Five steps into a channel state (salt radii x 1.02, so salt discs
    overlap, and an arbitrary velocity field): the reference density is the
    mean kernel density of the salt at the first step, and every salt disc's
    force is the sum of the Morris viscosity 2 c eta V_i V_j |W'|/r (v_j - v_i)
    with V = m / rho (rho the continuity density the style dumps, c the
    correction), the corrected SPH pressure (m_j A_i + m_i A_j) |W'|/r (x_i - x_j) with
    A = m P / rho^2 (S / rho)^-1, S = sum_j m_j |W'|/r d d, and the elastic core kn delta n
    over all partners within 2h (within 1e-9 of the largest force).
    K0: a fluid without pressure (K = 0) keeps its kernel volumes and its
    viscosity.  contact-walls: the walls' own law is 'contact' and the
    salt-wall pair 'fluid': the walls mirror the salt's pressure and have the
    volume m / rho0 of the salt."""
    K = 0.0 if case == "K0" else PAPER["K_salt"]
    deck = SNAP
    if case == "fill":    # contact walls, whose salt partners count with their fill (max 8)
        deck = deck.replace("pair_style saltdem/viscous substeps ${substeps} ${popts}\"",
                            "pair_style saltdem/viscous fill 8 substeps ${substeps} ${popts}\"")
        assert "fill 8" in deck
    if case in ("contact-walls", "fill"):
        deck = deck.replace("neigh_modify    exclude type 3 3",
                            "pair_coeff 3 3 ${eta} ${knw} contact 0\n"
                            "neigh_modify    exclude type 3 3")
        assert "contact 0" in deck
    # 5 steps: the continuity density has moved off rho0, so the pressure acts
    r = run_lmp(deck, tmp_path, pack=pack, V=0, nrun=5, nsteps=100, shrink=1.02, K=K)
    check_ok(r)
    s = Snapshot(tmp_path / "snap.dump", PACK["W"])
    rho0 = {2: s.rho0(2), 3: s.rho0(3)}
    if K > 0:
        assert rho0_in(r.out, 2) == pytest.approx(rho0[2], rel=1e-3)    # taken 5 steps earlier
    if case == "paper":
        assert rho0_in(r.out, 3) == pytest.approx(rho0[3], rel=1e-3)
    assert np.abs(s.rhoc[s.salt] / rho0_in(r.out, 2) - 1.0).max() > 1e-6    # pressure is tested
    delta = s.radius[:, None] + s.radius[None, :] - s.r
    assert ((delta > 0) & s.pair)[np.ix_(s.salt, s.salt)].sum() > 100    # the core is tested
    # the law uses the reference densities it printed (taken 5 steps earlier)
    rho0 = {t: rho0_in(r.out, t) if f"fluid type {t} =" in r.out else v for t, v in rho0.items()}
    F = s.forces(ETA, K, PAPER["kn_salt"], PAPER["kn_wall"], rho0,
                 wall_fluid=case not in ("contact-walls", "fill"),
                 fill_max=8.0 if case == "fill" else 1.0)
    err = np.abs(F[s.salt] - s.f[s.salt]).max() / np.abs(s.f[s.salt]).max()
    assert err < 1e-9, f"forces differ from the equations by {err:.3g} of the largest"


def test_salt_at_rest_keeps_its_density(pack, tmp_path):
    """No wall motion, no body force, 2 x 5,000 steps from the channel's initial
    state: the salt's mean kernel density stays within 0.5 % of its reference
    rho0 (no spontaneous compaction).  A drift here makes the wall stress of
    the Couette flow drift too (test_couette_wall_stress_is_steady)."""
    r = run_lmp(SNAP.replace("velocity salt set v_vxs v_vys 0\n", ""), tmp_path, pack=pack, V=0,
                nrun=10000, nsteps=5000)
    check_ok(r)
    s = Snapshot(tmp_path / "snap.dump", PACK["W"])
    comp = s.rho[s.salt].mean() / rho0_in(r.out, 2) - 1.0
    delta = s.radius[:, None] + s.radius[None, :] - s.r
    over = ((delta > 0) & s.pair)[np.ix_(s.salt, s.salt)].sum() // 2
    assert abs(comp) < 0.005, \
        f"salt at rest: mean kernel density {100 * comp:+.2f} % from rho0, " \
        f"{over} overlapping salt pairs (none at the start)"


# ---------------------------------------------------------------------------
# 1. plane Couette
# ---------------------------------------------------------------------------

def test_couette_paper_parameters(channel):
    """eta 5e8, dt 0.002, S 20, radii 6.25-15.625, V 1 m/s (Re 0.04), 2 x 10,000
    steps.  The final profile (steps 15,000-20,000) is linear (R^2 > 0.99) and
    the same as that of steps 5,000-10,000 (slope within 2 %), tau / (dv/dy) =
    eta within 5 %, nothing is NaN and the kinetic energy of the salt stays
    near that of the linear profile, M V^2 / 6."""
    c = channel(V=1.0)
    assert c.reynolds < REYNOLDS_MAX
    t1, t2 = c.run.thermo(0), c.run.thermo(1)
    assert t2["Step"][-1] == 2 * NSTEPS >= 20000
    assert not re.search(r"\b(nan|inf)\b", c.run.out.lower())
    for t in (t1, t2):
        assert all(math.isfinite(v) for col in t.values() for v in col)

    p, r2 = c.fit(1)
    assert r2 > 0.99, f"Couette profile not linear: R^2 = {r2:.5f}"
    p1, _ = c.fit(1, k=0)
    assert abs(p1[0] / p[0] - 1.0) < 0.02, \
        f"shear rate {p1[0]:.5g} (steps 5,000-10,000), {p[0]:.5g} (15,000-20,000)"
    assert c.eta_eff == pytest.approx(ETA, rel=0.05), \
        f"eta_eff = {c.eta_eff:.4g} (tau {c.tau:.4g} Pa, dv/dy {c.rate:.4g} 1/s)"

    # kinetic energy: salt mass times <v^2>/2 of the linear profile
    mass = c.rhob * PACK["W"] * (PACK["H"] - 4 * RMAX)
    ke_lin = 0.5 * mass * c.V ** 2 / 3.0
    ke = t1["c_kes"] + t2["c_kes"]
    assert max(ke) < 1.5 * ke_lin, f"KE peaked at {max(ke) / ke_lin:.3g} x M V^2/6"
    assert ke[-1] == pytest.approx(ke_lin, rel=0.25)


def test_couette_wall_stress_is_steady(channel):
    """Steady flow: the wall shear stress has no trend over the deck's second
    run (steps 10,000-20,000), where the profile is steady.  The linear trend
    of the instantaneous stress (thermo, every 1,000 steps) over it must be
    < 2 % of its mean; otherwise eta_eff depends on when it is measured."""
    c = channel(V=1.0)
    t = c.run.thermo(1)
    step, tau = np.array(t["Step"]), np.array(t["v_tau"])
    slope = np.polyfit(step, tau, 1)[0]
    drift = slope * (step[-1] - step[0]) / tau.mean()
    assert abs(drift) < 0.02, \
        f"wall stress drifts by {100 * drift:+.2f} % over steps 10,000-20,000 " \
        f"({tau[0]:.4g} -> {tau[-1]:.4g} Pa) at a steady shear rate"


def test_couette_second_rate_is_newtonian(channel):
    """V 0.5 m/s as well (Re 0.02): the same tau / rate within 5 %, and the line
    through the two (rate, tau) points passes near the origin: |tau0| < 5 % of
    the stress at the lower rate (no yield stress), slope = eta within 5 %.
    Both run the same number of steps: the effective viscosity ages with run
    time (test_couette_wall_stress_is_steady), so the rates are compared at
    the same age of the salt."""
    lo, hi = channel(V=0.5), channel(V=1.0)
    assert lo.reynolds < REYNOLDS_MAX and lo.fit(1)[1] > 0.99
    assert lo.eta_eff / hi.eta_eff == pytest.approx(1.0, rel=0.05), \
        f"eta_eff {lo.eta_eff:.4g} at V 0.5, {hi.eta_eff:.4g} at V 1"
    slope = (hi.tau - lo.tau) / (hi.rate - lo.rate)
    tau0 = lo.tau - slope * lo.rate
    assert abs(tau0) < 0.05 * lo.tau, f"intercept tau0 = {tau0:.4g} Pa, tau(low) = {lo.tau:.4g}"
    assert slope == pytest.approx(ETA, rel=0.05), f"two-rate slope {slope:.4g}"


def test_couette_twice_the_viscosity(channel):
    """eta 1e9 (S 40, the same viscous stable dt and Reynolds number): the same
    eta_eff / eta as eta 5e8 within 5 %."""
    a, b = channel(V=1.0), channel(V=1.0, eta=2 * ETA, S=2 * S_PAPER)
    assert b.reynolds < REYNOLDS_MAX and b.fit(1)[1] > 0.99
    ra, rb = a.eta_eff / ETA, b.eta_eff / (2 * ETA)
    assert rb == pytest.approx(ra, rel=0.05), f"eta_eff/eta = {ra:.4f} (5e8), {rb:.4f} (1e9)"


# ---------------------------------------------------------------------------
# 2. Poiseuille
# ---------------------------------------------------------------------------

def test_poiseuille_parabola(channel):
    """Body force gx = 12 m/s^2 on the salt between two fixed walls (v_max about
    1 m/s, Re 0.04): the interior profile is a parabola (R^2 > 0.99) whose
    maximum is rho g H_eff^2 / (8 eta) within 5 %, with H_eff the distance
    between the parabola's zeros and rho the salt mass per area."""
    g = 12.0
    c = channel(gx=g)
    assert c.reynolds < REYNOLDS_MAX
    p, r2 = c.fit(2)
    assert r2 > 0.99, f"Poiseuille profile not parabolic: R^2 = {r2:.5f}"
    assert p[0] < 0
    y0, y1 = sorted(np.roots(p).real)
    heff = y1 - y0
    # the zeros lie near the band edges (no-slip at both walls)
    assert abs(y0 - 2 * RMAX) < 2 * RMAX and abs(y1 - (c.H - 2 * RMAX)) < 2 * RMAX, (y0, y1)
    vmax = p[2] - p[1] ** 2 / (4 * p[0])
    pred = c.rhob * g * heff ** 2 / (8 * ETA)
    assert vmax == pytest.approx(pred, rel=0.05), \
        f"v_max {vmax:.4g} vs rho g H^2/(8 eta) = {pred:.4g} (H_eff {heff:.1f}): " \
        f"eta_eff = {ETA * pred / vmax:.4g}"


# ---------------------------------------------------------------------------
# 3. no-slip
# ---------------------------------------------------------------------------

def test_no_slip_at_both_walls(channel):
    """Couette V 1 m/s.  Measure: the linear fit of the interior profile,
    extrapolated to the edges of the wall bands (the SPH boundary), gives the
    wall speeds - V at the top, 0 at the bottom - within 3 % of V (the effective
    no-slip plane of a rough disc band sits about 0.6 mean radii inside it: 1.4 %
    of V over this channel, with about 1 % scatter from pack to pack).  And the
    layer of salt next to the moving band (layer centres within 2 rmax of its
    edge: the discs that touch it) moves at V within 2 % (time average)."""
    c = channel(V=1.0)
    p, _ = c.fit(1)
    top, bot = np.polyval(p, c.H - 2 * RMAX), np.polyval(p, 2 * RMAX)
    assert abs(top - c.V) < 0.03 * c.V, f"salt at the moving wall: {top:.4f} m/s, wall {c.V}"
    assert abs(bot) < 0.03 * c.V, f"salt at the fixed wall: {bot:.4f} m/s"
    y, n, vx = c.profile()
    near = (y > c.H - 4 * RMAX) & (y < c.H - 2 * RMAX) & (n > 0)
    assert near.any()
    vnear = (n[near] * vx[near]).sum() / n[near].sum()
    assert abs(vnear - c.V) < 0.02 * c.V, f"salt layer touching the moving wall: {vnear:.4f} m/s"


# ---------------------------------------------------------------------------
# 4. MPI ranks and OpenMP threads
# ---------------------------------------------------------------------------

SHORT = f"include {PARAMS}\n" + CHANNEL + \
    "write_dump all custom final.dump id x y vx vy modify sort id format float %.17g\n"


@pytest.fixture(scope="module")
def short_serial(pack, tmp_path_factory):
    d = tmp_path_factory.mktemp("short")
    r = run_lmp(SHORT, d, pack=pack, V=1.0, nsteps=1000)
    check_ok(r)
    return Channel(r, PACK["H"], V=1.0), read_dump(d / "final.dump")


@pytest.mark.parametrize("mode", ["np2", "omp2"])
def test_parallel_same_eta_eff(short_serial, pack, tmp_path, mode):
    """2 x 1,000 Couette steps on 2 MPI ranks, or with -sf omp -pk omp 2: the
    same wall stress, shear rate and eta_eff as serial within 1e-6 relative,
    and the same positions within 1e-8 of the box width (only the summation
    order differs)."""
    a, da = short_serial
    kw = dict(np=2) if mode == "np2" else dict(omp=2)
    r = run_lmp(SHORT, tmp_path, pack=pack, V=1.0, nsteps=1000, **kw)
    check_ok(r)
    if mode == "np2":
        assert "2 by 1 by 1" in r.out or "1 by 2 by 1" in r.out
    else:
        assert "pair saltdem/viscous/omp" in r.out
    b = Channel(r, PACK["H"], V=1.0)
    assert b.tau == pytest.approx(a.tau, rel=1e-6)
    assert b.rate == pytest.approx(a.rate, rel=1e-6)
    assert b.eta_eff == pytest.approx(a.eta_eff, rel=1e-6)
    db = read_dump(tmp_path / "final.dump")
    assert max_diff(da, db) / PACK["W"] < 1e-8


# ---------------------------------------------------------------------------
# 5. restart
# ---------------------------------------------------------------------------

RESTART_A = f"include {PARAMS}\n" + CHANNEL.replace(
    "run             $(v_nsteps)\nrun             $(v_nsteps)\n",
    "run 400\nwrite_restart r.restart\nrun 400\n"
    "write_dump all custom final.dump id x y vx vy modify sort id format float %.17g\n")

assert "write_restart" in RESTART_A

RESTART_B = """read_restart r.restart
comm_modify vel yes
neighbor 2.8 bin
neigh_modify exclude type 3 3
neigh_modify every 1 delay 0 check yes
if "${recreate} > 0" then "pair_style saltdem/viscous" &
  "pair_coeff * * 5e8 5e9 fluid ${h} 1e8" "pair_coeff 2 2 5e8 0 fluid ${h} 1e8"
fix integ salt saltdem/nve inertia 20
fix drive top move linear 1 0 0 units box
fix 2d all enforce2d
run 400
write_dump all custom final.dump id x y vx vy modify sort id format float %.17g
"""


def test_restart_continues_identically(pack, tmp_path):
    """run 400; write_restart; run 400  ==  read_restart; run 400 (one rank,
    Couette, positions within 1e-10 of the box width).  eta, K, h come from the
    restart file, the densities and the reference densities rho0 from the
    restart data of the density fix: rho0 is not measured again, also when the
    pair style is given again after read_restart (the fix keeps the salt's
    state).  Control: a kernel h changed after read_restart measures rho0 again,
    with a warning, and changes the result."""
    ra = run_lmp(RESTART_A, tmp_path, pack=pack, V=1.0, nsteps=400)
    check_ok(ra)
    assert ra.out.count("reference density of fluid type 2") == 1
    a = read_dump(tmp_path / "final.dump")
    for recreate in (0, 1):
        rb = run_lmp(RESTART_B, tmp_path, recreate=recreate, h=28)
        check_ok(rb)
        assert "reference density of fluid type 2 = " in rb.out
        assert rb.out.count("reference density of fluid type") == rb.out.count("(from the restart file)")
        assert "WARNING" not in rb.out
        b = read_dump(tmp_path / "final.dump")
        assert len(a) == len(b) > 900
        assert max_diff(a, b) / PACK["W"] < 1e-10
        assert max_diff(a, b, cols=(2, 3)) < 1e-8

    rc = run_lmp(RESTART_B, tmp_path, recreate=1, h=28.5)
    check_ok(rc)
    assert re.search(r"reference density of fluid type 2 = [0-9.eE+-]+\n", rc.out)
    assert "WARNING: Pair style saltdem/viscous: the reference density of fluid type 2 was " \
        "measured again" in rc.out
    c = read_dump(tmp_path / "final.dump")
    assert max_diff(a, c) / PACK["W"] > 1e-8


# ---------------------------------------------------------------------------
# 6. errors and the stable time step
# ---------------------------------------------------------------------------

def err_deck(astyle="sphere", comm="comm_modify vel yes", ps="",
             pc=("1 1 5e8 1e7 fluid 28 1e8", "2 2 5e8 5e9 contact 0.5",
                 "1 2 5e8 5e9 contact 0.5 tangential 0.5"),
             fix="saltdem/nve inertia 20", dt=0.002, nrun=10):
    """10 x 10 discs (diameter 19, spacing 20), type 1 salt (fluid), the lowest
    two rows type 2 walls (contact, not integrated)."""
    setline = ("set group all diameter 19\nset group all density/disc 2200"
               if astyle == "sphere" else "mass * 1.0")
    coeffs = "\n".join(f"pair_coeff {c}" for c in pc)
    return f"""units si
dimension 2
atom_style {astyle}
boundary p f p
{comm}
region box block 0 200 0 200 -0.5 0.5
create_box 2 box
lattice sq 20
create_atoms 1 box
region low block INF INF INF 25 INF INF units box
set region low type 2
{setline}
group salt type 1
neighbor 2.8 bin
pair_style saltdem/viscous {ps}
{coeffs}
neigh_modify exclude type 2 2
fix 1 salt {fix}
fix 2 all enforce2d
timestep {dt}
thermo 5
run {nrun}
"""


def limit_in(line):
    m = re.search(r"stable limit ([0-9.eE+-]+)", line)
    assert m, line
    return float(m.group(1))


def test_good_deck_runs(lmp):
    r = lmp(err_deck())
    check_ok(r)
    assert "reference density of fluid type 1" in r.out


def test_minimize_and_run0_leave_the_density_alone(lmp):
    """The salt's continuity density is state, integrated in the integrator's stage of a run
    (fix SALTDEM_DENSITY): a minimization (force calls outside the time integration) and
    'run 0' leave the summed density of the salt as the run left it; before, the pair style
    integrated it in its force computation, and minimize changed it."""
    # discs of diameter 21 at spacing 20 overlap: the minimization has energy to lower
    deck = err_deck(nrun=0).replace("diameter 19", "diameter 21").replace("run 0\n", """velocity salt create 1 7 loop geom
run 20
compute rs all reduce sum f_SALTDEM_DENSITY
thermo_style custom step pe c_rs
thermo_modify format float %.17g
thermo 1
run 0
minimize 0 0 10 10
run 0
""")
    r = lmp(deck)
    check_ok(r)
    before, during, after = r.thermo(1), r.thermo(2), r.thermo(3)
    assert len(during["c_rs"]) > 2 and during["Step"][-1] > during["Step"][0]    # it minimized
    assert before["c_rs"][0] > 0
    assert set(during["c_rs"]) == {before["c_rs"][0]}
    assert after["c_rs"][0] == before["c_rs"][0]


PC_GOOD = ("1 1 5e8 1e7 fluid 28 1e8", "2 2 5e8 5e9 contact 0.5",
           "1 2 5e8 5e9 contact 0.5 tangential 0.5")


def pc1(c):
    return (c,) + PC_GOOD[1:]


def pc2(c):
    return (PC_GOOD[0], c, PC_GOOD[2])


@pytest.mark.parametrize("kw,words", [
    (dict(pc=pc1("1 1 5e8 1e7 fluid 28")), ["saltdem/viscous", "'fluid' takes h and K", "got 1"]),
    (dict(pc=pc1("1 1 5e8 1e7 fluid 28 1e8 3")), ["saltdem/viscous", "unexpected or incomplete '3'",
                                              "after 'fluid h K'"]),
    (dict(pc=pc1("1 1 5e8 1e7 fluid")), ["saltdem/viscous", "6 or more", "got 5"]),
    (dict(pc=pc1("1 1 5e8")), ["saltdem/viscous", "6 or more", "got 3"]),
    (dict(pc=pc2("2 2 5e8 5e9 contact 0.5 tangential")), ["saltdem/viscous", "contact 0.5",
                                                          "tangential R"]),
    (dict(pc=pc2("2 2 5e8 5e9 contact 0.5 bogus 1")), ["saltdem/viscous", "tangential R"]),
    (dict(pc=pc1("1 1 5e8 1e7 liquid 28 1e8")), ["saltdem/viscous", "unknown law 'liquid'"]),
    (dict(pc=pc1("1 1 -5e8 1e7 fluid 28 1e8")), ["saltdem/viscous", "eta", "must be > 0"]),
    (dict(pc=pc1("1 1 0 1e7 fluid 28 1e8")), ["saltdem/viscous", "eta", "must be > 0"]),
    (dict(pc=pc1("1 1 5e8 -1e7 fluid 28 1e8")), ["saltdem/viscous", "kn", "must be >= 0"]),
    (dict(pc=pc1("1 1 5e8 0 contact 0.5")), ["saltdem/viscous", "contact kn", "must be > 0"]),
    (dict(pc=pc1("1 1 5e8 1e7 fluid -28 1e8")), ["saltdem/viscous", "h = -28", "must be > 0"]),
    (dict(pc=pc1("1 1 5e8 1e7 fluid 28 -1e8")), ["saltdem/viscous", "K =", "must be >= 0"]),
    (dict(pc=pc2("2 2 5e8 5e9 contact -0.5")), ["saltdem/viscous", "gap = -0.5"]),
    (dict(pc=pc2("2 2 5e8 5e9 contact 0.5 tangential -1")), ["saltdem/viscous",
                                                             "tangential ratio = -1"]),
    (dict(pc=pc1("1 1 abc 1e7 fluid 28 1e8")), ["abc"]),
    (dict(pc=pc1("1 3 5e8 1e7 fluid 28 1e8")), ["3"]),
    (dict(pc=PC_GOOD[:2]), ["saltdem/viscous", "different laws", "pair_coeff 1 2"]),
    (dict(ps="bogus 1"), ["saltdem/viscous", "unknown keyword 'bogus'"]),
    (dict(ps="calibration"), ["saltdem/viscous", "calibration"]),
    (dict(ps="calibration 0"), ["saltdem/viscous", "calibration 0 must be > 0"]),
    (dict(ps="dtfactor 0.9"), ["saltdem/viscous", "dtfactor"]),
    (dict(ps="viscfactor 1.5"), ["saltdem/viscous", "viscfactor"]),
    (dict(astyle="atomic", fix="nve"), ["saltdem/viscous", "atom_style sphere"]),
    (dict(comm=""), ["saltdem/viscous", "comm_modify vel yes"]),
    (dict(fix="saltdem/nve inertia 0.5"), ["saltdem/nve", "inertia 0.5 must be >= 1"]),
    (dict(fix="saltdem/nve inertia"), ["saltdem/nve", "inertia"]),
    (dict(fix="saltdem/nve bogus 1"), ["saltdem/nve", "unknown keyword 'bogus'"]),
    (dict(fix="saltdem/nve check -1"), ["saltdem/nve", "check -1"]),
    (dict(astyle="atomic"), ["saltdem/nve", "atom style sphere"]),
], ids=["fluid-noK", "fluid-extra", "5args", "3args", "tangential-novalue", "contact-kw",
        "law-kw", "eta<0", "eta0", "kn<0", "contact-kn0", "h<0", "K<0", "gap<0", "ratio<0", "nonnumeric",
        "type-range", "mixed-laws", "style-kw", "calibration-novalue", "calibration0",
        "dtfactor>0.8", "viscfactor>1", "atomic", "no-ghost-vel", "inertia<1",
        "inertia-novalue", "fix-kw", "check<0", "fix-atomic"])
def test_error(lmp, kw, words):
    assert_error(lmp(err_deck(**kw)), *words)


def test_error_timestep_viscous_without_inertia(lmp):
    """The paper's dt without the inertia factor: the viscous limit
    viscfactor 0.8 x 0.175 rho h^2 / (c eta) (c the correction) = 4.6e-4 s is exceeded; the message
    names eta, the types, the limit and the way out (inertia S)."""
    # (the salt-wall contact pair 1 2 at a tenth of the viscosity, so that its own limit,
    # 0.8 x 0.625 m / (eta (1 + 3 ratio)), stays above the fluid's)
    pc = ("1 1 5e8 1e7 fluid 28 1e8", "2 2 5e8 5e9 contact 0.5",
          "1 2 5e7 5e9 contact 0.5 tangential 0.5")
    line = assert_error(lmp(err_deck(fix="saltdem/nve", pc=pc)), "saltdem/viscous",
                        "timestep 0.002", "eta = 5e+08", "types 1 1", "inertia")
    lim = limit_in(line)
    assert lim == pytest.approx(0.8 * 0.175 * 2200 * 28 ** 2 / (CORRECTION * 5e8), rel=1e-4)
    # inertia S scales the limit by S
    line = assert_error(lmp(err_deck(fix="saltdem/nve inertia 5", pc=pc, dt=0.005)),
                        "eta = 5e+08", "types 1 1", "inertia")
    assert limit_in(line) == pytest.approx(5 * lim, rel=1e-4)


def test_error_timestep_contact_and_sound(lmp):
    """The contact dashpot limit 0.8 x 0.625 S m / (eta (1 + 3 ratio)) and the sound
    limit 0.25 h / c, c^2 = K / (0.7 S rho), each named when it binds."""
    m = 2200 * math.pi * 9.5 ** 2
    line = assert_error(lmp(err_deck(pc=pc2("2 2 5e8 5e9 contact 0.5")[:2] +
                                     ("1 2 5e9 5e9 contact 0.5 tangential 2",))),
                        "saltdem/viscous", "eta = 5e+09", "types 1 2", "calibration")
    assert limit_in(line) == pytest.approx(0.5 * 20 * m / (5e9 * 7), rel=1e-4)
    line = assert_error(lmp(err_deck(pc=pc1("1 1 5e8 1e7 fluid 28 1e12"))),
                        "saltdem/viscous", "K = 1e+12", "sound")
    c = math.sqrt(1e12 / (0.7 * 20 * 2200))
    assert limit_in(line) == pytest.approx(0.25 * 28 / c, rel=1e-4)


def test_timestep_just_below_limit_runs(lmp):
    line = assert_error(lmp(err_deck(fix="saltdem/nve")), "eta")
    lim = limit_in(line)
    check_ok(lmp(err_deck(fix="saltdem/nve", dt=0.99 * lim)))


NAN_DECK = """units si
dimension 2
atom_style sphere
boundary p p p
comm_modify vel yes
region box block -50 50 -50 50 -0.5 0.5
create_box 1 box
create_atoms 1 single 0 0 0
set type 1 diameter 10
set type 1 density/disc 2200
neigh_modify every 1000000 delay 0 check no
fix 1 all saltdem/nve ${check}
fix 2 all viscous 1e15
fix 3 all enforce2d
velocity all set 1 0 0
timestep 1e-3
thermo 100000
run 1000
"""


@pytest.mark.parametrize("check,step", [("check 1", None), ("", 100)])
def test_nan_guard(lmp, check, step):
    """A drag far beyond its explicit stability limit (gamma dt / m = 6e6; no
    pair style checks it) makes the velocity overflow within a few tens of
    steps: fix saltdem/nve stops the run with its non-finite message at the
    first check (every step, or every 100 by default)."""
    r = lmp(NAN_DECK, check=check)
    line = assert_error(r, "Fix saltdem/nve", "atom 1 (type 1)", "non-finite", "timestep")
    n = int(re.search(r"at step (\d+)", line).group(1))
    if step is None:
        assert 10 < n < 100, line
    else:
        assert n == step, line
