"""Outcomes of a scene run: the statements the reference paper makes by eye
about its Figs. 3-7, measured per frame.

For a frame, its first frame (finite strain, rigid motion, initial walls and
salt top) and the frame one increment earlier (incremental strain):

1. salt thickness profile, its minimum and where it lies relative to the
   basement fault tips and the footwall edge;
2. welds (salt thinner than one salt-disc diameter);
3. relief of the salt-cover interface and whether a cover fault offsets it;
4. cover faults: localised bands of high maximum shear strain, with their
   surface and interface positions, dip, sense, throw from the marker layers;
5. rigid-block motion of the cover thirds, gaps, collapse and salt rise at
   the end walls;
6. keystone: width of the deformed cover either side of the graben; tilted:
   rotation of the blocks between faults and the fault spacing;
7. salt flow character (Couette / Poiseuille, direction) from the salt bands.

``frame_outcomes`` returns a JSON-ready dict; ``outcomes_markdown`` turns a
list of them into tables for the docs.  Methods and thresholds:
docs/postprocessing.md, "Outcomes".
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Dict, Iterator, List, Optional, Sequence, Tuple

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from .dump import Frame, match_ids
from .materials import DEFAULT_MARKER_COLUMN, MaterialMap, markers
from .measure import FaultDisplacement, ThicknessProfile, _median_diameter, fit_couette_poiseuille, salt_thickness
from .strain import StrainField, strain_between

SCENES = ("fault", "keystone", "tilted")
DIRECTIONS = ("left", "right")
MAX_BANDS_PER_CLUSTER = 50


@dataclass
class OutcomeOptions:
    """Thresholds of the outcome measurements.  Lengths left ``None`` are
    multiples of the median cover-disc diameter d (see :class:`Lengths`)."""

    scene: str = "fault"
    fault_x: Tuple[float, ...] = ()          # m: where each basement fault meets the base, initially
    downslope: str = "right"                 # tilted scene: the reference for synthetic / antithetic
    marker_column: str = DEFAULT_MARKER_COLUMN
    # strain (cover discs only)
    radius: Optional[float] = None           # neighbour radius (default: strain.default_radius)
    method: str = "radius"
    min_neighbours: int = 3
    # cover-fault bands
    band_factor: float = 4.0                 # strong: max shear > band_factor x the cover's median ...
    band_min_strain: float = 0.02            # ... and > this
    link: Optional[float] = None             # [2 d] strong discs closer than this are connected
    band_halfwidth: Optional[float] = None   # [2 d] discs this close to a band's line belong to it
    min_length: Optional[float] = None       # [6 d] shorter bands are not faults
    min_discs: int = 8
    min_dip: float = 20.0                    # degrees: flatter bands (layer-parallel shear) are not faults
    max_flank_fraction: float = 0.5          # bands with a strained flank are distributed, not localised
    wall_margin: Optional[float] = None      # [3 d] strong discs this close to an end wall are ignored
    tip_tolerance: Optional[float] = None    # [3 d] a band ending this close to the surface reaches it
    marker_window: Optional[float] = None    # [5 d] width of the side windows (throw, interface step)
    ransac_trials: int = 300
    seed: int = 0
    # salt
    bin_width: Optional[float] = None        # thickness columns (default: salt_thickness's)
    weld_thickness: Optional[float] = None
    gap: Optional[float] = None
    flow_min: Optional[float] = None         # [one salt-disc diameter] smaller offsets are no flow
    # walls and scene-specific
    collapse_drop: Optional[float] = None    # [2 d] edge subsidence (relative to the wall) that is a collapse
    deformed_fraction: float = 0.1           # keystone: a column is deformed when this fraction is strong

    def __post_init__(self):
        if self.scene not in SCENES:
            raise ValueError(f"scene must be one of {', '.join(SCENES)}, not {self.scene!r}")
        if self.downslope not in DIRECTIONS:
            raise ValueError(f"downslope must be left or right, not {self.downslope!r}")
        self.fault_x = tuple(sorted(float(x) for x in (self.fault_x or ())))
        if self.scene == "keystone" and len(self.fault_x) != 2:
            raise ValueError("a keystone scene needs the two fault tips: --fault-x X1 X2")


@dataclass
class Lengths:
    """The options' lengths in metres for one frame."""

    d: float                 # median cover-disc diameter
    d_salt: float            # median salt-disc diameter
    link: float
    halfwidth: float
    min_length: float
    wall_margin: float
    tip_tolerance: float
    window: float
    flow_min: float
    collapse_drop: float

    @classmethod
    def resolve(cls, opts: OutcomeOptions, frame: Frame, materials: MaterialMap) -> "Lengths":
        types = frame["type"]
        d = _median_diameter(frame, materials.mask(types, "cover"))
        d_salt = _median_diameter(frame, materials.mask(types, "salt"))

        def pick(value, multiple, unit=d):
            return float(value) if value is not None else multiple * unit
        return cls(d, d_salt, pick(opts.link, 2.0), pick(opts.band_halfwidth, 2.0), pick(opts.min_length, 6.0),
                   pick(opts.wall_margin, 3.0), pick(opts.tip_tolerance, 3.0), pick(opts.marker_window, 5.0),
                   pick(opts.flow_min, 1.0, d_salt), pick(opts.collapse_drop, 2.0))


