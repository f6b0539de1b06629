"""Cover-fault candidates: localised straight bands of high max shear strain,
found by RANSAC line fits in clusters of strong discs and merged across the
finite and incremental strain."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator, List, Optional, Sequence, Tuple

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from ..strain import StrainField
from .options import Lengths, OutcomeOptions

MAX_BANDS_PER_CLUSTER = 50


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
