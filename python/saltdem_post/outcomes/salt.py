"""Salt thickness, welds and the relief of the salt-cover interface."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from ..measure import ThicknessProfile
from .basement import BasementTip, relative_to_tips
from .geometry import Columns


def salt_outcome(profile: ThicknessProfile, tips: Sequence[BasementTip]) -> dict:
    """Thickness profile, its minimum (with its position relative to the
    tips) and the welds."""
    mn = profile.minimum()
    welds = profile.welds()
    mn.update(relative_to_tips(mn["x_m"], tips))
    t = profile.thickness[profile.inside]
    return {
        "body": salt_body(profile),
        "profile": {"x_m": profile.x, "thickness_m": profile.thickness},
        "bin_width_m": profile.bin_width, "mean_thickness_m": float(t.mean()) if t.size else None,
        "minimum": mn,
        "welds": {"weld_thickness_m": profile.weld_thickness, "count": len(welds),
                  "total_width_m": float(sum(w["width_m"] for w in welds)),
                  "x_range_m": ([welds[0]["x_start_m"], welds[-1]["x_end_m"]] if welds else None),
                  "list": welds},
    }


def salt_body(profile: ThicknessProfile) -> dict:
    """Where the salt is thickest (a pillow's crest) and how far it reaches: the first and last
    columns thicker than a weld (a pinch-out's edge)."""
    t = np.where(profile.inside, profile.thickness, np.nan)
    if not np.isfinite(t).any():
        return {"max_thickness_m": None, "x_max_m": None, "extent_m": None}
    k = int(np.nanargmax(t))
    salt = np.flatnonzero(profile.inside & ~profile.welded)
    half = 0.5 * profile.bin_width
    extent = [float(profile.x[salt[0]] - half), float(profile.x[salt[-1]] + half)] if salt.size else None
    return {"max_thickness_m": float(t[k]), "x_max_m": float(profile.x[k]), "extent_m": extent}


def interface_outcome(cols: Columns, base: np.ndarray) -> dict:
    """Relief of the salt-cover interface (the cover's base per column)."""
    ok = np.isfinite(base)
    if not ok.any():
        return {"relief_m": None, "x_low_m": None, "x_high_m": None, "profile": {"x_m": cols.x, "y_m": base}}
    lo, hi = int(np.nanargmin(base)), int(np.nanargmax(base))
    return {"relief_m": float(base[hi] - base[lo]), "x_low_m": float(cols.x[lo]), "y_low_m": float(base[lo]),
            "x_high_m": float(cols.x[hi]), "y_high_m": float(base[hi]), "profile": {"x_m": cols.x, "y_m": base}}
