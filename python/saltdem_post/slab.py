"""3D slabs seen with the 2D tools: sections along strike and a map view of the cover's top.

A 3D scene is the 2D section (x along it, y up) extruded along strike z into a
slab of spheres, periodic in z.  ``section_at`` cuts a thin slice at one z and
returns it as a 2D frame (no z columns), so strain, thickness, outcomes and the
figures run on it unchanged.  ``map_view`` looks at the slab from above -- what
a section cannot show is how the cover varies along strike: on an x-z grid, the
elevation of the cover's top surface and the horizontal strain of its top layer
between two frames.
"""

from __future__ import annotations

from typing import Optional

import numpy as np
from scipy.spatial import cKDTree

from .dump import Box, Frame, match_ids
from .materials import MaterialMap
from .strain import StrainField, wrap_periodic, deformation_gradient

__all__ = ["section_at", "map_view", "map_view_figure", "default_width", "default_cell"]

# Columns that only a 3D frame has: dropping them leaves a frame the 2D tools read.
_Z_COLUMNS = ("z", "zu", "zs", "zsu", "vz", "iz")


def _z(frame: Frame) -> np.ndarray:
    if not any(c in frame for c in ("z", "zu", "zs", "zsu")):
        raise ValueError(f"{frame.path or 'frame'} has no z column: a 2D frame is already a section "
                         "(slabs are 3D runs, lmp ... -var dim 3)")
    return frame._coord(2)


def _period_z(frame: Frame) -> Optional[float]:
    return float(frame.box.length[2]) if frame.box.periodic[2] else None


def default_width(frame: Frame) -> float:
    """One median sphere diameter.  A slice that thick holds about as many sphere centres
    per unit area (6 phi / pi ~ 1.15 / d^2 at a packing fraction phi ~ 0.6) as a 2D disc
    packing holds discs (~1.1 / d^2): a continuous section, its discs spaced as in a 2D
    run, so the 2D tools' defaults (in disc diameters) still fit.  Thinner leaves holes;
    thicker stacks discs that overlap in projection."""
    return 2.0 * float(np.median(frame.radius))


def section_at(frame: Frame, z0: float, width: Optional[float] = None) -> Frame:
    """The spheres whose centres lie within ``width / 2`` of the plane z = ``z0`` (distances
    wrapped by the box length when z is periodic), as a 2D frame: z and vz columns dropped,
    the box's z bounds set to the slice.  ``width`` defaults to :func:`default_width`."""
    z = _z(frame)
    lo, hi = float(frame.box.lo[2]), float(frame.box.hi[2])
    if not lo <= z0 <= hi:
        raise ValueError(f"z = {z0:g} m is outside the box ({lo:g} to {hi:g} m): give a z inside it")
    width = default_width(frame) if width is None else float(width)
    if not width > 0:
        raise ValueError(f"section width {width:g} m: give a positive width (default one median diameter)")
    keep = np.abs(wrap_periodic(z - z0, _period_z(frame))) <= 0.5 * width
    box = Box(frame.box.lo.copy(), frame.box.hi.copy(), frame.box.tilt.copy(), frame.box.boundary)
    box.lo[2], box.hi[2] = z0 - 0.5 * width, z0 + 0.5 * width
    data = {k: v[keep] for k, v in frame.data.items() if k not in _Z_COLUMNS}
    return Frame(frame.timestep, box, data, frame.path, frame.index, frame.time)


# ------------------------------------------------------------------ map view

def default_cell(cover: Frame) -> float:
    """Two median cover diameters: the neighbour radius strain.py uses, so a cell's top
    layer (~12 spheres within that radius) fits a stable gradient."""
    return 4.0 * float(np.median(cover.radius))


