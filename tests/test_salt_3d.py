"""The SPH salt (pair saltdem/viscous fluid) in 3D: plane Couette flow of a random sphere pack
(tools/pack.in -var dim 3) between two bands of wall spheres, x and z periodic
(tests/decks/channel.in -var dim 3), against the analytic linear profile and tau = eta dv/dy; and
the 3D viscous stable-step rule (measured in this channel: 0.073 S rho h^2 / (correction eta),
against 0.175 for discs).  The walls carry no pressure of their own and mirror the salt's, as
in the scenes (wallK 0): bands of sphere walls with a pressure of their own, compressed by the
pack's settling, grow an instability in the first salt layer after about one diffusion time."""
import math

import numpy as np
import pytest

from lmprun import ROOT, assert_error, check_ok, run_lmp
from saltdem_post.channel import ChannelFlow

CHANNEL = (ROOT / "tests" / "decks" / "channel.in").read_text()
PACK_IN = (ROOT / "tools" / "pack.in").read_text()

# spheres of radii 10-25 m (14 across the 500 m channel), h = 1.3 sphere spacings
RMIN, RMAX, W, H, D = 10.0, 25.0, 500, 500, 200
R3 = (RMAX ** 4 - RMIN ** 4) / (4 * (RMAX - RMIN))
HS = 1.3 * (4 / 3 * math.pi * R3 / 0.62) ** (1 / 3)
ETA, S, V, RHO = 5e8, 1000, 0.01, 2200
KNW = 1e10 * (RMIN + RMAX)    # the scenes' salt-wall core, per metre of thickness x zthick
FLOW = dict(dim=3, eta=ETA, V=V, S=S, rmax=RMAX, h=round(HS, 3), K=1e9, kn=0, knw=KNW, wallK=0)


@pytest.fixture(scope="module")
def pack3(tmp_path_factory):
    d = tmp_path_factory.mktemp("pack3")
    r = run_lmp(PACK_IN, d, dim=3, W=W, H=H, D=D, rmin=RMIN, rmax=RMAX, seed=7, kn=1e9 * (RMIN + RMAX),
                out="pack3.data")
    check_ok(r)
    assert "spheres" in r.out
    return d / "pack3.data"


@pytest.fixture(scope="module")
def couette3(pack3, tmp_path_factory):
    """couette3(V) runs the 3D Couette channel once per lid speed (2 x 3000 steps of 0.1 s)."""
    cache = {}

    def get(v):
        if v not in cache:
            d = tmp_path_factory.mktemp("couette3")
            r = run_lmp(CHANNEL, d, pack=pack3, dt=0.1, nsteps=3000, **dict(FLOW, V=v))
            check_ok(r)
            cache[v] = (r, ChannelFlow(d, r.out, H, RMAX, RHO, V=v, eta=ETA, S=S))
        return cache[v]
    return get


def test_couette_3d_matches_analytic(couette3):
    """V 0.01 m/s (Re 0.02), dt 0.1 s (0.22 of the limit, the sound's), 2 x 3000 steps: the second half of the
    second run, 450-600 s, is 1.05-1.4 diffusion times H^2 rho S / eta in.  The interior profile
    is linear (R^2 > 0.999) with the rate of the first run's second half (150-300 s) within 3 %,
    tau / (dv/dy) = eta within 3 % (the style's default correction 1.047, measured on discs),
    and the salt's kinetic energy stays that of the linear profile (no growing mode)."""
    r, c = couette3(V)
    assert c.reynolds < 0.05
    p, r2 = c.fit(1)
    assert r2 > 0.999, f"Couette profile not linear: R^2 = {r2:.5f}"
    assert c.fit(1, k=0)[0][0] == pytest.approx(p[0], rel=0.03)
    assert c.eta_eff == pytest.approx(ETA, rel=0.03), f"eta_eff {c.eta_eff:.4g}"
    ke = r.thermo(1)["c_kes"]
    assert max(ke) < 1.05 * ke[0], "the salt's kinetic energy grew"


def test_couette_3d_viscosity_is_linear_in_rate(couette3):
    """Twice the lid speed: twice the stress, the same eta_eff within 2 % (a Newtonian salt)."""
    c1, c2 = couette3(V)[1], couette3(2 * V)[1]
    assert c2.reynolds < 0.05
    assert c2.tau == pytest.approx(2 * c1.tau, rel=0.03)
    assert c2.eta_eff == pytest.approx(c1.eta_eff, rel=0.02)


def test_poiseuille_3d_parabola(pack3, tmp_path):
    """Body force gx 0.012 m/s^2 on the salt between two fixed walls (v_max 6e-4 m/s, Re 0.001),
    2 x 3000 steps: the interior profile is a parabola (R^2 > 0.999) whose maximum is
    rho g H_eff^2 / (8 eta) within 3 %, rho the salt's mass per volume and H_eff the distance
    between the parabola's zeros (which lie at the band edges, within 2 rmax)."""
    g = 0.012
    r = run_lmp(CHANNEL, tmp_path, pack=pack3, dt=0.1, nsteps=3000, **dict(FLOW, V=0, gx=g))
    check_ok(r)
    c = ChannelFlow(tmp_path, r.out, H, RMAX, RHO, gx=g, eta=ETA, S=S)
    p, r2 = c.fit(2)
    assert r2 > 0.999 and p[0] < 0, f"Poiseuille profile not parabolic: R^2 = {r2:.5f}"
    y0, y1 = sorted(np.roots(p).real)
    assert abs(y0 - 2 * RMAX) < 2 * RMAX and abs(y1 - (H - 2 * RMAX)) < 2 * RMAX, (y0, y1)
    vmax = p[2] - p[1] ** 2 / (4 * p[0])
    pred = c.rhob * g * (y1 - y0) ** 2 / (8 * ETA)
    assert vmax == pytest.approx(pred, rel=0.03), f"v_max {vmax:.4g} vs {pred:.4g}"


def test_3d_viscous_limit_is_refused(pack3, tmp_path):
    """With a soft pressure (K 1e7) the viscous rule binds: 0.073 S rho h^2 / (correction eta) =
    0.635 s (h 45.5 m, S 1000), 0.51 s at viscfactor 0.8.  The channel is stable at 0.60 s and
    blows up within 300 steps at 0.68 s: 0.7 s is refused, with the 3D constant in the message."""
    flow = dict(FLOW, K=1e7, knw=1e9)
    r = run_lmp(CHANNEL, tmp_path, pack=pack3, dt=0.7, nsteps=100, **flow)
    assert_error(r, "exceeds the stable limit", "0.8 * 0.073 S rho h^2 / (correction eta), rho the sphere density")