def _matched(first: Frame, frame: Frame, materials: MaterialMap, material: str):
    """Initial and current positions (and current indices) of the discs of
    ``material`` (by their type in the first frame) present in both frames."""
    ia, ib = match_ids(first.ids, frame.ids)
    keep = materials.mask(first["type"][ia], material)
    return first.xy[ia[keep]], frame.xy[ib[keep]], ib[keep]


# ---------------------------------------------------------------- columns

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


# ------------------------------------------------------------- basement

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
    xy0, xy1, ib = _matched(first, frame, materials, "wall")
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


def _nearest_tip(tips: Sequence[BasementTip], x: float) -> Optional[BasementTip]:
    return min(tips, key=lambda t: abs(t.x - x)) if tips else None


def relative_to_tips(x: Optional[float], tips: Sequence[BasementTip]) -> dict:
    """Position of x relative to the nearest tip now and to its footwall edge."""
    tip = _nearest_tip(tips, x) if x is not None else None
    if tip is None:
        return {"tip_x0_m": None, "rel_tip_m": None, "rel_footwall_edge_m": None, "side": None}
    return {"tip_x0_m": tip.x0, "rel_tip_m": x - tip.x, "rel_footwall_edge_m": x - tip.x0, "side": tip.side(x)}


# -------------------------------------------------------- salt, interface

def salt_outcome(profile: ThicknessProfile, tips: Sequence[BasementTip]) -> dict:
    """Thickness profile, its minimum (with its position relative to the
    tips) and the welds."""
    mn = profile.minimum()
    welds = profile.welds()
    mn.update(relative_to_tips(mn["x_m"], tips))
    t = profile.thickness[profile.inside]
    return {
        "profile": {"x_m": profile.x, "thickness_m": profile.thickness},
        "bin_width_m": profile.bin_width, "mean_thickness_m": float(t.mean()) if t.size else None,
        "minimum": mn,
        "welds": {"weld_thickness_m": profile.weld_thickness, "count": len(welds),
                  "total_width_m": float(sum(w["width_m"] for w in welds)),
                  "x_range_m": ([welds[0]["x_start_m"], welds[-1]["x_end_m"]] if welds else None),
                  "list": welds},
    }


def interface_outcome(cols: Columns, base: np.ndarray) -> dict:
    """Relief of the salt-cover interface (the cover's base per column)."""
    ok = np.isfinite(base)
    if not ok.any():
        return {"relief_m": None, "x_low_m": None, "x_high_m": None, "profile": {"x_m": cols.x, "y_m": base}}
    lo, hi = int(np.nanargmin(base)), int(np.nanargmax(base))
    return {"relief_m": float(base[hi] - base[lo]), "x_low_m": float(cols.x[lo]), "y_low_m": float(base[lo]),
            "x_high_m": float(cols.x[hi]), "y_high_m": float(base[hi]), "profile": {"x_m": cols.x, "y_m": base}}


