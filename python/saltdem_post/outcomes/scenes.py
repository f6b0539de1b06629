"""Scene-specific outcomes: the deformed width beside a keystone graben, and
the rotation of the tilted scene's blocks and its fault spacing."""

from __future__ import annotations

from typing import List, Optional, Sequence

import numpy as np

from ..dump import Frame, match_ids
from ..materials import MaterialMap, markers
from ..strain import StrainField
from .bands import Band
from .basement import BasementTip
from .faults import fault_position
from .geometry import Columns, matched_discs
from .options import Lengths


def deformed_widths(field: StrainField, strong: np.ndarray, cols: Columns, tips: Sequence[BasementTip],
                    fraction: float, basal_m: float = 0.0, gap_m: float = np.inf) -> dict:
    """Keystone: the deformed cover (columns where at least ``fraction`` of
    the cover discs are strong in the incremental strain) left of the left
    tip and right of the right tip.  ``width_m``: the total width of such
    columns on that side.  ``extent_m``: how far from the tip the zone that
    starts at the graben reaches: its first column within twice the cover's
    thickness of the tip (a fault rising from the tip at 45° or steeper
    through salt no thicker than the cover), then deformed columns with at
    most ``gap_m`` of undeformed cover between them; a deformed column beyond
    a wider gap (the cover at a moving end wall) is not part of it.  The
    discs within ``basal_m`` of a column's lowest cover disc do not count: a
    cover that slides over the salt as a raft shears there in every column."""
    x, y = field.cur_xy[:, 0], field.cur_xy[:, 1]
    k = cols.index(x)
    ok = k >= 0
    if basal_m > 0.0 and ok.any():
        base = np.full(len(cols.x), np.inf)
        np.minimum.at(base, k[ok], y[ok])
        ok &= y > base[np.maximum(k, 0)] + basal_m
    n = np.bincount(k[ok], minlength=len(cols.x))
    n_strong = np.bincount(k[ok], strong[ok].astype(float), minlength=len(cols.x))
    deformed = (n > 0) & (n_strong >= fraction * np.maximum(n, 1))
    start = 2.0 * float(np.ptp(y)) if len(y) else 0.0
    left, right = tips[0].x, tips[-1].x
    out = {}
    for side, sel, dist in (("left", cols.x < left, left - cols.x), ("right", cols.x > right, cols.x - right)):
        hit = np.sort(dist[deformed & sel])    # outwards from the tip
        reach = None
        for dd in hit:
            if (reach is None and dd > start) or (reach is not None and dd - reach > gap_m + cols.width):
                break
            reach = dd
        out[side] = {"width_m": float(len(hit) * cols.width),
                     "extent_m": float(reach + 0.5 * cols.width) if reach is not None else 0.0}
    out["graben_width_at_base_m"] = right - left
    return out


def _layer_angle(P: np.ndarray) -> float:
    b, _ = np.polyfit(P[:, 0], P[:, 1], 1)
    return float(np.degrees(np.arctan(b)))


def block_rotations(bands: Sequence[Band], first: Frame, frame: Frame, materials: MaterialMap,
                    layer_of_first: np.ndarray, L: Lengths, min_discs: int = 5) -> List[dict]:
    """Tilted scene: rotation of each cover block between faults (ordered
    along x) from the slopes of its marker layers: per layer, the angle of a
    line through its discs in the block now minus the angle of the same discs
    in the first frame; the block's rotation is the median over layers
    (degrees, counter-clockwise positive)."""
    xy0, xy1, _ = matched_discs(first, frame, materials, "cover")
    ia, _ = match_ids(first.ids, frame.ids)
    layer = layer_of_first[ia][materials.mask(first["type"][ia], "cover")]
    mid = 0.5 * (xy1[:, 1].min() + xy1[:, 1].max())
    ordered = sorted(bands, key=lambda b: float(b.x_at(mid)))
    bounds = [None] + list(ordered) + [None]
    blocks = []
    for k in range(len(bounds) - 1):
        inside = _between(xy1, bounds[k], bounds[k + 1], L.halfwidth)
        angles = []
        for m in np.unique(layer[inside]):
            sel = inside & (layer == m)
            if sel.sum() >= min_discs and np.ptp(xy1[sel, 0]) > 4.0 * L.d:
                angles.append(_layer_angle(xy1[sel]) - _layer_angle(xy0[sel]))
        blocks.append({"block": k, "between_faults": bounds[k] is not None and bounds[k + 1] is not None,
                       "x_mid_m": float(xy1[inside, 0].mean()) if inside.any() else None,
                       "rotation_deg": float(np.median(angles)) if angles else None, "layers": len(angles)})
    return blocks


def _between(xy: np.ndarray, left: Optional[Band], right: Optional[Band], halfwidth: float) -> np.ndarray:
    ok = np.ones(len(xy), bool)
    if left is not None:
        ok &= xy[:, 0] > left.x_at(xy[:, 1]) + left.horizontal_halfwidth(halfwidth)
    if right is not None:
        ok &= xy[:, 0] < right.x_at(xy[:, 1]) - right.horizontal_halfwidth(halfwidth)
    return ok


def tilted_outcome(bands, faults, first, frame, materials, opts, L) -> dict:
    """Tilted scene: the blocks' rotation (the mean over the blocks between
    faults, else over all) and the spacing of the faults along x."""
    blocks = block_rotations(bands, first, frame, materials, markers(first, materials, opts.marker_column), L)
    inner = [b["rotation_deg"] for b in blocks if b["between_faults"] and b["rotation_deg"] is not None]
    every = [b["rotation_deg"] for b in blocks if b["rotation_deg"] is not None]
    xs = sorted(fault_position(f) for f in faults)
    spacing = np.diff(xs)
    return {"blocks": blocks,
            "mean_rotation_deg": float(np.mean(inner or every)) if (inner or every) else None,
            "rotation_of": "blocks between faults" if inner else "all blocks",
            "fault_spacing_m": spacing.tolist(),
            "mean_fault_spacing_m": float(spacing.mean()) if len(spacing) else None}
