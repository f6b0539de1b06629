"""Measurements a geologist reads off a run: salt thickness and welds, fault
displacement, and flow profiles through the salt with a Couette + Poiseuille fit."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import List, Optional, Tuple

import numpy as np

from .dump import Frame, match_ids
from .materials import MaterialMap


def median_diameter(frame: Frame, mask: np.ndarray) -> float:
    r = frame.radius[mask] if mask.any() else frame.radius
    return 2.0 * float(np.median(r))


# ------------------------------------------------------------ salt thickness

def _runs(flags: np.ndarray) -> List[Tuple[int, int]]:
    """(first, last) index of each run of True values."""
    padded = np.concatenate([[False], flags, [False]]).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2])]


def column_union_length(bins: np.ndarray, lo: np.ndarray, hi: np.ndarray, nbins: int,
                        gap: float = 0.0) -> np.ndarray:
    """Per bin, the total length of the union of intervals ``[lo, hi]``;
    gaps shorter than ``gap`` (pores between discs) count as filled.

    Vectorised: intervals are sorted by (bin, lo) and a new merged segment
    starts wherever ``lo`` exceeds the running top of the bin by more than ``gap``.
    """
    out = np.zeros(nbins)
    if not len(lo):
        return out
    order = np.lexsort((lo, bins))
    b, lo, hi = bins[order], lo[order], hi[order]
    shift = lo.min()
    lo, hi = lo - shift, hi - shift                 # all >= 0, so bins can be stacked
    big = hi.max() + abs(gap) + 1.0
    run_top = np.maximum.accumulate(hi + b * big) - b * big
    first = np.concatenate([[True], b[1:] != b[:-1]])
    prev_top = np.concatenate([[-np.inf], run_top[:-1]])
    starts = np.flatnonzero(first | (lo > prev_top + gap))
    length = np.maximum.reduceat(hi, starts) - lo[starts]
    np.add.at(out, b[starts], length)
    return out


@dataclass
class ThicknessProfile:
    """Salt thickness in vertical columns of width ``bin_width`` along x."""

    x: np.ndarray               # column centres, m
    thickness: np.ndarray       # union of salt-disc vertical extents, m (NaN outside the model)
    base: np.ndarray            # lowest salt point in the column, m
    top: np.ndarray             # highest salt point in the column, m
    n_salt: np.ndarray          # salt discs with centre in the column
    bin_width: float
    weld_thickness: float       # columns thinner than this are welded
    timestep: int = 0

    @property
    def inside(self) -> np.ndarray:
        return np.isfinite(self.thickness)

    @property
    def welded(self) -> np.ndarray:
        return self.inside & (np.nan_to_num(self.thickness, nan=np.inf) < self.weld_thickness)

    def minimum(self) -> dict:
        if not self.inside.any():
            return {"x_m": None, "thickness_m": None}
        k = int(np.nanargmin(self.thickness))
        return {"x_m": float(self.x[k]), "thickness_m": float(self.thickness[k]),
                "welded": bool(self.welded[k])}

    def welds(self) -> List[dict]:
        """Contiguous welded stretches: where, how wide, how thin."""
        half = 0.5 * self.bin_width
        return [{"x_start_m": float(self.x[a] - half), "x_end_m": float(self.x[b] + half),
                 "width_m": float(self.x[b] - self.x[a] + self.bin_width),
                 "min_thickness_m": float(np.min(self.thickness[a:b + 1]))}
                for a, b in _runs(self.welded)]

    def table(self) -> dict:
        return {"x": self.x, "thickness": self.thickness, "base": self.base, "top": self.top,
                "n_salt": self.n_salt, "welded": self.welded.astype(int)}

    def summary(self) -> dict:
        t = self.thickness[self.inside]
        return {"timestep": int(self.timestep), "bin_width_m": self.bin_width,
                "weld_thickness_m": self.weld_thickness,
                "mean_thickness_m": float(t.mean()) if t.size else None,
                "max_thickness_m": float(t.max()) if t.size else None,
                "minimum": self.minimum(), "welds": self.welds(),
                "welded_length_m": float(self.welded.sum() * self.bin_width)}


def salt_thickness(frame: Frame, materials: Optional[MaterialMap] = None, bin_width: Optional[float] = None,
                   x_range: Optional[Tuple[float, float]] = None, gap: Optional[float] = None,
                   weld_thickness: Optional[float] = None) -> ThicknessProfile:
    """Salt thickness profile along x.

    Each salt disc covers ``[y - r, y + r]`` in the column holding its centre;
    the thickness is the length of the union of those intervals, pores
    shorter than ``gap`` filled.  Cover discs caught inside the salt (or salt
    pods within the cover) are thus not counted as salt.  Columns with cover
    but no salt have thickness 0; columns with no cover/salt at all are
    outside the model (NaN).

    Defaults: ``bin_width`` two median disc diameters (adjusted so that a
    whole number of columns spans ``x_range``, by default the extent of the
    cover and salt), ``gap`` half a salt disc diameter, ``weld_thickness`` one
    salt disc diameter.
    """
    materials = materials or MaterialMap()
    types = frame["type"]
    salt = materials.mask(types, "salt")
    model = salt | materials.mask(types, "cover")
    x, y, r = frame.x, frame.y, frame.radius
    d_salt = median_diameter(frame, salt)
    bin_width = bin_width or 2.0 * median_diameter(frame, model)
    gap = 0.5 * d_salt if gap is None else gap
    weld_thickness = d_salt if weld_thickness is None else weld_thickness
    if not model.any():
        raise ValueError(f"no cover or salt discs (types {materials}) in frame {frame.timestep}")
    if x_range is None:
        x_range = (float((x - r)[model].min()), float((x + r)[model].max()))
    x0, x1 = x_range
    # Whole number of equal columns, so the edge columns are not slivers.
    nbins = max(int(round((x1 - x0) / bin_width)), 1)
    bin_width = (x1 - x0) / nbins
    centres = x0 + (np.arange(nbins) + 0.5) * bin_width

    def column(mask):
        b = np.floor((x[mask] - x0) / bin_width).astype(np.int64)
        keep = (b >= 0) & (b < nbins)
        return b[keep], np.flatnonzero(mask)[keep]

    b_model, _ = column(model)
    b_salt, k_salt = column(salt)
    lo, hi = y[k_salt] - r[k_salt], y[k_salt] + r[k_salt]
    thickness = column_union_length(b_salt, lo, hi, nbins, gap)
    inside = np.bincount(b_model, minlength=nbins) > 0
    thickness[~inside] = np.nan
    base = np.full(nbins, np.inf)
    top = np.full(nbins, -np.inf)
    np.minimum.at(base, b_salt, lo)
    np.maximum.at(top, b_salt, hi)
    base[~np.isfinite(base)] = np.nan
    top[~np.isfinite(top)] = np.nan
    return ThicknessProfile(centres, thickness, base, top, np.bincount(b_salt, minlength=nbins),
                            float(bin_width), float(weld_thickness), frame.timestep)


# -------------------------------------------------------- fault displacement

@dataclass
class FaultDisplacement:
    """Displacement of the moving basement block relative to the static one."""

    timestep: int
    dx: float          # m, moving block minus static block
    dy: float
    n_moving: int
    n_static: int

    @property
    def slip(self) -> float:
        return float(np.hypot(self.dx, self.dy))

    @property
    def throw(self) -> float:
        return abs(self.dy)

    @property
    def heave(self) -> float:
        return abs(self.dx)

    def to_dict(self) -> dict:
        d = asdict(self)
        d.update(slip=self.slip, throw=self.throw, heave=self.heave)
        return d


def fault_displacement(ref: Frame, cur: Frame, materials: Optional[MaterialMap] = None,
                       fault_x: Optional[float] = None, threshold: float = 0.5) -> FaultDisplacement:
    """Fault displacement from the wall/basement discs between two frames.

    The basement is split into a moving and a static block: by default the
    discs that moved more than ``threshold`` times the largest wall
    displacement; with ``fault_x`` (m) the discs right/left of that x in the
    reference frame, the block that moved more being the moving one.  The
    result is the difference of the blocks' median displacements (medians
    ignore the odd loose disc).
    """
    materials = materials or MaterialMap()
    ia, ib = match_ids(ref.ids, cur.ids)
    wall = materials.mask(ref["type"][ia], "wall")
    ia, ib = ia[wall], ib[wall]
    if not len(ia):
        raise ValueError("no wall/basement discs common to both frames; check the type mapping")
    u = cur.xy[ib] - ref.xy[ia]
    mag = np.hypot(u[:, 0], u[:, 1])
    if fault_x is not None:
        right = ref.x[ia] > fault_x
        med = [np.median(mag[s]) if s.any() else -1.0 for s in (~right, right)]
        moving = right if med[1] >= med[0] else ~right
    elif mag.max() > 0:
        moving = mag > threshold * mag.max()
    else:
        moving = np.zeros(len(mag), bool)
    static_u = np.median(u[~moving], axis=0) if (~moving).any() else np.zeros(2)
    moving_u = np.median(u[moving], axis=0) if moving.any() else static_u
    d = moving_u - static_u
    return FaultDisplacement(cur.timestep, float(d[0]), float(d[1]), int(moving.sum()), int((~moving).sum()))


# ------------------------------------------------------------ flow profiles

@dataclass
class FlowFit:
    """``u(eta) = u_base + couette * eta + poiseuille * 4 eta (1 - eta)``,
    ``eta = (y - base) / (top - base)`` across the salt layer.

    ``couette`` is the velocity (or displacement) difference between the top
    and the base of the salt: the linear, shear-driven part.  ``poiseuille``
    is the extra flow at mid-layer from the parabolic, pressure-driven part;
    for a Newtonian salt of viscosity mu it equals ``-(dp/dx) h^2 / (8 mu)``.
    """

    base: float
    top: float
    u_base: float
    couette: float
    poiseuille: float
    r2: float
    rms: float
    n: int
    viscosity: Optional[float] = None

    @property
    def thickness(self) -> float:
        return self.top - self.base

    @property
    def shear_rate(self) -> float:
        """Couette shear rate (per s for velocities, strain for displacements)."""
        return self.couette / self.thickness

    @property
    def pressure_gradient(self) -> Optional[float]:
        """dp/dx (Pa/m) implied by the Poiseuille part, if the viscosity is known."""
        if self.viscosity is None:
            return None
        return -8.0 * self.viscosity * self.poiseuille / self.thickness ** 2

    def predict(self, y: np.ndarray) -> np.ndarray:
        eta = (np.asarray(y) - self.base) / self.thickness
        return self.u_base + self.couette * eta + self.poiseuille * 4.0 * eta * (1.0 - eta)

    def to_dict(self) -> dict:
        d = asdict(self)
        d.update(thickness=self.thickness, shear_rate=self.shear_rate,
                 pressure_gradient=self.pressure_gradient)
        return d


def fit_couette_poiseuille(y: np.ndarray, u: np.ndarray, base: float, top: float,
                           viscosity: Optional[float] = None) -> FlowFit:
    """Linear least-squares fit of the Couette + Poiseuille profile."""
    y, u = np.asarray(y, float), np.asarray(u, float)
    ok = np.isfinite(y) & np.isfinite(u)
    y, u = y[ok], u[ok]
    if len(y) < 3:
        raise ValueError("need at least 3 samples to fit a Couette + Poiseuille profile")
    if not top > base:
        raise ValueError("top of the salt must be above its base")
    eta = (y - base) / (top - base)
    G = np.column_stack([np.ones_like(eta), eta, 4.0 * eta * (1.0 - eta)])
    coef, *_ = np.linalg.lstsq(G, u, rcond=None)
    resid = u - G @ coef
    ss_tot = float(np.sum((u - u.mean()) ** 2))
    r2 = 1.0 - float(resid @ resid) / ss_tot if ss_tot > 0 else 1.0
    return FlowFit(float(base), float(top), float(coef[0]), float(coef[1]), float(coef[2]),
                   r2, float(np.sqrt(np.mean(resid ** 2))), int(len(y)), viscosity)


@dataclass
class VerticalProfile:
    """A quantity sampled through the salt in a window around ``x``."""

    x: float
    halfwidth: float
    quantity: str
    timestep: int
    y: np.ndarray                   # per-disc samples
    u: np.ndarray
    fit: Optional[FlowFit]
    bins: dict = field(default_factory=dict)   # binned mean/std/count vs y

    def table(self) -> dict:
        fitted = self.fit.predict(self.bins["y"]) if self.fit else np.full(len(self.bins["y"]), np.nan)
        return {**self.bins, "fit": fitted}

    def summary(self) -> dict:
        return {"x_m": self.x, "halfwidth_m": self.halfwidth, "quantity": self.quantity,
                "timestep": int(self.timestep), "n": int(len(self.y)),
                "fit": self.fit.to_dict() if self.fit else None}


def profile_values(frame: Frame, quantity: str, reference: Optional[Frame] = None) -> np.ndarray:
    """``ux``/``uy``: displacement since ``reference`` (matched by id; the
    deformed shape of an initially vertical marker line); otherwise a dump
    column such as ``vx``."""
    if quantity in ("ux", "uy") and quantity not in frame:
        if reference is None:
            raise ValueError(f"quantity {quantity} needs a reference frame")
        out = np.full(frame.natoms, np.nan)
        ia, ib = match_ids(frame.ids, reference.ids)
        axis = 0 if quantity == "ux" else 1
        out[ia] = frame.xy[ia, axis] - reference.xy[ib, axis]
        return out
    return np.asarray(frame[quantity], dtype=float)


def vertical_profile(frame: Frame, x: float, quantity: str = "vx", materials: Optional[MaterialMap] = None,
                     halfwidth: Optional[float] = None, reference: Optional[Frame] = None,
                     bin_height: Optional[float] = None, viscosity: Optional[float] = None) -> VerticalProfile:
    """Profile of ``quantity`` vs y through the salt at ``x``, with its fit.

    Samples are the salt discs whose centre lies within ``halfwidth``
    (default two median salt-disc diameters) of ``x``; the salt base and top
    are the lowest and highest salt-disc edges in that window.
    """
    materials = materials or MaterialMap()
    salt = materials.mask(frame["type"], "salt")
    d = median_diameter(frame, salt)
    halfwidth = 2.0 * d if halfwidth is None else halfwidth
    bin_height = d if bin_height is None else bin_height
    sel = salt & (np.abs(frame.x - x) <= halfwidth)
    values = profile_values(frame, quantity, reference)
    y, u, r = frame.y[sel], values[sel], frame.radius[sel]
    fit, bins = None, {"y": np.empty(0), "mean": np.empty(0), "std": np.empty(0), "count": np.empty(0)}
    if sel.sum() >= 3:
        base, top = float((y - r).min()), float((y + r).max())
        fit = fit_couette_poiseuille(y, u, base, top, viscosity)
        nb = max(int(np.ceil((top - base) / bin_height)), 1)
        k = np.clip(((y - base) / bin_height).astype(int), 0, nb - 1)
        ok = np.isfinite(u)
        count = np.bincount(k[ok], minlength=nb)
        with np.errstate(invalid="ignore", divide="ignore"):
            mean = np.bincount(k[ok], u[ok], nb) / count
            var = np.bincount(k[ok], u[ok] ** 2, nb) / count - mean ** 2
        bins = {"y": base + (np.arange(nb) + 0.5) * bin_height, "mean": mean,
                "std": np.sqrt(np.maximum(var, 0.0)), "count": count}
    return VerticalProfile(float(x), float(halfwidth), quantity, frame.timestep, y, u, fit, bins)
