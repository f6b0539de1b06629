"""What the measurements share: the discs matched between two frames and the
vertical columns of the salt-thickness profile."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..dump import Frame, match_ids
from ..materials import MaterialMap


def matched_discs(first: Frame, frame: Frame, materials: MaterialMap, material: str):
    """Initial and current positions (and current indices) of the discs of
    ``material`` (by their type in the first frame) present in both frames."""
    ia, ib = match_ids(first.ids, frame.ids)
    keep = materials.mask(first["type"][ia], material)
    return first.xy[ia[keep]], frame.xy[ib[keep]], ib[keep]


@dataclass
class Columns:
    """Vertical columns along x (those of the salt-thickness profile)."""

    x: np.ndarray
    width: float

    def index(self, x: np.ndarray) -> np.ndarray:
        """Column of each x; -1 outside."""
        k = np.floor((np.asarray(x) - (self.x[0] - 0.5 * self.width)) / self.width).astype(np.int64)
        return np.where((k >= 0) & (k < len(self.x)), k, -1)

    def extreme(self, x: np.ndarray, values: np.ndarray, how: str) -> np.ndarray:
        """Per column the max or min of ``values``; NaN where empty."""
        k = self.index(x)
        ok = k >= 0
        out = np.full(len(self.x), -np.inf if how == "max" else np.inf)
        (np.maximum if how == "max" else np.minimum).at(out, k[ok], np.asarray(values)[ok])
        out[~np.isfinite(out)] = np.nan
        return out

    def near(self, x: float, halfwidth: float) -> np.ndarray:
        """Columns whose centre is within ``halfwidth`` of x (at least the nearest)."""
        sel = np.abs(self.x - x) <= max(halfwidth, 0.5 * self.width)
        return sel
