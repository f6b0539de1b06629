"""Salt flow character per marker band (Couette, Poiseuille, plug or static)
and per region between the basement fault tips."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import List, Optional, Sequence, Tuple

import numpy as np

from ..dump import Frame, match_ids
from ..materials import MaterialMap
from ..measure import fit_couette_poiseuille
from .basement import BasementTip
from .options import Lengths


@dataclass
class BandFlow:
    """Shape of one vertical salt marker band: its horizontal displacement
    since the first frame against height, fitted by Couette + Poiseuille."""

    marker: int
    x_m: float              # mean x now
    x0_m: float             # mean x in the first frame
    n: int
    u_base_m: float
    couette_m: float
    poiseuille_m: float
    r2: float               # Couette + Poiseuille fit
    r2_linear: float        # linear (Couette only) fit
    mean_offset_m: float
    character: str          # Couette, Poiseuille, plug or static
    direction: str          # right, left or none
    region: Optional[str] = None

    def to_dict(self) -> dict:
        return asdict(self)


def classify_flow(couette: float, poiseuille: float, mean_offset: float, flow_min: float) -> Tuple[str, str]:
    """Couette when the linear term's amplitude dominates, Poiseuille when the
    parabolic one does; below ``flow_min`` a plug (moved as a whole) or
    static.  Direction: the sign of the mean offset ("none" when static)."""
    if max(abs(couette), abs(poiseuille)) >= flow_min:
        character = "Couette" if abs(couette) >= abs(poiseuille) else "Poiseuille"
    else:
        character = "plug" if abs(mean_offset) >= flow_min else "static"
    if character == "static" or mean_offset == 0.0:
        return character, "none"
    return character, "right" if mean_offset > 0 else "left"


def _r2_linear(eta: np.ndarray, u: np.ndarray) -> float:
    ss = float(np.sum((u - u.mean()) ** 2))
    if ss == 0.0:
        return 1.0
    resid = u - np.polyval(np.polyfit(eta, u, 1), eta)
    return 1.0 - float(resid @ resid) / ss


def salt_band_flows(first: Frame, frame: Frame, materials: MaterialMap, band_of_first: np.ndarray,
                    L: Lengths, min_discs: int = 6) -> List[BandFlow]:
    """Per salt marker band: the fit of its discs' x-displacement since the
    first frame (matched by id) against height between the band's salt base
    and top (the lowest and highest edges of its discs now)."""
    ia, ib = match_ids(first.ids, frame.ids)
    salt = materials.mask(first["type"][ia], "salt")
    ia, ib = ia[salt], ib[salt]
    band = band_of_first[ia]
    flows = []
    for m in np.unique(band):
        sel = band == m
        y, r = frame.y[ib[sel]], frame.radius[ib[sel]]
        base, top = float((y - r).min()), float((y + r).max())
        if sel.sum() < min_discs or top - base < 2.0 * L.d_salt:
            continue
        u = frame.x[ib[sel]] - first.x[ia[sel]]
        fit = fit_couette_poiseuille(y, u, base, top)
        mean = float(u.mean())
        character, direction = classify_flow(fit.couette, fit.poiseuille, mean, L.flow_min)
        flows.append(BandFlow(int(m), float(frame.x[ib[sel]].mean()), float(first.x[ia[sel]].mean()),
                              int(sel.sum()), fit.u_base, fit.couette, fit.poiseuille, fit.r2,
                              _r2_linear((y - base) / (top - base), u), mean, character, direction))
    return flows


def region_names(tips: Sequence[BasementTip], scene: str) -> List[str]:
    if not tips:
        return ["all"]
    if scene == "keystone" and len(tips) == 2:
        return ["left block", "graben", "right block"]
    if len(tips) == 1:
        return ["footwall", "hanging wall"] if tips[0].dip_direction == "right" else ["hanging wall", "footwall"]
    return [f"block {k}" for k in range(len(tips) + 1)]


def flow_regions(flows: Sequence[BandFlow], tips: Sequence[BasementTip], scene: str) -> List[dict]:
    """Assign each band to a region between the tips (by its x now) and
    summarise: band counts per character, the most common character, mean
    terms and the direction of the mean offset."""
    names = region_names(tips, scene)
    edges = [t.x for t in tips]
    for f in flows:
        f.region = names[int(np.searchsorted(edges, f.x_m))]
    return [_region_summary(name, [f for f in flows if f.region == name]) for name in names]


def _region_summary(name: str, fs: Sequence[BandFlow]) -> dict:
    order = ("Couette", "Poiseuille", "plug", "static")
    counts = {c: sum(f.character == c for f in fs) for c in order}
    # the most common character (ties go to the earlier one in 'order'): a salt that mostly rides
    # as a plug with one sheared band is a plug, not a Couette flow
    dominant = max(order, key=lambda c: (counts[c], -order.index(c))) if fs else None
    mean = float(np.mean([f.mean_offset_m for f in fs])) if fs else None
    if mean is None:
        direction = None
    elif all(f.direction == "none" for f in fs):
        direction = "none"
    else:
        direction = "right" if mean > 0 else "left"
    return {"region": name, "n_bands": len(fs), "counts": counts, "character": dominant,
            "n_dominant": counts[dominant] if dominant else 0, "mean_offset_m": mean, "direction": direction,
            "mean_couette_m": float(np.mean([f.couette_m for f in fs])) if fs else None,
            "mean_poiseuille_m": float(np.mean([f.poiseuille_m for f in fs])) if fs else None}