# ------------------------------------------------------------ band lines

def fit_line(xy: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Centroid and unit direction (principal axis, pointing down) of points."""
    c = xy.mean(axis=0)
    w, v = np.linalg.eigh(np.cov((xy - c).T) if len(xy) > 1 else np.eye(2))
    t = v[:, int(np.argmax(w))]
    if t[1] > 0 or (t[1] == 0 and t[0] < 0):
        t = -t
    return c, t


def fit_band_line(xy: np.ndarray, trim: float = 0.15) -> Tuple[np.ndarray, np.ndarray]:
    """The line of a band: PCA of its discs, refitted on the central
    ``1 - 2 trim`` of its length.  The band's footwall and hanging-wall
    halves are offset along it by the slip (strain is drawn at current
    positions), which tilts a plain fit toward the diagonal; the unpaired
    ends are what the trim drops."""
    c, t = fit_line(xy)
    s = (xy - c) @ t
    lo, hi = np.quantile(s, [trim, 1.0 - trim])
    core = (s >= lo) & (s <= hi)
    return fit_line(xy[core]) if core.sum() >= 3 else (c, t)


def _normal(t: np.ndarray) -> np.ndarray:
    return np.array([-t[1], t[0]])


def _longest_run(s: np.ndarray, gap: float) -> np.ndarray:
    """Indices of the largest group of values whose sorted neighbours are at
    most ``gap`` apart."""
    order = np.argsort(s)
    breaks = np.flatnonzero(np.diff(s[order]) > gap) + 1
    groups = np.split(order, breaks)
    return max(groups, key=len)


def _line_members(P: np.ndarray, c: np.ndarray, t: np.ndarray, halfwidth: float, gap: float) -> np.ndarray:
    """Points within ``halfwidth`` of the line, in its largest contiguous run."""
    inside = np.flatnonzero(np.abs((P - c) @ _normal(t)) < halfwidth)
    if not len(inside):
        return inside
    return inside[_longest_run((P[inside] - c) @ t, gap)]


def _best_line(P: np.ndarray, L: Lengths, opts: OutcomeOptions, rng) -> Optional[np.ndarray]:
    """RANSAC: the line through two points with the largest contiguous run of
    points within the band half-width, refined by PCA of its members."""
    n = len(P)
    i, j = rng.integers(0, n, opts.ransac_trials), rng.integers(0, n, opts.ransac_trials)
    best = None
    for a, b in zip(i, j):
        d = P[b] - P[a]
        length = float(np.hypot(*d))
        if length < 2.0 * L.halfwidth:
            continue
        members = _line_members(P, P[a], d / length, L.halfwidth, L.link)
        if best is None or len(members) > len(best):
            best = members
    if best is None or len(best) < 2:
        return None
    for _ in range(3):                              # PCA refinement
        c, t = fit_line(P[best])
        refined = _line_members(P, c, t, L.halfwidth, L.link)
        if len(refined) < 2 or np.array_equal(np.sort(refined), np.sort(best)):
            break
        best = refined
    return best


def _strip(P: np.ndarray, c: np.ndarray, t: np.ndarray, s_range: Tuple[float, float],
           dist_range: Tuple[float, float]) -> np.ndarray:
    """Points along [s_range] of the line at a distance in [dist_range)."""
    s, dist = (P - c) @ t, np.abs((P - c) @ _normal(t))
    return (s >= s_range[0]) & (s <= s_range[1]) & (dist >= dist_range[0]) & (dist < dist_range[1])


def extract_lines(P: np.ndarray, L: Lengths, opts: OutcomeOptions, rng,
                  accept=lambda members: True) -> Iterator[np.ndarray]:
    """Member indices of the accepted straight bands in one cluster of strong
    discs, best supported first.  The discs near an accepted band (within
    twice the half-width) are removed before the next is sought, so a wide
    band gives one line and crossing (conjugate) bands give one line each; a
    rejected line (``accept`` false) gives up its own members only."""
    remaining = np.arange(len(P))
    for _ in range(MAX_BANDS_PER_CLUSTER):
        if len(remaining) < opts.min_discs:
            return
        Q = P[remaining]
        members = _best_line(Q, L, opts, rng)
        if members is None or len(members) < opts.min_discs:
            return
        c, t = fit_line(Q[members])
        s = (Q[members] - c) @ t
        if np.ptp(s) < L.min_length:
            return
        drop = np.zeros(len(Q), bool)
        if accept(remaining[members]):
            yield remaining[members]
            drop = _strip(Q, c, t, (s.min() - L.halfwidth, s.max() + L.halfwidth), (0.0, 2.0 * L.halfwidth))
        drop[members] = True
        remaining = remaining[~drop]


@dataclass
class Band:
    """A localised band of strong discs fitted by a straight line."""

    xy: np.ndarray             # current positions of its discs
    strain: np.ndarray         # their max shear
    centroid: np.ndarray
    direction: np.ndarray      # unit vector along the band, pointing down
    s_min: float               # extent along the direction from the centroid
    s_max: float
    source: str                # "incremental" or "finite"

    @classmethod
    def from_points(cls, xy: np.ndarray, strain: np.ndarray, source: str) -> "Band":
        c, t = fit_band_line(xy)
        s = (xy - c) @ t
        return cls(xy, strain, c, t, float(s.min()), float(s.max()), source)

    @property
    def dip(self) -> float:
        return float(np.degrees(np.arctan2(abs(self.direction[1]), abs(self.direction[0]))))

    @property
    def dip_direction(self) -> str:
        return "right" if self.direction[0] > 0 else "left"

    @property
    def length(self) -> float:
        return self.s_max - self.s_min

    @property
    def upper_end(self) -> np.ndarray:
        return self.centroid + self.s_min * self.direction     # direction points down

    @property
    def lower_end(self) -> np.ndarray:
        return self.centroid + self.s_max * self.direction

    def x_at(self, y):
        """x of the band's line at height y."""
        c, t = self.centroid, self.direction
        return c[0] + (np.asarray(y) - c[1]) * t[0] / t[1]

    def horizontal_halfwidth(self, halfwidth: float) -> float:
        return halfwidth / max(abs(self.direction[1]), 0.1)

    def distance(self, xy: np.ndarray) -> np.ndarray:
        return np.abs((xy - self.centroid) @ _normal(self.direction))


# --------------------------------------------------------- band detection

def strong_discs(values: np.ndarray, factor: float, floor: float) -> Tuple[np.ndarray, float, float]:
    """Discs whose max shear exceeds max(factor x median, floor)."""
    v = np.nan_to_num(values, nan=0.0)
    med = float(np.nanmedian(values)) if np.isfinite(values).any() else 0.0
    threshold = max(factor * med, floor)
    return v > threshold, threshold, med


def connected_clusters(xy: np.ndarray, link: float, min_size: int) -> List[np.ndarray]:
    """Groups of points connected by steps shorter than ``link`` (single
    linkage, i.e. DBSCAN with min_samples 1), at least ``min_size`` strong."""
    if len(xy) < min_size:
        return []
    pairs = cKDTree(xy).query_pairs(link, output_type="ndarray")
    n = len(xy)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    groups = np.split(np.argsort(labels, kind="stable"), np.cumsum(np.bincount(labels))[:-1])
    return [g for g in groups if len(g) >= min_size]


def _flank_fraction(band: Band, xy: np.ndarray, strong: np.ndarray, L: Lengths) -> float:
    """Fraction of strong discs in the more strained of the two strips beside
    the band (2 to 4 half-widths from its line): high inside, or along the
    edge of, a zone of distributed deformation."""
    flank = _strip(xy, band.centroid, band.direction, (band.s_min, band.s_max),
                   (2.0 * L.halfwidth, 4.0 * L.halfwidth))
    side = (xy - band.centroid) @ _normal(band.direction) > 0
    fractions = [strong[flank & s].mean() for s in (side, ~side) if (flank & s).any()]
    return float(max(fractions)) if fractions else 0.0


def _near_walls(x: np.ndarray, walls: dict, margin: float) -> np.ndarray:
    near = np.zeros(len(x), bool)
    for side, w in walls.items():
        face = w["face_x_m"]
        near |= (x < face + margin) if side == "left" else (x > face - margin)
    return near


def detect_bands(field: StrainField, source: str, L: Lengths, opts: OutcomeOptions,
                 walls: Optional[dict] = None) -> Tuple[List[Band], dict]:
    """Localised straight bands of high max shear strain in a (cover-only) field."""
    values = field.max_shear
    strong, threshold, median = strong_discs(values, opts.band_factor, opts.band_min_strain)
    xy = field.cur_xy
    if walls:
        strong &= ~_near_walls(xy[:, 0], walls, L.wall_margin)
    idx = np.flatnonzero(strong)
    stats = {"source": source, "median_strain": median, "threshold": threshold, "n_strong": int(len(idx)),
             "rejected": {"flat": 0, "distributed": 0}}
    rng = np.random.default_rng(opts.seed)
    bands = []
    for cluster in connected_clusters(xy[idx], L.link, opts.min_discs):
        P, strain = xy[idx[cluster]], values[idx[cluster]]

        def accept(members):
            # members again from the whole cluster: discs a rejected line took back
            c, t = fit_band_line(P[members])
            members = np.union1d(members, _line_members(P, c, t, L.halfwidth, L.link))
            band = Band.from_points(P[members], strain[members], source)
            reason = _rejection(band, xy, strong, L, opts)
            if reason:
                stats["rejected"][reason] += 1
            else:
                bands.append(band)
            return reason is None
        for _ in extract_lines(P, L, opts, rng, accept):
            pass
    stats["n_bands"] = len(bands)
    return bands, stats


def _rejection(band: Band, xy: np.ndarray, strong: np.ndarray, L: Lengths, opts: OutcomeOptions) -> Optional[str]:
    """Why a straight band is not a fault: too flat, or not localised."""
    if band.dip < opts.min_dip:
        return "flat"
    if _flank_fraction(band, xy, strong, L) > opts.max_flank_fraction:
        return "distributed"
    return None


def same_fault(a: Band, b: Band, L: Lengths, max_angle: float = 15.0) -> bool:
    """Nearly parallel, within two half-widths of each other's line and
    overlapping along it."""
    cosang = abs(float(a.direction @ b.direction))
    if np.degrees(np.arccos(min(cosang, 1.0))) > max_angle:
        return False
    if min(b.distance(a.centroid[None])[0], a.distance(b.centroid[None])[0]) > 2.0 * L.halfwidth:
        return False
    ends = (np.array([a.upper_end, a.lower_end]) - b.centroid) @ b.direction
    return ends.max() >= b.s_min - L.halfwidth and ends.min() <= b.s_max + L.halfwidth


def merge_bands(incremental: Sequence[Band], finite: Sequence[Band], L: Lengths) -> List[Tuple[Band, bool, bool]]:
    """(band, active, in_finite) per fault: a finite band is active when an
    incremental band matches it (the longer of the two gives the geometry);
    unmatched incremental bands are new, active faults."""
    used, faults = set(), []
    for fb in finite:
        match = [k for k, ib in enumerate(incremental) if k not in used and same_fault(ib, fb, L)]
        used.update(match)
        best = max([fb] + [incremental[k] for k in match], key=lambda b: b.length)
        faults.append((best, bool(match), True))
    faults += [(ib, True, False) for k, ib in enumerate(incremental) if k not in used]
    return faults


# ------------------------------------------------------- fault description

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
        tip = _nearest_tip(geo.tips, xi if np.isfinite(xi) else float(low[0]))
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


def _fault_x(f: dict) -> float:
    """A fault's x for ordering and spacing: at the surface if it gets there."""
    return f["x_surface_m"] if f["x_surface_m"] is not None else f["x_upper_tip_m"]


# ----------------------------------------------------------- rigid cover

def cover_thirds(first: Frame, frame: Frame, materials: MaterialMap) -> dict:
    """Mean displacement since the first frame of the cover's left, middle and
    right thirds (by initial x)."""
    xy0, xy1, _ = _matched(first, frame, materials, "cover")
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


# ------------------------------------------------------ scene-specific

def deformed_widths(field: StrainField, strong: np.ndarray, cols: Columns, tips: Sequence[BasementTip],
                    fraction: float) -> dict:
    """Keystone: width of the deformed cover (columns where at least
    ``fraction`` of the cover discs are strong in the incremental strain)
    left of the left tip and right of the right tip."""
    k = cols.index(field.cur_xy[:, 0])
    ok = k >= 0
    n = np.bincount(k[ok], minlength=len(cols.x))
    n_strong = np.bincount(k[ok], strong[ok].astype(float), minlength=len(cols.x))
    deformed = (n > 0) & (n_strong >= fraction * np.maximum(n, 1))
    left, right = tips[0].x, tips[-1].x
    out = {}
    for side, sel, dist in (("left", cols.x < left, left - cols.x), ("right", cols.x > right, cols.x - right)):
        hit = deformed & sel
        out[side] = {"width_m": float(hit.sum() * cols.width),
                     "extent_m": float(dist[hit].max() + 0.5 * cols.width) if hit.any() else 0.0}
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
    xy0, xy1, _ = _matched(first, frame, materials, "cover")
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


# ------------------------------------------------------------- salt flow

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


# ------------------------------------------------------------ one frame

def cover_strain(ref: Frame, cur: Frame, materials: MaterialMap, opts: OutcomeOptions) -> StrainField:
    """Strain of the cover discs from cover neighbours only, so that the
    salt's shear does not leak into the base of the cover."""
    return strain_between(ref.subset(materials.mask(ref["type"], "cover")),
                          cur.subset(materials.mask(cur["type"], "cover")),
                          opts.radius, opts.method, opts.min_neighbours)


def frame_outcomes(frame: Frame, first: Frame, previous: Optional[Frame], materials: MaterialMap,
                   opts: OutcomeOptions, displacement: Optional[float] = None,
                   previous_displacement: Optional[float] = None) -> dict:
    """All outcomes of one frame (see the module docstring)."""
    types = frame["type"]
    if not materials.mask(types, "cover").any():
        raise ValueError(f"no cover discs (types {materials}) in frame {frame.index}")
    L = Lengths.resolve(opts, frame, materials)
    tips = basement_tips(first, frame, materials, opts) if opts.fault_x else []
    profile = salt_thickness(frame, materials, opts.bin_width, None, opts.gap, opts.weld_thickness)
    cols = Columns(profile.x, profile.bin_width)
    cover = materials.mask(types, "cover")
    cx, cy, cr = frame.x[cover], frame.y[cover], frame.radius[cover]
    layers = markers(frame, materials, opts.marker_column, reference=first)
    geo = CoverGeometry(cols, cols.extreme(cx, cy + cr, "max"), cols.extreme(cx, cy - cr, "min"),
                        np.column_stack([cx, cy]), layers[cover], tips,
                        opts.downslope if opts.scene == "tilted" else None)
    walls = wall_faces(frame, materials)

    fields = {"finite": cover_strain(first, frame, materials, opts)}
    if previous is not None:
        fields["incremental"] = cover_strain(previous, frame, materials, opts)
    detected = {name: detect_bands(f, name, L, opts, walls) for name, f in fields.items()}
    merged = merge_bands(detected.get("incremental", ([], {}))[0], detected["finite"][0], L)
    faults = [describe_fault(b, active, fin, geo, L) for b, active, fin in merged]
    order = np.argsort([_fault_x(f) for f in faults], kind="stable")
    faults = [dict(faults[k], id=f"F{j + 1}") for j, k in enumerate(order)]
    bands = [merged[k][0] for k in order]

    interface = interface_outcome(cols, geo.interface)
    offsets = [f for f in faults if f["interface_step_m"] is not None and abs(f["interface_step_m"]) > 0.5 * L.d]
    interface.update(offset_by_fault=bool(offsets), offsetting_faults=[f["id"] for f in offsets])

    result = {
        "frame": frame.index, "timestep": frame.timestep, "time": frame.time,
        "displacement_m": displacement, "previous_frame": previous.index if previous is not None else None,
        "previous_displacement_m": previous_displacement,
        "lengths_m": asdict(L), "tips": [t.to_dict() for t in tips],
        "salt": salt_outcome(profile, tips), "interface": interface,
        "faults": {"count": len(faults), "active": sum(f["active"] for f in faults),
                   "synthetic": sum(f["sense"] == "synthetic" for f in faults),
                   "antithetic": sum(f["sense"] == "antithetic" for f in faults),
                   "detection": {name: d[1] for name, d in detected.items()}, "list": faults},
        "cover_motion": cover_thirds(first, frame, materials),
        "end_walls": end_wall_outcome(first, frame, materials, L),
    }
    flows = salt_band_flows(first, frame, materials, markers(first, materials, opts.marker_column), L)
    result["salt_flow"] = {"regions": flow_regions(flows, tips, opts.scene), "bands": [f.to_dict() for f in flows]}
    if opts.scene == "keystone":
        inc = detected.get("incremental")
        result["keystone"] = (deformed_widths(fields["incremental"], _strong_of(fields["incremental"], inc[1]),
                                              cols, tips, opts.deformed_fraction) if inc else None)
    if opts.scene == "tilted":
        result["tilted"] = _tilted_outcome(bands, faults, first, frame, materials, opts, L)
    return result


def _strong_of(field: StrainField, stats: dict) -> np.ndarray:
    return np.nan_to_num(field.max_shear, nan=0.0) > stats["threshold"]


def _tilted_outcome(bands, faults, first, frame, materials, opts, L) -> dict:
    blocks = block_rotations(bands, first, frame, materials, markers(first, materials, opts.marker_column), L)
    inner = [b["rotation_deg"] for b in blocks if b["between_faults"] and b["rotation_deg"] is not None]
    every = [b["rotation_deg"] for b in blocks if b["rotation_deg"] is not None]
    xs = sorted(_fault_x(f) for f in faults)
    spacing = np.diff(xs)
    return {"blocks": blocks,
            "mean_rotation_deg": float(np.mean(inner or every)) if (inner or every) else None,
            "rotation_of": "blocks between faults" if inner else "all blocks",
            "fault_spacing_m": spacing.tolist(),
            "mean_fault_spacing_m": float(spacing.mean()) if len(spacing) else None}


# -------------------------------------------------------------- markdown

def _km(x) -> str:
    return "–" if x is None else f"{x / 1000:.2f} km"


def _m(v, signed: bool = False) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "–"
    return f"{v:+.0f} m" if signed else f"{v:.0f} m"


def _stage_label(r: dict) -> str:
    d = r.get("displacement_m")
    return f"{d:.0f} m" if d is not None and np.isfinite(d) else f"step {r['timestep']}"


def _weld_text(w: dict) -> str:
    if not w["count"]:
        return "none"
    a, b = w["x_range_m"]
    return f"{w['count']}: {_m(w['total_width_m'])} in {a / 1000:.2f}–{b / 1000:.2f} km"


def _minimum_text(mn: dict) -> str:
    if mn["x_m"] is None:
        return "–"
    return f"{_m(mn['thickness_m'])} at {_km(mn['x_m'])}"


def _relative_text(mn: dict) -> str:
    if mn.get("rel_tip_m") is None:
        return "–"
    return f"{_m(mn['rel_tip_m'], True)} / {_m(mn['rel_footwall_edge_m'], True)} ({mn['side']})"


def _interface_text(i: dict) -> str:
    if i["relief_m"] is None:
        return "–"
    return f"{_m(i['relief_m'])} (low {_km(i['x_low_m'])}, high {_km(i['x_high_m'])})"


def _faults_text(f: dict) -> str:
    if not f["count"]:
        return "none"
    return (f"{f['count']} ({f['active']} active; {f['synthetic']} synthetic, "
            f"{f['antithetic']} antithetic)")


def _thirds_text(c: dict) -> str:
    if not c:
        return "–"
    return " / ".join(_m(c[k]["ux_m"], True) for k in ("left", "middle", "right"))


def _wall_text(w: Optional[dict]) -> str:
    if not w:
        return "–"
    flags = [name for name in ("gap", "collapse") if w[name]]
    return (f"edge {_m(w['edge_distance_m'])}, salt rise {_m(w['salt_rise_m'], True)}, "
            f"edge drop {_m(w['edge_drop_m'], True)}" + (f" ({', '.join(flags)})" if flags else ""))


def _flow_text(reg: dict) -> str:
    if not reg["n_bands"]:
        return "–"
    return f"{reg['character']}, {reg['direction']} ({reg['n_dominant']} of {reg['n_bands']} bands)"


def _summary_rows(results: Sequence[dict]) -> List[Tuple[str, List[str]]]:
    rows = [
        ("frame (step)", [f"{r['frame']} ({r['timestep']})" for r in results]),
        ("min. salt thickness", [_minimum_text(r["salt"]["minimum"]) for r in results]),
        ("min. vs fault tip / footwall edge", [_relative_text(r["salt"]["minimum"]) for r in results]),
        ("welds (< 1 salt disc)", [_weld_text(r["salt"]["welds"]) for r in results]),
        ("salt-cover interface relief", [_interface_text(r["interface"]) for r in results]),
        ("interface offset by a cover fault",
         [", ".join(r["interface"]["offsetting_faults"]) or "no" for r in results]),
        ("cover faults", [_faults_text(r["faults"]) for r in results]),
        ("cover ux, left / middle / right third", [_thirds_text(r["cover_motion"]) for r in results]),
        ("left end wall", [_wall_text(r["end_walls"].get("left")) for r in results]),
        ("right end wall", [_wall_text(r["end_walls"].get("right")) for r in results]),
    ]
    for k, reg in enumerate(results[0]["salt_flow"]["regions"]):
        rows.append((f"salt flow, {reg['region']}",
                     [_flow_text(r["salt_flow"]["regions"][k]) for r in results]))
    if "keystone" in results[0]:
        rows.append(("deformed cover left / right of graben",
                     [(f"{_km(r['keystone']['left']['extent_m'])} / {_km(r['keystone']['right']['extent_m'])}"
                       if r["keystone"] else "–") for r in results]))
    if "tilted" in results[0]:
        rows.append(("block rotation (mean)", [("–" if r["tilted"]["mean_rotation_deg"] is None else
                                               f"{r['tilted']['mean_rotation_deg']:+.1f}°") for r in results]))
        rows.append(("fault spacing (mean)", [_km(r["tilted"]["mean_fault_spacing_m"]) for r in results]))
    return rows


def _table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> List[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return lines + ["| " + " | ".join(row) + " |" for row in rows]


def _fault_rows(faults: Sequence[dict]) -> List[List[str]]:
    rows = []
    for f in faults:
        surface = _km(f["x_surface_m"]) if f["reaches_surface"] else f"tip {_m(f['upper_tip_depth_m'])} deep"
        base = (_km(f["x_interface_m"]) if f["reaches_salt"]
                else f"tip {_m(f['lower_tip_above_salt_m'])} above salt")
        rows.append([f["id"], surface, base, f"{f['dip_deg']:.0f}°", f["dip_direction"], f["sense"] or "–",
                     _m(f["throw_m"]), "yes" if f["reaches_salt"] else "no",
                     "yes" if f["active"] else "no", _m(f["length_m"])])
    return rows


def outcomes_markdown(results: Sequence[dict], title: str = "Outcomes", notes: Sequence[str] = ()) -> str:
    """Markdown: one summary table (a column per frame) and a fault table per frame."""
    if not results:
        return f"## {title}\n\nno frames\n"
    lines = [f"## {title}", ""] + [f"{n}  " for n in notes] + ([""] if notes else [])
    header = ["outcome"] + [_stage_label(r) for r in results]
    lines += _table(header, [[name] + vals for name, vals in _summary_rows(results)])
    for r in results:
        lines += ["", f"### Cover faults at {_stage_label(r)} (frame {r['frame']})", ""]
        if not r["faults"]["list"]:
            lines.append("No localised band in the cover.")
            continue
        lines += _table(["fault", "x surface", "x interface", "dip", "dips", "sense", "throw", "reaches salt",
                         "active", "length"], _fault_rows(r["faults"]["list"]))
    return "\n".join(lines) + "\n"
