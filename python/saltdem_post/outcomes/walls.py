"""Rigid motion of the cover and what happens at the end walls: gaps,
collapse of the cover edge and salt rise."""

from __future__ import annotations

from typing import Dict, Tuple

import numpy as np

from ..dump import Frame, match_ids
from ..materials import MaterialMap
from .geometry import matched_discs
from .options import Lengths


def cover_thirds(first: Frame, frame: Frame, materials: MaterialMap) -> dict:
    """Mean displacement since the first frame of the cover's left, middle and
    right thirds (by initial x)."""
    xy0, xy1, _ = matched_discs(first, frame, materials, "cover")
    if not len(xy0):
        return {}
    u = xy1 - xy0
    edges = np.linspace(xy0[:, 0].min(), xy0[:, 0].max(), 4)
    k = np.clip(np.searchsorted(edges, xy0[:, 0], side="right") - 1, 0, 2)
    out = {}
    for j, name in enumerate(("left", "middle", "right")):
        sel = k == j
        out[name] = {"x0_range_m": [float(edges[j]), float(edges[j + 1])], "n": int(sel.sum()),
                     "ux_m": float(u[sel, 0].mean()) if sel.any() else None,
                     "uy_m": float(u[sel, 1].mean()) if sel.any() else None}
    return out


def wall_faces(frame: Frame, materials: MaterialMap) -> Dict[str, dict]:
    """The end walls: wall discs at the extremes of x within the cover's
    height range; their inner face x and atom ids."""
    types = frame["type"]
    cover, wall = materials.mask(types, "cover"), materials.mask(types, "wall")
    if not cover.any() or not wall.any():
        return {}
    x, y, r = frame.x, frame.y, frame.radius
    band = wall & (y >= (y - r)[cover].min()) & (y <= (y + r)[cover].max())
    if not band.any():
        return {}
    xw, rw = x[band], r[band]
    centre = 0.5 * (x[cover].min() + x[cover].max())
    faces = {}
    if xw.min() < centre:
        col = xw <= xw.min() + 2.0 * rw.max()
        faces["left"] = {"face_x_m": float((xw + rw)[col].max()), "ids": frame.ids[band][col]}
    if xw.max() > centre:
        col = xw >= xw.max() - 2.0 * rw.max()
        faces["right"] = {"face_x_m": float((xw - rw)[col].min()), "ids": frame.ids[band][col]}
    return faces


def _inward(x: np.ndarray, face: float, side: str) -> np.ndarray:
    """Distance from the wall face into the model."""
    return x - face if side == "left" else face - x


def _salt_top_at_wall(frame: Frame, materials: MaterialMap, face: float, side: str, reach: float) -> float:
    salt = materials.mask(frame["type"], "salt")
    dist = _inward(frame.x, face, side)
    sel = salt & (dist >= -reach) & (dist <= reach)
    return float((frame.y + frame.radius)[sel].max()) if sel.any() else np.nan


def _median_uy(first: Frame, frame: Frame, ids: np.ndarray) -> float:
    ia, ib = match_ids(first.ids, frame.ids)
    keep = np.isin(frame.ids[ib], ids)
    return float(np.median(frame.y[ib[keep]] - first.y[ia[keep]])) if keep.any() else 0.0


def end_wall_outcome(first: Frame, frame: Frame, materials: MaterialMap, L: Lengths) -> dict:
    """Per end wall: the cover's edge distance from it (median over height
    bins of 2 d), the subsidence of the cover edge relative to the wall, the
    salt rise at the wall (top of salt within 2 salt-disc diameters of it,
    relative to the initial salt top there), and the gap / collapse flags."""
    faces_now, faces_first = wall_faces(frame, materials), wall_faces(first, materials)
    cover = materials.mask(frame["type"], "cover")
    x, y, r = frame.x[cover], frame.y[cover], frame.radius[cover]
    ids = frame.ids[cover]
    out = {}
    for side, w in faces_now.items():
        face = w["face_x_m"]
        edge_gap = _edge_gaps(x, y, r, face, side, L.d)
        wall_dy = _median_uy(first, frame, w["ids"])
        edge_dy = _edge_uy(first, frame, ids, x, y, r, face, side, L.d)
        initial_top = (_salt_top_at_wall(first, materials, faces_first[side]["face_x_m"], side, 2.0 * L.d_salt)
                       if side in faces_first else np.nan)
        top = _salt_top_at_wall(frame, materials, face, side, 2.0 * L.d_salt)
        drop = wall_dy - edge_dy
        out[side] = {"face_x_m": face, "edge_distance_m": edge_gap[0], "max_edge_distance_m": edge_gap[1],
                     "wall_dy_m": wall_dy, "edge_drop_m": drop, "salt_top_m": top,
                     "salt_rise_m": top - initial_top, "gap": bool(edge_gap[0] > L.d),
                     "collapse": bool(drop > L.collapse_drop)}
    return out


def _edge_gaps(x, y, r, face: float, side: str, d: float) -> Tuple[float, float]:
    """Median and largest distance between the wall face and the nearest cover
    disc edge, over height bins of 2 d."""
    edge = _inward(x, face, side) - r
    k = np.floor((y - y.min()) / (2.0 * d)).astype(np.int64)
    per_bin = np.full(k.max() + 1, np.inf)
    np.minimum.at(per_bin, k, edge)
    per_bin = per_bin[np.isfinite(per_bin)]
    return float(np.median(per_bin)), float(per_bin.max())


def _edge_uy(first, frame, ids, x, y, r, face: float, side: str, d: float) -> float:
    """Vertical displacement of the cover's top corner at a wall: the discs
    within 4 d of the cover's edge and 2 d of its top there."""
    dist = _inward(x, face, side) - r
    near = dist <= dist.min() + 4.0 * d
    corner = near & (y + r >= (y + r)[near].max() - 2.0 * d)
    return _median_uy(first, frame, ids[corner])