class _Grid:
    """Regular x-z cells: x spans the cover of both frames, z the box (whole cells over a
    periodic length, so the last cell meets the first)."""

    def __init__(self, x_min: float, x_max: float, box: Box, cell: float):
        self.x0, self.z0, self.period = x_min, float(box.lo[2]), float(box.length[2]) if box.periodic[2] else None
        self.nx = max(1, int(np.ceil((x_max - x_min) / cell)))
        self.nz = max(1, int(round(float(box.length[2]) / cell)))
        self.dx, self.dz = cell, float(box.length[2]) / self.nz
        self.x = x_min + (np.arange(self.nx) + 0.5) * self.dx
        self.z = self.z0 + (np.arange(self.nz) + 0.5) * self.dz

    def index(self, x: np.ndarray, z: np.ndarray) -> np.ndarray:
        """Flat cell index (row = z, column = x) of each point."""
        dz = z - self.z0 if self.period is None else np.mod(z - self.z0, self.period)
        ix = np.clip(np.floor((x - self.x0) / self.dx).astype(np.int64), 0, self.nx - 1)
        iz = np.clip(np.floor(dz / self.dz).astype(np.int64), 0, self.nz - 1)
        return iz * self.nx + ix

    def top(self, cover: Frame) -> np.ndarray:
        """Highest y + r of the cover spheres centred in each cell (NaN: none)."""
        top = np.full(self.nz * self.nx, -np.inf)
        np.maximum.at(top, self.index(cover.x, _z(cover)), cover.y + cover.radius)
        top[np.isinf(top)] = np.nan
        return top

    def thickness(self, salt: Frame) -> np.ndarray:
        """Per cell, from the lowest y - r to the highest y + r of the salt spheres centred in
        it (NaN: none)."""
        k = self.index(salt.x, _z(salt))
        top, base = np.full(self.nz * self.nx, -np.inf), np.full(self.nz * self.nx, np.inf)
        np.maximum.at(top, k, salt.y + salt.radius)
        np.minimum.at(base, k, salt.y - salt.radius)
        t = top - base
        t[~np.isfinite(t)] = np.nan
        return t

    def mean(self, x: np.ndarray, z: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Mean of v over the points in each cell (NaN: none)."""
        k = self.index(x, z)
        n = np.bincount(k, minlength=self.nz * self.nx)
        s = np.bincount(k, v, minlength=self.nz * self.nx)
        return np.where(n > 0, s / np.maximum(n, 1), np.nan)


def map_view(ref: Frame, cur: Frame, cell: Optional[float] = None, radius: Optional[float] = None,
             materials: Optional[MaterialMap] = None, min_neighbours: int = 3) -> dict:
    """The cover's top surface between ``ref`` (earlier) and ``cur`` (later), on x-z cells.

    Per cell (arrays of shape (nz, nx); ``x``, ``z`` the cell centres):

    * ``top``, ``top_ref``: the highest y + r of the cover spheres centred in the cell;
      ``uplift`` = top - top_ref at the fixed cell (negative: subsidence);
    * ``dilatation``, ``shear``: horizontal incremental strain of the top layer -- the cover
      spheres of ``ref`` whose top lies within one median diameter of their cell's top,
      matched by id in ``cur``.  F (2 x 2, in x-z) is the least-squares affine fit of the
      (x, z) motion of the top-layer spheres whose reference centres lie within ``radius``
      (default: ``cell``) of the cell centre.  ``dilatation`` = det F - 1 (area change,
      extension positive); ``shear`` = (S1 - S2) / 2, the maximum shear of the Biot strain
      U - I (S1 >= S2 the principal stretches): tensor, not engineering, shear -- 0.01 for a
      2 % uniaxial stretch, half the equivalent simple shear that strain.py's ``max_shear``
      reports; both are zero for any rigid motion.  NaN where fewer than ``min_neighbours``
      spheres, or collinear ones, are there;
    * ``n_top``: top-layer spheres in each fit;
    * ``salt_dz``: the mean displacement along strike (+z) of the salt spheres, matched by id,
      binned at their reference (x, z): how the salt flows along strike;
    * ``salt_thickness``, ``salt_thickness_ref``, ``salt_dthick``: the salt's thickness in each
      column (lowest sphere bottom to highest sphere top) and its change at the fixed cell.
      All NaN where the column holds no salt (or, for ``salt_dz``, the frames none).

    ``cell`` defaults to :func:`default_cell`; along a periodic z it is adjusted so whole
    cells span the box.  z differences are wrapped by the box length when z is periodic.
    """
    materials = materials or MaterialMap()
    cover_ref = ref.subset(materials.mask(ref["type"], "cover"))
    cover_cur = cur.subset(materials.mask(cur["type"], "cover"))
    if not cover_ref.natoms or not cover_cur.natoms:
        raise ValueError(f"no cover spheres (types {materials.types_of('cover')}) in both frames: check --types")
    d = 2.0 * float(np.median(cover_ref.radius))
    cell = default_cell(cover_ref) if cell is None else float(cell)
    if not cell > 0:
        raise ValueError(f"cell size {cell:g} m: give a positive size")
    radius = cell if radius is None else float(radius)
    x_all = np.concatenate([cover_ref.x, cover_cur.x])
    grid = _Grid(float(x_all.min()), float(x_all.max()), ref.box, cell)
    top_ref, top_cur = grid.top(cover_ref), grid.top(cover_cur)

    # The top layer, matched by id: reference and current (z, x) -- z first, the axis
    # strain.py's functions treat as periodic.
    z_ref = _z(cover_ref)
    layer = cover_ref.y + cover_ref.radius >= top_ref[grid.index(cover_ref.x, z_ref)] - d
    ia, ib = match_ids(cover_ref.ids[layer], cover_cur.ids)
    X = np.column_stack([z_ref[layer][ia], cover_ref.x[layer][ia]])
    x = np.column_stack([_z(cover_cur)[ib], cover_cur.x[ib]])
    P, P_cur = grid.period, _period_z(cur)
    u = x - X
    u[:, 0] = wrap_periodic(u[:, 0], P_cur)

    # Members of each cell's neighbourhood (reference positions).
    centres = np.column_stack([np.repeat(grid.z, grid.nx), np.tile(grid.x, grid.nz)])
    if P:
        tree = cKDTree(np.column_stack([np.mod(X[:, 0] - grid.z0, P), X[:, 1]]), boxsize=[P, 0.0])
        members = tree.query_ball_point(np.column_stack([centres[:, 0] - grid.z0, centres[:, 1]]), radius)
    else:
        members = cKDTree(X).query_ball_point(centres, radius)
    cell_of = np.repeat(np.arange(len(members)), [len(m) for m in members])
    member = np.concatenate([np.asarray(m, dtype=np.int64) for m in members])

    # A node per cell at its members' centroid, paired with each member: deformation_gradient's
    # fit at that node is then the least-squares affine fit (translation included) of the cell.
    n = np.maximum(np.bincount(cell_of, minlength=len(centres)), 1)
    offset = X[member] - centres[cell_of]
    offset[:, 0] = wrap_periodic(offset[:, 0], P)
    node_ref = centres + np.column_stack([np.bincount(cell_of, offset[:, k], len(centres)) / n for k in (0, 1)])
    node_cur = node_ref + np.column_stack([np.bincount(cell_of, u[member, k], len(centres)) / n for k in (0, 1)])
    nodes = len(X) + np.arange(len(centres))
    F, count, d2min = deformation_gradient(np.vstack([X, node_ref]), np.vstack([x, node_cur]),
                                           (nodes[cell_of], member), (P, P_cur), min_neighbours)
    fit = StrainField(np.arange(len(centres)), node_ref, node_cur, F[nodes], count[nodes], d2min[nodes],
                      ref.timestep, cur.timestep, radius)
    s1, s2 = fit.stretches

    def grid_of(v):
        return np.asarray(v, float).reshape(grid.nz, grid.nx)

    salt_ref = ref.subset(materials.mask(ref["type"], "salt"))
    salt_cur = cur.subset(materials.mask(cur["type"], "salt"))
    nan = np.full(grid.nz * grid.nx, np.nan)
    th_ref = grid.thickness(salt_ref) if salt_ref.natoms else nan
    th_cur = grid.thickness(salt_cur) if salt_cur.natoms else nan
    sa, sb = match_ids(salt_ref.ids, salt_cur.ids) if salt_ref.natoms and salt_cur.natoms else ([], [])
    if len(sa):
        zs = _z(salt_ref)[sa]
        dz = wrap_periodic(_z(salt_cur)[sb] - zs, P_cur)
        salt_dz = grid.mean(salt_ref.x[sa], zs, dz)
    else:
        salt_dz = nan
    return {"x": grid.x, "z": grid.z, "cell": (grid.dx, grid.dz), "radius": radius,
            "ref_timestep": ref.timestep, "cur_timestep": cur.timestep,
            "top": grid_of(top_cur), "top_ref": grid_of(top_ref), "uplift": grid_of(top_cur - top_ref),
            "dilatation": grid_of(fit.dilatation), "shear": grid_of(0.5 * (s1 - s2)),
            "n_top": grid_of(fit.n_neighbours).astype(np.int64),
            "salt_dz": grid_of(salt_dz), "salt_thickness": grid_of(th_cur),
            "salt_thickness_ref": grid_of(th_ref), "salt_dthick": grid_of(th_cur - th_ref)}


def map_view_figure(view: dict, path: str, dpi: int = 150) -> str:
    """Stacked map panels, x along the section, z along strike, equal aspect, each on a scale
    centred on 0: the change of the cover's top elevation, the horizontal dilatation of its
    top layer, the salt's mean displacement along strike and the change of its thickness."""
    from .figures import km_axes, plt        # matplotlib (Agg) only when drawing
    x, z, (dx, dz) = view["x"], view["z"], view["cell"]
    xe = np.append(x - 0.5 * dx, x[-1] + 0.5 * dx)
    ze = np.append(z - 0.5 * dz, z[-1] + 0.5 * dz)
    aspect = (ze[-1] - ze[0]) / (xe[-1] - xe[0])
    steps = f"steps {view['ref_timestep']} → {view['cur_timestep']}"
    panels = [("uplift", f"change of the cover's top elevation, {steps}", "Δ top (m)", "RdBu_r"),
              ("dilatation", "horizontal dilatation of its top layer (extension > 0)", "dilatation (–)", "PuOr_r"),
              ("salt_dz", "the salt's mean displacement along strike (+z)", "Δz (m)", "BrBG"),
              ("salt_dthick", "change of the salt's thickness", "Δ thickness (m)", "RdBu_r")]
    fig, axes = plt.subplots(len(panels), 1, figsize=(8.0, len(panels) * max(1.6, 6.5 * aspect) + 1.4),
                             constrained_layout=True)
    for ax, (key, title, label, cmap) in zip(axes, panels):
        v = np.ma.masked_invalid(view[key])
        vmax = float(np.abs(v).max()) if v.count() else 1.0
        vmax = vmax or 1.0
        mesh = ax.pcolormesh(xe, ze, v, cmap=cmap, vmin=-vmax, vmax=vmax)
        ax.set_aspect("equal")
        km_axes(ax)
        ax.set_ylabel("z along strike (km)")
        ax.set_title(title, fontsize="medium")
        fig.colorbar(mesh, ax=ax, label=label)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path
