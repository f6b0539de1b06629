"""The measurements of a plane channel flow of the salt (tests/decks/channel.in:
Couette or Poiseuille flow between two bands of wall discs): the wall shear
stress, the velocity profiles and their polynomial fit, eta_eff and the
Reynolds number.  The viscosity tests and bench/validation/channel_table.py
read the same runs with it."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Dict

import numpy as np


def read_params(path) -> Dict[str, float]:
    """{name: value} of the 'variable NAME index VALUE' lines of a params file."""
    vals = {}
    for line in Path(path).read_text().splitlines():
        s = line.split("#")[0].split()
        if len(s) == 4 and s[0] == "variable" and s[2] == "index":
            vals[s[1]] = float(s[3])
    return vals


class ChannelFlow:
    """One run of the channel deck: its files in ``workdir``
    (channel_stress.txt, channel_profile.txt) and its output text (the salt's
    mass per area).  H: the channel's height; rmax: the largest disc radius
    (wall bands of 2 rmax, profile layers within 3 rmax of a band not fitted);
    rho: the disc density."""

    def __init__(self, workdir, output: str, H: float, rmax: float, rho: float, V: float = 0.0,
                 gx: float = 0.0, *, eta: float, S: float):
        self.H, self.rmax, self.rho, self.V, self.gx, self.eta, self.S = H, rmax, rho, V, gx, eta, S
        d = Path(workdir)
        lines = (d / "channel_stress.txt").read_text().splitlines()
        self.taus = [float(l.split()[1]) for l in lines if l.strip() and not l.startswith("#")]
        self.tau = self.taus[-1]            # second half of the run
        self.profiles = []
        for line in (d / "channel_profile.txt").read_text().splitlines():
            s = line.split()
            if not s or s[0].startswith("#"):
                continue
            if len(s) == 3:
                self.profiles.append([])
            else:
                self.profiles[-1].append([float(v) for v in s[1:]])
        self.profiles = [np.array(p) for p in self.profiles]
        self.rhob = float(re.search(r"salt mass per (?:area|volume): ([0-9.eE+-]+)", output).group(1))

    def profile(self, k=-1):
        y, n, vx = self.profiles[k].T
        return y, n, vx

    def interior(self, y):
        excl = 3 * self.rmax
        return (y > 2 * self.rmax + excl) & (y < self.H - 2 * self.rmax - excl)

    def fit(self, deg, k=-1):
        """Polynomial fit of the interior profile: coefficients and R^2."""
        y, n, vx = self.profile(k)
        m = self.interior(y)
        if m.sum() < 8:
            raise ValueError(f"only {m.sum()} profile layers to fit")
        p = np.polyfit(y[m], vx[m], deg)
        res = vx[m] - np.polyval(p, y[m])
        r2 = 1.0 - (res ** 2).sum() / ((vx[m] - vx[m].mean()) ** 2).sum()
        return p, r2

    @property
    def rate(self):
        return self.fit(1)[0][0]

    @property
    def eta_eff(self):
        return self.tau / self.rate

    @property
    def reynolds(self):
        vmax = self.V if self.V else np.abs(self.profile()[2]).max()
        return self.rho * self.S * vmax * (self.H - 4 * self.rmax) / self.eta
