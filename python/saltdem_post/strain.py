"""Per-particle strain from the displacements between two frames.

For each disc *i* the deformation gradient ``F`` is the least-squares fit of
the relative positions of its neighbours *j* in the two frames::

    minimise  sum_j | dx_ij - F dX_ij |^2      dX = X_j - X_i  (reference frame)
                                               dx = x_j - x_i  (current frame)
    =>  F = (sum_j dx dX^T) (sum_j dX dX^T)^-1

(Falk & Langer 1998; the residual is their D^2_min, a measure of non-affine
motion).  Neighbours are the discs within ``radius`` of *i* in the reference
frame, or its Delaunay neighbours there.  The description is Lagrangian: the
reference frame is the *earlier* frame, gradients are with respect to
reference positions, and results belong to atom ids (plotted by default at
their positions in the later frame).  "Incremental" strain uses the previous
frame (e.g. 50 m of fault displacement earlier) as reference, "finite" strain
the first frame of the run.

Two families of measures are reported, both exact for any strain size:

* finite-strain measures from ``F`` (``max_shear``, ``dilatation``,
  ``rotation``, stretches ``S1 >= S2``): zero for any rigid motion;
* linearised measures from ``H = F - I`` (``*_small``), the classic small-strain
  tensor -- only meaningful when the step is small (they are not zero for a
  large rigid rotation).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, Optional, Tuple

import numpy as np
from scipy.spatial import Delaunay, cKDTree

from .dump import Frame, match_ids

#: default neighbourhood radius in median disc radii (= two disc diameters)
RADIUS_IN_DISC_RADII = 4.0


def default_radius(frame: Frame) -> float:
    """Two median disc diameters: enough neighbours (~12 in a packing) for a
    stable fit, small enough to resolve shear bands a few discs wide."""
    return RADIUS_IN_DISC_RADII * float(np.median(frame.radius))


def wrap_periodic(d: np.ndarray, period: Optional[float]) -> np.ndarray:
    """Minimum-image convention along a periodic axis (period None or 0: not periodic)."""
    if period:
        d = d - period * np.round(d / period)
    return d


def neighbour_pairs(xy: np.ndarray, radius: Optional[float], method: str = "radius",
                    period_x: Optional[float] = None, x0: float = 0.0) -> Tuple[np.ndarray, np.ndarray]:
    """Unique neighbour pairs ``(i, j)``, ``i < j``, in configuration ``xy``.

    ``method="radius"``: all pairs closer than ``radius``.  ``"delaunay"``: the
    edges of the Delaunay triangulation, dropping those longer than ``radius``
    (if given) so that hull edges across free surfaces do not couple distant
    discs.  ``period_x`` (box length, with box origin ``x0``) makes x periodic.
    """
    if method == "radius":
        if not radius or radius <= 0:
            raise ValueError("radius method needs a positive radius")
        if period_x:
            pts = np.column_stack([np.mod(xy[:, 0] - x0, period_x), xy[:, 1]])
            tree = cKDTree(pts, boxsize=[period_x, 0.0])   # 0: y not periodic
        else:
            tree = cKDTree(xy)
        pairs = tree.query_pairs(radius, output_type="ndarray")
        return pairs[:, 0], pairs[:, 1]
    if method == "delaunay":
        if period_x:
            raise NotImplementedError("the Delaunay variant does not support periodic x; use method='radius'")
        simplices = Delaunay(xy).simplices
        edges = np.concatenate([simplices[:, [0, 1]], simplices[:, [1, 2]], simplices[:, [0, 2]]])
        edges = np.sort(edges, axis=1).astype(np.int64)
        key = np.unique(edges[:, 0] * len(xy) + edges[:, 1])    # 1-D unique is much faster
        edges = np.column_stack([key // len(xy), key % len(xy)])
        if radius:
            d = xy[edges[:, 1]] - xy[edges[:, 0]]
            edges = edges[np.hypot(d[:, 0], d[:, 1]) <= radius]
        return edges[:, 0], edges[:, 1]
    raise ValueError(f"unknown neighbour method {method!r} (use 'radius' or 'delaunay')")


def deformation_gradient(ref_xy: np.ndarray, cur_xy: np.ndarray, pairs: Tuple[np.ndarray, np.ndarray],
                         period_x: Tuple[Optional[float], Optional[float]] = (None, None),
                         min_neighbours: int = 3, tol: float = 1e-8):
    """Least-squares ``F`` (N x 2 x 2), neighbour count and D^2_min per disc.

    Discs with fewer than ``min_neighbours`` neighbours, or whose neighbours
    are (nearly) collinear, get NaN.  ``period_x`` = (reference, current) box
    lengths for a periodic x axis.
    """
    n = len(ref_xy)
    i, j = pairs
    dX = ref_xy[j] - ref_xy[i]
    dx = cur_xy[j] - cur_xy[i]
    dX[:, 0] = wrap_periodic(dX[:, 0], period_x[0])
    dx[:, 0] = wrap_periodic(dx[:, 0], period_x[1])

    def acc(w):
        # A pair contributes the same outer products to both ends (signs cancel).
        return np.bincount(i, w, minlength=n) + np.bincount(j, w, minlength=n)

    a11, a12, a22 = acc(dX[:, 0] ** 2), acc(dX[:, 0] * dX[:, 1]), acc(dX[:, 1] ** 2)
    b11, b12 = acc(dx[:, 0] * dX[:, 0]), acc(dx[:, 0] * dX[:, 1])
    b21, b22 = acc(dx[:, 1] * dX[:, 0]), acc(dx[:, 1] * dX[:, 1])
    c = acc(dx[:, 0] ** 2 + dx[:, 1] ** 2)
    count = np.bincount(i, minlength=n) + np.bincount(j, minlength=n)

    det = a11 * a22 - a12 ** 2
    ok = (count >= min_neighbours) & (det > tol * (0.5 * (a11 + a22)) ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), np.nan)
        F = np.empty((n, 2, 2))
        F[:, 0, 0] = (b11 * a22 - b12 * a12) * inv
        F[:, 0, 1] = (b12 * a11 - b11 * a12) * inv
        F[:, 1, 0] = (b21 * a22 - b22 * a12) * inv
        F[:, 1, 1] = (b22 * a11 - b21 * a12) * inv
        # D^2_min = sum|dx|^2 - tr(F B^T): the part of the motion F cannot explain.
        d2 = c - (F[:, 0, 0] * b11 + F[:, 0, 1] * b12 + F[:, 1, 0] * b21 + F[:, 1, 1] * b22)
        d2min = np.maximum(d2, 0.0) / np.where(count > 0, count, np.nan)
    return F, count, d2min


@dataclass
class StrainField:
    """Strain of every disc present in both frames, ordered by atom id."""

    ids: np.ndarray
    ref_xy: np.ndarray
    cur_xy: np.ndarray
    F: np.ndarray
    n_neighbours: np.ndarray
    d2min: np.ndarray
    ref_timestep: int = 0
    cur_timestep: int = 0
    radius: Optional[float] = None
    method: str = "radius"

    # ---- finite-strain measures (exact for any deformation)
    def _cauchy_green(self) -> Tuple[np.ndarray, np.ndarray]:
        """Mean and half-difference of the eigenvalues of C = F^T F."""
        F = self.F
        c11 = F[:, 0, 0] ** 2 + F[:, 1, 0] ** 2
        c22 = F[:, 0, 1] ** 2 + F[:, 1, 1] ** 2
        c12 = F[:, 0, 0] * F[:, 0, 1] + F[:, 1, 0] * F[:, 1, 1]
        return 0.5 * (c11 + c22), np.hypot(0.5 * (c11 - c22), c12)

    @property
    def stretches(self) -> Tuple[np.ndarray, np.ndarray]:
        """Principal stretches S1 >= S2 (square roots of the eigenvalues of F^T F)."""
        m, r = self._cauchy_green()
        return np.sqrt(m + r), np.sqrt(np.maximum(m - r, 0.0))

    @property
    def jacobian(self) -> np.ndarray:
        F = self.F
        return F[:, 0, 0] * F[:, 1, 1] - F[:, 0, 1] * F[:, 1, 0]

    @property
    def max_shear(self) -> np.ndarray:
        """Equivalent simple-shear strain ``(S1 - S2) / sqrt(S1 S2)``: the gamma
        of the simple shear with the same stretch ratio.  Equals gamma exactly
        for simple shear, k - 1/k for pure shear diag(k, 1/k), 0 for rigid motion."""
        m, r = self._cauchy_green()
        s1, s2 = np.sqrt(m + r), np.sqrt(np.maximum(m - r, 0.0))
        with np.errstate(divide="ignore", invalid="ignore"):
            # S1 - S2 = (S1^2 - S2^2) / (S1 + S2) avoids cancellation at small strain.
            return 2.0 * r / (s1 + s2) / np.sqrt(s1 * s2)

    @property
    def dilatation(self) -> np.ndarray:
        """Relative area change ``det F - 1``."""
        return self.jacobian - 1.0

    @property
    def rotation(self) -> np.ndarray:
        """Rigid rotation of the polar decomposition F = R U, radians,
        counter-clockwise positive (x right, y up)."""
        F = self.F
        return np.arctan2(F[:, 1, 0] - F[:, 0, 1], F[:, 0, 0] + F[:, 1, 1])

    # ---- linearised (small-strain) measures from H = F - I
    @property
    def small_strain(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        F = self.F
        return F[:, 0, 0] - 1.0, F[:, 1, 1] - 1.0, 0.5 * (F[:, 0, 1] + F[:, 1, 0])

    @property
    def max_shear_small(self) -> np.ndarray:
        """Engineering maximum shear strain ``2 sqrt(((exx-eyy)/2)^2 + exy^2)``."""
        exx, eyy, exy = self.small_strain
        return 2.0 * np.hypot(0.5 * (exx - eyy), exy)

    @property
    def dilatation_small(self) -> np.ndarray:
        exx, eyy, _ = self.small_strain
        return exx + eyy

    @property
    def rotation_small(self) -> np.ndarray:
        F = self.F
        return 0.5 * (F[:, 1, 0] - F[:, 0, 1])

    @property
    def displacement(self) -> np.ndarray:
        return self.cur_xy - self.ref_xy

    def table(self) -> Dict[str, np.ndarray]:
        """Columns for CSV output, in a fixed order."""
        exx, eyy, exy = self.small_strain
        s1, s2 = self.stretches
        u = self.displacement
        return {
            "id": self.ids, "x": self.cur_xy[:, 0], "y": self.cur_xy[:, 1],
            "x_ref": self.ref_xy[:, 0], "y_ref": self.ref_xy[:, 1], "ux": u[:, 0], "uy": u[:, 1],
            "n_neighbours": self.n_neighbours,
            "F11": self.F[:, 0, 0], "F12": self.F[:, 0, 1], "F21": self.F[:, 1, 0], "F22": self.F[:, 1, 1],
            "max_shear": self.max_shear, "dilatation": self.dilatation, "rotation": self.rotation,
            "S1": s1, "S2": s2,
            "exx": exx, "eyy": eyy, "exy": exy, "max_shear_small": self.max_shear_small,
            "dilatation_small": self.dilatation_small, "rotation_small": self.rotation_small,
            "d2min": self.d2min,
        }

    def summary(self) -> dict:
        def stats(v):
            v = v[np.isfinite(v)]
            if not v.size:
                return {}
            p = np.percentile(v, [50, 90, 99])
            return {"mean": float(v.mean()), "median": float(p[0]), "p90": float(p[1]),
                    "p99": float(p[2]), "max": float(v.max())}
        return {
            "ref_timestep": int(self.ref_timestep), "cur_timestep": int(self.cur_timestep),
            "n_particles": int(len(self.ids)), "n_undefined": int(np.isnan(self.F[:, 0, 0]).sum()),
            "neighbours": self.method, "radius_m": self.radius,
            "max_shear": stats(self.max_shear), "dilatation": stats(self.dilatation),
            "rotation_rad": stats(self.rotation),
        }


def strain_between(ref: Frame, cur: Frame, radius: Optional[float] = None, method: str = "radius",
                   min_neighbours: int = 3) -> StrainField:
    """Strain of the discs common to ``ref`` (earlier) and ``cur`` (later).

    ``radius`` defaults to :func:`default_radius` of the reference frame; for
    the Delaunay method it caps the edge length instead.
    """
    ia, ib = match_ids(ref.ids, cur.ids)
    if not len(ia):
        raise ValueError("the two frames have no atom ids in common")
    ref_xy, cur_xy = ref.xy[ia], cur.xy[ib]
    if radius is None and ("radius" in ref or "diameter" in ref):
        radius = default_radius(ref)
    periodic = ref.box.periodic[0] and cur.box.periodic[0]
    period = (float(ref.box.length[0]), float(cur.box.length[0])) if periodic else (None, None)
    pairs = neighbour_pairs(ref_xy, radius, method, period[0], float(ref.box.lo[0]))
    F, count, d2min = deformation_gradient(ref_xy, cur_xy, pairs, period, min_neighbours)
    return StrainField(ref.ids[ia], ref_xy, cur_xy, F, count, d2min,
                       ref.timestep, cur.timestep, radius, method)
