"""Measurements of the calibration tests (examples/calibration/*.in): the peak
of a biaxial stress-strain curve, the Mohr-Coulomb fit over several
confinements with its uncertainty, the slope of a heap's surface (angle of
repose) and the effective viscosity of a plane Couette flow.

Stresses are compression-positive principal stresses in Pa: sigma1 the axial
(vertical) and sigma3 the confining (lateral) stress of a biaxial test.  The
Mohr-Coulomb envelope in principal stresses is the line

    sigma1 = N sigma3 + 2 C sqrt(N),   N = (1 + sin phi) / (1 - sin phi)

so a least-squares line sigma1 = a sigma3 + b through the peak states gives
phi = asin((a - 1) / (a + 1)) and C = b / (2 sqrt(a)).  The uncertainties are
the standard errors of the line (residual variance, n - 2 degrees of
freedom) carried to phi and C to first order:

    dphi/da = 1 / ((a + 1) sqrt(a)),
    dC/da = -b / (4 a^1.5),  dC/db = 1 / (2 sqrt(a)).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Dict, List, Optional, Sequence

import numpy as np


# ------------------------------------------------------------ biaxial curves

@dataclass
class BiaxialCurve:
    """One biaxial test: columns of the deck's biaxial_TAG.txt."""
    step: np.ndarray
    axial: np.ndarray          # axial strain (compression positive)
    volumetric: np.ndarray     # volumetric strain (compression positive; dilation negative)
    sigma1: np.ndarray         # Pa
    sigma3: np.ndarray         # Pa
    sigma3_target: float = math.nan
    header: str = ""

    @property
    def q(self) -> np.ndarray:
        return self.sigma1 - self.sigma3

    @classmethod
    def read(cls, path) -> "BiaxialCurve":
        header, rows = "", []
        with open(path, encoding="utf-8") as fh:
            for line in fh:
                s = line.split()
                if not s:
                    continue
                if s[0].startswith("#"):
                    if "sigma3_target" in line:
                        header = line.strip()
                    continue
                rows.append([float(v) for v in s[:6]])
        if len(rows) < 3:
            raise ValueError(f"{path}: fewer than 3 data lines: did the biaxial run finish?")
        a = np.array(rows)
        target = math.nan
        toks = header.replace(",", " ").split()
        if "sigma3_target" in toks:
            target = float(toks[toks.index("sigma3_target") + 1])
        return cls(a[:, 0], a[:, 1], a[:, 2], a[:, 3], a[:, 4], target, header)


def smooth(y: np.ndarray, n: int) -> np.ndarray:
    """Centred running mean over n points (n odd), shrinking at the ends."""
    y = np.asarray(y, float)
    n = max(1, int(n) | 1)
    if n == 1 or len(y) < 3:
        return y.copy()
    h = n // 2
    c = np.concatenate([[0.0], np.cumsum(y)])
    i = np.arange(len(y))
    lo, hi = np.maximum(i - h, 0), np.minimum(i + h + 1, len(y))
    return (c[hi] - c[lo]) / (hi - lo)


@dataclass
class Peak:
    """Peak state of a biaxial test (smoothed curve) and its residual state."""
    axial: float
    sigma1: float
    sigma3: float
    q: float
    volumetric: float
    residual_sigma1: float      # mean over the last `residual_fraction` of the strain
    residual_sigma3: float
    reached: bool               # the peak lies before the last 10 % of the strain

    def to_dict(self) -> dict:
        return asdict(self)


def find_peak(curve: BiaxialCurve, window: float = 0.002, residual_fraction: float = 0.2) -> Peak:
    """Peak of the deviatoric stress q = sigma1 - sigma3, after a running mean
    over `window` of axial strain (stick-slip noise of a small sample); sigma1
    and sigma3 are the smoothed values at that strain, so each peak state is
    a measured (sigma3, sigma1) pair.  The residual state is the mean over the
    last `residual_fraction` of the applied strain."""
    ea = curve.axial
    if len(ea) < 3 or ea[-1] <= ea[0]:
        raise ValueError("biaxial curve without axial strain")
    d = float(np.median(np.diff(ea)))
    n = int(round(window / d)) if d > 0 else 1
    s1, s3 = smooth(curve.sigma1, n), smooth(curve.sigma3, n)
    q = s1 - s3
    i = int(np.argmax(q))
    tail = ea >= ea[-1] - residual_fraction * (ea[-1] - ea[0])
    return Peak(axial=float(ea[i]), sigma1=float(s1[i]), sigma3=float(s3[i]), q=float(q[i]),
                volumetric=float(curve.volumetric[i]),
                residual_sigma1=float(curve.sigma1[tail].mean()),
                residual_sigma3=float(curve.sigma3[tail].mean()),
                reached=bool(ea[i] < ea[0] + 0.9 * (ea[-1] - ea[0])))


