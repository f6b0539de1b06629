"""The Rayleigh-Taylor benchmark of van Keken et al. (1997), isoviscous case:
the analytic linear growth rate, and the analysis of the runs of
bench/validation/rt_vankeken.in (docs/validation.md, section 4.5).

Analytic growth (Stokes flow, equal viscosities, no-slip walls at y = 0 and y = H, interface at
y = a + zeta cos(k x), k = pi / L).  Lengths in H, time in t_b = eta / (drho g H), velocities in
U_b = drho g H^2 / eta.  Displacing the interface by zeta puts light fluid where heavy was: a
line force drho g zeta cos(kx) upwards on the plane y = a.  With the stream function
psi = phi(y) sin(kx) (u = d psi/dy, v = -d psi/dx), the curl of the Stokes equations is
    (D^2 - k^2)^2 phi = -k zeta delta(y - a),    phi = phi' = 0 at y = 0 and y = 1,
so phi = -k zeta G(y; a), G the Green's function of (D^2 - k^2)^2 with clamped ends (G, G', G''
continuous at a, G''' jumps by 1; on each side G = (A + B y) cosh ky + (C + D y) sinh ky).  The
interface moves with v(a) = -k phi(a) cos(kx) = k^2 G(a; a) zeta cos(kx):
    gamma t_b = k^2 G(a; a)     (0.0109402 for a = 0.2, L = 0.9142; van Keken et al.: 0.01094019)
and the rms velocity over the box, vrms / U_b = zeta k [1/2 int_0^1 (G'^2 + k^2 G^2) dy]^(1/2).
"""

from __future__ import annotations


import math

import numpy as np

L_BOX = 0.9142           # box width / height
A_LAYER = 0.2            # light layer thickness / height
AMP = 0.02               # initial perturbation / height
# van Keken et al. (1997), isoviscous case: the analytic growth rate (their Ramberg-type
# analysis), and the best resolved peak (HS code, 81 x 81, their Table): vrms and its time
GAMMA_VK = 0.01094019
VRMS_PEAK_VK = 0.0030916
T_PEAK_VK = 208.99
PEAK_AFTER = 50.0        # t_b: the vrms peak is looked for after the start's transient


def _basis(k, y):
    """cosh, y cosh, sinh, y sinh and their first three derivatives at y (rows)"""
    c, s = math.cosh(k * y), math.sinh(k * y)
    return np.array([
        [c, y * c, s, y * s],
        [k * s, c + k * y * s, k * c, s + k * y * c],
        [k * k * c, 2 * k * s + k * k * y * c, k * k * s, 2 * k * c + k * k * y * s],
        [k ** 3 * s, 3 * k * k * c + k ** 3 * y * s, k ** 3 * c, 3 * k * k * s + k ** 3 * y * c],
    ])


def green(k, a):
    """coefficients (below a, above a) of the clamped Green's function of (D^2 - k^2)^2 on [0, 1]"""
    m = np.zeros((8, 8))
    r = np.zeros(8)
    b0, b1, ba = _basis(k, 0.0), _basis(k, 1.0), _basis(k, a)
    m[0, :4], m[1, :4] = b0[0], b0[1]
    m[2, 4:], m[3, 4:] = b1[0], b1[1]
    for i in range(4):
        m[4 + i, :4], m[4 + i, 4:] = ba[i], -ba[i]
    r[7] = -1.0     # G'''(a+) - G'''(a-) = 1
    c = np.linalg.solve(m, r)
    return c[:4], c[4:]


def growth_rate(a=A_LAYER, width=L_BOX, height=1.0):
    """analytic gamma t_b of the box [0, width] x [0, height] (lengths in H), interface at a"""
    k = math.pi / width * height                 # in units of the box height
    lo, _ = green(k, a / height)
    return k * k * (_basis(k, a / height)[0] @ lo) * height


def vrms_per_amplitude(a=A_LAYER, width=L_BOX, n=20001):
    """analytic vrms / (U_b zeta / H) of the instantaneous Stokes flow"""
    k = math.pi / width
    lo, hi = green(k, a)
    ys = np.linspace(0.0, 1.0, n)
    g = np.empty(n)
    dg = np.empty(n)
    for i, y in enumerate(ys):
        b = _basis(k, y)
        c = lo if y <= a else hi
        g[i], dg[i] = b[0] @ c, b[1] @ c
    return k * math.sqrt(0.5 * np.trapz(dg ** 2 + k * k * g ** 2, ys))


