"""A cover fault described: where it meets the surface and the salt, its dip,
sense, throw from the marker layers and the interface step beside it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import List, Optional, Tuple

import numpy as np

from .bands import Band
from .basement import BasementTip, nearest_tip
from .geometry import Columns
from .options import Lengths


def _level_near(cols: Columns, levels: np.ndarray, x: float, halfwidth: float) -> float:
    """Highest finite level among the columns near x (NaN if none)."""
    v = levels[cols.near(x, halfwidth)]
    v = v[np.isfinite(v)]
    return float(v.max()) if v.size else np.nan


def _side_median(cols: Columns, levels: np.ndarray, x: float, skip: float, window: float) -> Tuple[float, float]:
    """Median level of the columns in [x - skip - window, x - skip] and [x + skip, x + skip + window]."""
    out = []
    for sign in (-1.0, 1.0):
        dist = sign * (cols.x - x)
        v = levels[(dist >= skip) & (dist <= skip + window)]
        v = v[np.isfinite(v)]
        out.append(float(np.median(v)) if v.size else np.nan)
    return out[0], out[1]


def _crossing(band: Band, cols: Columns, levels: np.ndarray, d: float, upward: bool) -> Tuple[float, float]:
    """Where the band's line, followed from its centroid up (surface) or down
    (interface) in steps of d/4, first meets a level profile, the level of a
    column being the highest of it and its two neighbours: the footwall
    cutoff of a normal fault.  NaN if it leaves the columns first."""
    padded = np.concatenate([[np.nan], levels, [np.nan]])
    nearby = np.fmax(np.fmax(padded[:-2], padded[1:-1]), padded[2:])     # fmax skips NaN
    reach = 2.0 * (np.ptp(cols.x) + cols.width) + band.length
    s = np.arange(0.0, reach, 0.25 * d) * (-1.0 if upward else 1.0)
    pts = band.centroid + s[:, None] * band.direction
    k = cols.index(pts[:, 0])
    level = np.where(k >= 0, nearby[np.maximum(k, 0)], np.nan)
    with np.errstate(invalid="ignore"):
        met = pts[:, 1] >= level - 0.5 * d if upward else pts[:, 1] <= level + 0.5 * d
    hit = np.flatnonzero(met & np.isfinite(level))
    if not len(hit) or (k[:hit[0] + 1] < 0).any():
        return np.nan, np.nan
    x, y = pts[hit[0]]
    return float(x), float(y)


def _side_strip(P: np.ndarray, band: Band, sign: float, skip: float, window: float) -> np.ndarray:
    """The layer's discs in a vertical strip of width ``window`` beside the
    band (left: sign -1), clear of the band by ``skip`` over the layer's
    height range there.  Vertical strips keep x and height uncorrelated
    within the layer, so the layer's slope is not biased by the band's dip."""
    dx = P[:, 0] - band.x_at(P[:, 1])
    near = (sign * dx > skip) & (sign * dx < skip + window)
    if near.sum() < 3:
        return near
    edge = band.x_at(np.array([P[near, 1].min(), P[near, 1].max()]))
    inner = edge.min() - skip if sign < 0 else edge.max() + skip
    dist = sign * (P[:, 0] - inner)
    return (dist >= 0.0) & (dist <= window)


def _offset_at(left: np.ndarray, right: np.ndarray, x_ref: float) -> float:
    """Left minus right layer height at x_ref: one slope fitted to both
    sides, one intercept per side (the layer's mean height if the strips
    give no slope)."""
    x = np.concatenate([left[:, 0], right[:, 0]]) - x_ref
    is_left = np.concatenate([np.ones(len(left)), np.zeros(len(right))])
    G = np.column_stack([is_left, 1.0 - is_left, x])
    y = np.concatenate([left[:, 1], right[:, 1]])
    if np.ptp(left[:, 0]) < 1e-9 or np.ptp(right[:, 0]) < 1e-9:
        return float(left[:, 1].mean() - right[:, 1].mean())
    coef, *_ = np.linalg.lstsq(G, y, rcond=None)
    return float(coef[0] - coef[1])


def marker_throw(band: Band, xy: np.ndarray, layer: np.ndarray, L: Lengths) -> dict:
    """Throw from the cover marker layers: per layer crossed by the band, the
    footwall minus hanging-wall height of the layer at the band, from the
    layer's discs in vertical strips either side of it (skipping the band
    itself).  Positive for a normal offset; the median over the layers."""
    skip = band.horizontal_halfwidth(L.halfwidth)
    y_top, y_bottom = band.upper_end[1] + L.halfwidth, band.lower_end[1] - L.halfwidth
    throws = []
    for m in np.unique(layer):
        P = xy[layer == m]
        left, right = (_side_strip(P, band, s, skip, L.window) for s in (-1.0, 1.0))
        if left.sum() < 3 or right.sum() < 3:
            continue
        y_cross = 0.5 * (P[left, 1].mean() + P[right, 1].mean())
        if not y_bottom <= y_cross <= y_top:
            continue
        offset = _offset_at(P[left], P[right], float(band.x_at(y_cross)))
        throws.append(offset if band.dip_direction == "right" else -offset)
    if not throws:
        return {"throw_m": None, "throw_layers": 0, "throw_range_m": None}
    return {"throw_m": float(np.median(throws)), "throw_layers": len(throws),
            "throw_range_m": [float(min(throws)), float(max(throws))]}


@dataclass
class CoverGeometry:
    """What a fault is measured against in one frame."""

    cols: Columns
    surface: np.ndarray          # top of the cover per column
    interface: np.ndarray        # base of the cover per column
    cover_xy: np.ndarray         # current cover-disc positions
    layers: np.ndarray           # their marker layer
    tips: List[BasementTip]
    reference_direction: Optional[str]   # tilted scene: downslope; else None (nearest tip)


def describe_fault(band: Band, active: bool, finite: bool, geo: CoverGeometry, L: Lengths) -> dict:
    """Position, dip, sense, throw and reach of one cover fault."""
    up, low = band.upper_end, band.lower_end
    xs, ys = _crossing(band, geo.cols, geo.surface, L.d, upward=True)
    xi, yi = _crossing(band, geo.cols, geo.interface, L.d, upward=False)
    reaches_surface = bool(np.isfinite(ys) and up[1] >= ys - L.tip_tolerance)
    reaches_salt = bool(np.isfinite(yi) and low[1] <= yi + L.tip_tolerance)
    surface_at_tip = _level_near(geo.cols, geo.surface, float(up[0]), 0.0)
    surface_at_low = _level_near(geo.cols, geo.surface, float(low[0]), 0.0)
    reference = geo.reference_direction
    if reference is None:
        tip = nearest_tip(geo.tips, xi if np.isfinite(xi) else float(low[0]))
        reference = tip.dip_direction if tip else None
    out = {
        "x_surface_m": xs if reaches_surface else None,
        "x_interface_m": xi if reaches_salt else None,
        "reaches_surface": reaches_surface, "reaches_salt": reaches_salt,
        "x_upper_tip_m": float(up[0]), "y_upper_tip_m": float(up[1]),
        "upper_tip_depth_m": float(surface_at_tip - up[1]),
        "x_lower_tip_m": float(low[0]), "y_lower_tip_m": float(low[1]),
        "lower_tip_depth_m": float(surface_at_low - low[1]),
        "lower_tip_above_salt_m": float(low[1] - yi) if np.isfinite(yi) else None,
        "dip_deg": band.dip, "dip_direction": band.dip_direction,
        "sense": None if reference is None else ("synthetic" if band.dip_direction == reference else "antithetic"),
        "reference_direction": reference,
        "length_m": band.length, "n_discs": int(len(band.xy)), "mean_strain": float(np.mean(band.strain)),
        "active": active, "in_finite_strain": finite, "geometry_from": band.source,
    }
    out.update(marker_throw(band, geo.cover_xy, geo.layers, L))
    out["interface_step_m"] = _interface_step(band, xi, geo, L) if reaches_salt else None
    return out


def _interface_step(band: Band, x_interface: float, geo: CoverGeometry, L: Lengths) -> Optional[float]:
    """Footwall minus hanging-wall interface height beside the fault."""
    left, right = _side_median(geo.cols, geo.interface, x_interface, band.horizontal_halfwidth(L.halfwidth),
                               L.window)
    if not (np.isfinite(left) and np.isfinite(right)):
        return None
    return float(left - right if band.dip_direction == "right" else right - left)


def fault_position(f: dict) -> float:
    """A fault's x for ordering and spacing: at the surface if it gets there."""
    return f["x_surface_m"] if f["x_surface_m"] is not None else f["x_upper_tip_m"]