# --------------------------------------------------------------- Mohr-Coulomb

@dataclass
class MohrCoulomb:
    """Mohr-Coulomb envelope from (sigma3, sigma1) failure states."""
    phi: float                  # degrees
    cohesion: float             # Pa
    phi_err: float              # degrees, standard error (nan with 2 points)
    cohesion_err: float         # Pa, standard error
    slope: float                # N
    intercept: float            # Pa, 2 C sqrt(N)
    n: int
    rms: float                  # Pa, rms residual of sigma1
    sigma3: List[float] = field(default_factory=list)
    sigma1: List[float] = field(default_factory=list)

    @property
    def friction(self) -> float:
        """Bulk friction coefficient tan(phi)."""
        return math.tan(math.radians(self.phi))

    def sigma1_at(self, sigma3):
        return self.slope * np.asarray(sigma3, float) + self.intercept

    def to_dict(self) -> dict:
        d = asdict(self)
        d["friction"] = self.friction
        return d


def mohr_coulomb_fit(sigma3: Sequence[float], sigma1: Sequence[float]) -> MohrCoulomb:
    """Least-squares Mohr-Coulomb line through failure states (see the module
    docstring).  Needs two distinct confinements; errors need three points."""
    s3, s1 = np.asarray(sigma3, float), np.asarray(sigma1, float)
    if s3.shape != s1.shape or s3.ndim != 1:
        raise ValueError("sigma3 and sigma1 must be 1-D arrays of the same length")
    if len(s3) < 2 or np.ptp(s3) <= 0:
        raise ValueError("a Mohr-Coulomb fit needs at least two different confining stresses")
    A = np.column_stack([s3, np.ones_like(s3)])
    (a, b), *_ = np.linalg.lstsq(A, s1, rcond=None)
    if a <= 1.0:
        raise ValueError(f"fitted slope N = {a:.4g} <= 1: no positive friction angle "
                         "(peaks missing or confinements mislabelled?)")
    res = s1 - (a * s3 + b)
    n = len(s3)
    phi = math.degrees(math.asin((a - 1.0) / (a + 1.0)))
    C = b / (2.0 * math.sqrt(a))
    if n > 2:
        s2 = float(res @ res) / (n - 2)
        cov = s2 * np.linalg.inv(A.T @ A)
        J = np.array([[1.0 / ((a + 1.0) * math.sqrt(a)), 0.0],
                      [-b / (4.0 * a ** 1.5), 1.0 / (2.0 * math.sqrt(a))]])
        c = J @ cov @ J.T
        phi_err, C_err = math.degrees(math.sqrt(c[0, 0])), math.sqrt(c[1, 1])
    else:
        phi_err = C_err = math.nan
    return MohrCoulomb(phi=phi, cohesion=C, phi_err=phi_err, cohesion_err=C_err, slope=float(a),
                       intercept=float(b), n=n, rms=float(math.sqrt(np.mean(res ** 2))),
                       sigma3=[float(v) for v in s3], sigma1=[float(v) for v in s1])


def sigma1_from_mc(sigma3, phi_deg: float, cohesion: float):
    """Peak sigma1 of a Mohr-Coulomb material at confinement sigma3."""
    s = math.sin(math.radians(phi_deg))
    N = (1.0 + s) / (1.0 - s)
    return N * np.asarray(sigma3, float) + 2.0 * cohesion * math.sqrt(N)


# ------------------------------------------------------------ angle of repose

@dataclass
class Repose:
    angle: float                # degrees
    angle_err: float            # degrees, standard error of the fitted slope
    height: float               # m, heap height (top of the highest disc above the floor)
    n_points: int               # surface bins in the fit
    x: List[float] = field(default_factory=list)      # surface profile (bin centres)
    top: List[float] = field(default_factory=list)    # surface height per bin
    fit_range: List[float] = field(default_factory=list)   # x range used in the fit
    intercept: float = math.nan
    slope: float = math.nan

    def to_dict(self) -> dict:
        return asdict(self)


