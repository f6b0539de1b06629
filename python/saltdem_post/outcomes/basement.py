"""The basement blocks between the fault tips: their displacement, the slip
between them and the tips' current position and dip direction."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import List, Optional, Sequence

import numpy as np

from ..dump import Frame
from ..materials import MaterialMap
from ..measure import FaultDisplacement
from .geometry import matched_discs
from .options import OutcomeOptions


def _base_discs(xy0: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Wall discs at or above the base line (the most populated height): the
    bases and end walls, not the fault faces below the base."""
    bw = 2.0 * float(np.median(r))
    y = xy0[:, 1]
    edges = np.arange(y.min(), y.max() + 2 * bw, bw)
    counts, edges = np.histogram(y, edges)
    k = int(np.argmax(counts))
    return y >= edges[k] - bw


def block_displacements(first: Frame, frame: Frame, materials: MaterialMap,
                        tips: Sequence[float]) -> np.ndarray:
    """Median displacement (n_tips + 1 x 2) of the basement blocks between
    the fault tips (initial x), from the wall discs at base level; NaN for a
    block without discs."""
    xy0, xy1, ib = matched_discs(first, frame, materials, "wall")
    out = np.full((len(tips) + 1, 2), np.nan)
    if not len(xy0):
        return out
    base = _base_discs(xy0, frame.radius[ib])
    edges = [-np.inf] + sorted(tips) + [np.inf]
    for k in range(len(edges) - 1):
        sel = base & (xy0[:, 0] >= edges[k]) & (xy0[:, 0] < edges[k + 1])
        if sel.any():
            out[k] = np.median(xy1[sel] - xy0[sel], axis=0)
    return out


def block_slip(ref: Frame, cur: Frame, materials: MaterialMap, tips: Sequence[float]) -> FaultDisplacement:
    """Displacement on the first of several basement faults: the block right
    of the first tip relative to the block left of it (the keystone's slip
    down the left fault in Expt 2).  Block disc counts are not kept (-1)."""
    u = block_displacements(ref, cur, materials, tips)
    d = u[1] - u[0]
    return FaultDisplacement(cur.timestep, float(d[0]), float(d[1]), -1, -1)


@dataclass
class BasementTip:
    """A basement fault tip: where the fault plane meets the base."""

    x0: float               # initial x (--fault-x): the footwall edge
    x: float                # now: moved with its footwall block
    dip_direction: str      # towards the hanging wall
    slip: float             # relative displacement of the two blocks, m
    measured: bool          # dip direction from the blocks' motion (else the scene's default)

    def side(self, x: float) -> str:
        right = x > self.x
        return "hanging wall" if right == (self.dip_direction == "right") else "footwall"

    def to_dict(self) -> dict:
        return asdict(self)


def basement_tips(first: Frame, frame: Frame, materials: MaterialMap, opts: OutcomeOptions,
                  min_throw: float = 1e-3) -> List[BasementTip]:
    """Tips with their current position and dip direction: the hanging wall is
    the block that went down relative to the other.  Before any motion the
    default is a fault dipping right (keystone: the left fault dips right, the
    right one left)."""
    u = block_displacements(first, frame, materials, opts.fault_x)
    tips = []
    for k, x0 in enumerate(opts.fault_x):
        rel = u[k + 1] - u[k]
        measured = bool(np.isfinite(rel[1]) and abs(rel[1]) > min_throw)
        if measured:
            direction = "right" if rel[1] < 0 else "left"
        else:
            direction = "left" if (opts.scene == "keystone" and k % 2) else "right"
        footwall = u[k] if direction == "right" else u[k + 1]
        dx = float(footwall[0]) if np.isfinite(footwall[0]) else 0.0
        tips.append(BasementTip(x0, x0 + dx, direction, float(np.hypot(*rel)) if measured else 0.0, measured))
    return tips


def nearest_tip(tips: Sequence[BasementTip], x: float) -> Optional[BasementTip]:
    return min(tips, key=lambda t: abs(t.x - x)) if tips else None


def relative_to_tips(x: Optional[float], tips: Sequence[BasementTip]) -> dict:
    """Position of x relative to the nearest tip now and to its footwall edge."""
    tip = nearest_tip(tips, x) if x is not None else None
    if tip is None:
        return {"tip_x0_m": None, "rel_tip_m": None, "rel_footwall_edge_m": None, "side": None}
    return {"tip_x0_m": tip.x0, "rel_tip_m": x - tip.x, "rel_footwall_edge_m": x - tip.x0, "side": tip.side(x)}