def wall_offset(gamma):
    """the offset delta (in H) of both no-slip planes into the fluid for which the analytic rate
    is gamma: a layer a - delta thick in a box 1 - 2 delta high"""
    lo, hi = 0.0, 0.09
    if growth_rate(A_LAYER - hi, L_BOX, 1 - 2 * hi) > gamma or growth_rate() < gamma:
        return float("nan")
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if growth_rate(A_LAYER - mid, L_BOX, 1 - 2 * mid) > gamma:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def read_run(path):
    """header (dict of the deck's parameters) and columns t, vrms, a_c, a_s"""
    head = {}
    with open(path) as f:
        first = f.readline().split()
    if first[:2] == ["#", "rt_vankeken"]:
        words = first[2:]
        for key, val in zip(words[::2], words[1::2]):
            try:
                head[key] = float(val)
            except ValueError:
                head[key] = val
    data = np.loadtxt(path, comments="#", ndmin=2)
    return head, data[:, 0], data[:, 1], data[:, 2], data[:, 3]


def fit_rate(t, y, t1, t2):
    """slope and intercept of ln y against t over [t1, t2]"""
    sel = (t >= t1) & (t <= t2) & (y > 0)
    if sel.sum() < 3:
        return float("nan"), float("nan")
    p = np.polyfit(t[sel], np.log(y[sel]), 1)
    return p[0], math.exp(p[1])


def peak(t, v, tmin):
    """maximum of v after tmin (a parabola through the largest sample and its neighbours), or
    None if the largest sample is the first or the last after tmin (the run stopped before the
    peak)"""
    i = int(np.argmax(np.where(t >= tmin, v, -np.inf)))
    if t[i] <= tmin or i == len(v) - 1:
        return None
    t0, t1, t2 = t[i - 1:i + 2]
    v0, v1, v2 = v[i - 1:i + 2]
    den = (v0 - 2 * v1 + v2)
    if den == 0:
        return t1, v1
    s = 0.5 * (v0 - v2) / den
    h = 0.5 * (t2 - t0)
    return t1 + s * h, v1 - 0.25 * (v0 - v2) * s


def analyse(path, t1, t2):
    head, t, vrms, ac, as_ = read_run(path)
    amp = np.hypot(ac, as_)
    g_a, a0 = fit_rate(t, amp, t1, t2)
    g_v, v0 = fit_rate(t, vrms, t1, t2)
    n = head.get("n", float("nan"))
    res = dict(path=path, n=n, Re_b=head.get("Re_b"), gamma_a=g_a, gamma_v=g_v, a0=a0,
               a_start=amp[0], vrms0=v0, delta=wall_offset(g_a), t_end=t[-1])
    pk = peak(t, vrms, PEAK_AFTER)
    if pk:
        res["t_peak"], res["vrms_peak"] = pk
        # the same run started from the benchmark's amplitude: earlier by ln(0.02 / a0) / gamma
        res["t_peak_amp"] = pk[0] - math.log(AMP / amp[0]) / g_a
    return res


def poiseuille(dump, height):
    """the no-slip planes of a Poiseuille run (-var gravity poiseuille -var dump 1): the fit of
    u = A (y - y0)(y1 - y) to the fluid's velocities; returns y0, y1 - height and A (the
    viscosity is rho_phi gx / (2 A))"""
    from scipy.optimize import curve_fit
    d = read_dump(dump)
    fluid = d["type"] < 3
    y, u = d["y"][fluid], d["vx"][fluid]
    p, _ = curve_fit(lambda yy, amp, y0, y1: amp * (yy - y0) * (y1 - yy), y, u,
                     p0=(u.max() * 4 / height ** 2, 0.0, height))
    return p[1], p[2] - height, p[0]


def read_dump(dump):
    """columns of a write_dump of the deck (id type x y vx vy density) as a dict"""
    with open(dump) as f:
        lines = f.read().splitlines()
    i = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[i].split()[2:]
    a = np.array([[float(w) for w in l.split()] for l in lines[i + 1:]])
    return {c: a[:, k] for k, c in enumerate(cols)}


def hydrostatic(dump, log, bulk_modulus, dy):
    """the pressure K (rho/rho0 - 1) of a flat-interface run (-var amp 0 -var gravity full -var
    wall half -var dump 1) by row: row centre, type, mean pressure; rho0 per type from the log"""
    import re
    rho0 = {}
    with open(log) as f:
        for line in f:
            m = re.match(r"pair saltdem/viscous: reference density of fluid type (\d+) = (\S+)",
                         line)
            if m:
                rho0[int(m.group(1))] = float(m.group(2))
    d = read_dump(dump)
    fluid = d["type"] < 3
    typ, y, rho = d["type"][fluid], d["y"][fluid], d["f_SALTDEM_DENSITY"][fluid]
    p = bulk_modulus * (rho / np.array([rho0[int(t)] for t in typ]) - 1.0)
    rows = np.floor(y / dy).astype(int)
    return [(y[rows == r].mean(), typ[rows == r].mean(), p[rows == r].mean())
            for r in np.unique(rows)]