def surface_profile(x, y, radius, bin_width: float, floor: float = 0.0):
    """Top surface of a heap: per x bin the highest disc top (y + r) above
    `floor`; bins without discs are dropped."""
    x, y, r = (np.asarray(v, float) for v in (x, y, radius))
    lo = x.min()
    k = np.floor((x - lo) / bin_width).astype(int)
    nb = k.max() + 1
    top = np.full(nb, -np.inf)
    np.maximum.at(top, k, y + r - floor)
    xc = lo + (np.arange(nb) + 0.5) * bin_width
    ok = np.isfinite(top)
    return xc[ok], top[ok]


def repose_angle(x, y, radius, bin_width: Optional[float] = None, floor: float = 0.0,
                 lo: float = 0.2, hi: float = 0.8) -> Repose:
    """Angle of repose of a heap from its surface profile: a line fitted to
    the surface bins whose height lies between `lo` and `hi` of the heap
    height, on the side of the heap that slopes down from its highest bin
    towards larger x (the deck's heap spreads to the right); the angle is
    atan(|slope|).  Bins of the flat top and of the toe are left out by the
    height window.  A 3D heap (repose.in -var dim 3, uniform along its
    periodic z) gives the spheres' x, y: a bin's surface is then its highest
    sphere top over the whole depth."""
    r = np.asarray(radius, float)
    bw = bin_width if bin_width else 2.0 * float(np.median(r))
    xc, top = surface_profile(x, y, r, bw, floor)
    H = float(top.max())
    # the descending flank: from the last bin within `hi` of the top to the toe
    ipk = int(np.nonzero(top >= hi * H)[0].max())
    m = np.zeros(len(xc), bool)
    m[ipk:] = True
    m &= (top >= lo * H) & (top <= hi * H)
    if m.sum() < 3:
        raise ValueError(f"only {int(m.sum())} surface bins between {lo} and {hi} of the heap height "
                         f"{H:.4g} m: heap too small for bins of {bw:.4g} m")
    A = np.column_stack([xc[m], np.ones(m.sum())])
    (sl, ic), *_ = np.linalg.lstsq(A, top[m], rcond=None)
    res = top[m] - (sl * xc[m] + ic)
    n = int(m.sum())
    if n > 2:
        s2 = float(res @ res) / (n - 2)
        sl_err = math.sqrt(s2 / float(((xc[m] - xc[m].mean()) ** 2).sum()))
    else:
        sl_err = math.nan
    ang = math.degrees(math.atan(abs(sl)))
    ang_err = math.degrees(sl_err / (1.0 + sl * sl))
    return Repose(angle=ang, angle_err=ang_err, height=H, n_points=n, x=xc.tolist(), top=top.tolist(),
                  fit_range=[float(xc[m].min()), float(xc[m].max())], intercept=float(ic), slope=float(sl))


# -------------------------------------------------------------------- Couette

@dataclass
class Couette:
    V: float                    # m/s, wall velocity
    tau: float                  # Pa, wall shear stress (steady part)
    rate: float                 # 1/s, shear rate of the interior profile
    eta_eff: float              # Pa s
    r2: float                   # linearity of the interior profile
    reynolds: float             # S rho V L / eta
    tau_first: float = math.nan   # Pa, the stress of the first averaging window (steadiness)

    def to_dict(self) -> dict:
        return asdict(self)


def couette_fit(y, vx, tau: float, lo: float, hi: float):
    """Shear rate (slope of vx(y)) over lo < y < hi, R^2 and tau / rate."""
    y, vx = np.asarray(y, float), np.asarray(vx, float)
    m = (y > lo) & (y < hi)
    if m.sum() < 4:
        raise ValueError(f"only {int(m.sum())} profile layers between y = {lo:.4g} and {hi:.4g}")
    p = np.polyfit(y[m], vx[m], 1)
    res = vx[m] - np.polyval(p, y[m])
    r2 = 1.0 - float(res @ res) / float(((vx[m] - vx[m].mean()) ** 2).sum())
    return float(p[0]), r2, tau / float(p[0])


def newtonian_fit(rates: Sequence[float], taus: Sequence[float]) -> Dict[str, float]:
    """tau = eta * rate + tau0 (least squares) and the power-law index n of
    tau = k rate^n (log-log fit): a Newtonian fluid has tau0 ~ 0 and n = 1."""
    g, t = np.asarray(rates, float), np.asarray(taus, float)
    A = np.column_stack([g, np.ones_like(g)])
    (eta, tau0), *_ = np.linalg.lstsq(A, t, rcond=None)
    n, logk = np.polyfit(np.log(g), np.log(t), 1)
    return {"eta": float(eta), "tau0": float(tau0), "n": float(n), "k": float(math.exp(logk))}
