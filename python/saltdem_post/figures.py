"""Paper-style PNG figures: marker geometry beside incremental shear strain,
strain maps, salt-thickness and flow profiles.  Axes are in km (data stay in
metres so discs are drawn at their true size)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

import matplotlib

matplotlib.use("Agg")                         # files only, never a window
import matplotlib.pyplot as plt               # noqa: E402
import numpy as np                            # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402
from matplotlib.colors import Normalize, to_rgba_array  # noqa: E402
from matplotlib.patches import Patch          # noqa: E402
from matplotlib.ticker import FuncFormatter   # noqa: E402

from .dump import Frame, match_ids            # noqa: E402
from .materials import MaterialMap            # noqa: E402
from .measure import ThicknessProfile, VerticalProfile  # noqa: E402
from .strain import StrainField               # noqa: E402

# Alternating colours per marker index, so layers and bands read as stripes.
COVER_COLOURS = ("#f2c14e", "#4d7ea8")
SALT_COLOURS = ("#f7b2c8", "#b5527f")
WALL_COLOUR = "#8c8c8c"
# Growth strata: discs deposited by fix saltdem/sediment carry marker GROWTH_OFFSET + epoch
# (examples/scene/sediment.in: 1000 + k for the k-th interval), coloured by epoch from light to
# dark green, alternate epochs lighter so neighbouring strata read apart.
GROWTH_OFFSET = 1000
GROWTH_CMAP = "Greens"
UNMAPPED_COLOUR = "#d9d9d9"
STRAIN_CMAP = "magma_r"
PANEL_WIDTH = 6.0                             # inches per model panel


def km_axes(ax, xlabel: bool = True, ylabel: bool = True) -> None:
    km = FuncFormatter(lambda v, _: f"{v / 1000:g}")
    ax.xaxis.set_major_formatter(km)
    ax.yaxis.set_major_formatter(km)
    if xlabel:
        ax.set_xlabel("x (km)")
    if ylabel:
        ax.set_ylabel("y (km)")


def draw_discs(ax, xy: np.ndarray, r: np.ndarray, facecolors=None, values=None,
               cmap=None, norm=None) -> EllipseCollection:
    """Discs at true size in data units (fast for ~10^5 discs)."""
    coll = EllipseCollection(2 * r, 2 * r, np.zeros(len(r)), units="xy", offsets=xy,
                             offset_transform=ax.transData, linewidths=0, edgecolors="none")
    if values is not None:
        coll.set_array(np.ma.masked_invalid(values))
        coll.set_cmap(cmap)
        coll.set_norm(norm)
    else:
        coll.set_facecolor(facecolors)
    ax.add_collection(coll)
    return coll


def growth_epochs(types: np.ndarray, markers: np.ndarray, materials: MaterialMap,
                  offset: Optional[int] = GROWTH_OFFSET) -> np.ndarray:
    """Deposition epoch per disc: k for a cover disc with marker offset + k (k >= 1), else 0
    (the cover and salt of the initial model, walls; everything when offset is None or 0)."""
    markers = np.asarray(markers)
    if not offset:
        return np.zeros(len(markers), dtype=np.int64)
    grown = materials.mask(types, "cover") & (markers > offset)
    return np.where(grown, markers - offset, 0).astype(np.int64)


def growth_colours(epochs: np.ndarray, nepochs: int) -> np.ndarray:
    """RGBA of growth strata of the given epochs (1..nepochs): light to dark green, alternate
    epochs lighter."""
    epochs = np.asarray(epochs)
    t = (epochs - 1) / max(nepochs - 1, 1)
    rgba = plt.get_cmap(GROWTH_CMAP)(0.35 + 0.6 * np.clip(t, 0.0, 1.0))
    even = (epochs % 2 == 0)
    rgba[even, :3] += (1.0 - rgba[even, :3]) * 0.3
    return rgba


def marker_colours(types: np.ndarray, markers: np.ndarray, materials: MaterialMap,
                   growth_offset: Optional[int] = GROWTH_OFFSET, nepochs: Optional[int] = None) -> np.ndarray:
    """RGBA per disc: cover layers and salt bands in alternating colours, growth strata (cover
    discs with marker growth_offset + epoch) by epoch on a scale of nepochs (default: the
    largest epoch present)."""
    rgba = np.tile(to_rgba_array(UNMAPPED_COLOUR), (len(types), 1))
    odd = (np.asarray(markers) % 2).astype(bool)
    for material, colours in (("cover", COVER_COLOURS), ("salt", SALT_COLOURS)):
        m = materials.mask(types, material)
        rgba[m & ~odd] = to_rgba_array(colours[0])
        rgba[m & odd] = to_rgba_array(colours[1])
    rgba[materials.mask(types, "wall")] = to_rgba_array(WALL_COLOUR)
    epochs = growth_epochs(types, markers, materials, growth_offset)
    grown = epochs > 0
    if grown.any():
        rgba[grown] = growth_colours(epochs[grown], nepochs or int(epochs.max()))
    return rgba


def marker_legend(nepochs: int = 0) -> List[Patch]:
    patches = [Patch(color=COVER_COLOURS[0], label="cover layers"), Patch(color=COVER_COLOURS[1]),
               Patch(color=SALT_COLOURS[0], label="salt bands"), Patch(color=SALT_COLOURS[1]),
               Patch(color=WALL_COLOUR, label="wall / basement")]
    if nepochs > 0:
        first, last = growth_colours(np.array([1, nepochs]), nepochs)
        label = "growth strata, epoch 1" + (f" (light) to {nepochs} (dark)" if nepochs > 1 else "")
        patches += [Patch(color=first, label=label)] + ([Patch(color=last)] if nepochs > 1 else [])
    return patches


def extent(frames: Sequence[Frame], pad: float = 0.0) -> Tuple[Tuple[float, float], Tuple[float, float]]:
    """Bounding box (m) of all discs of all frames, so panels share limits."""
    xs = [(f.x - f.radius).min() for f in frames] + [(f.x + f.radius).max() for f in frames]
    ys = [(f.y - f.radius).min() for f in frames] + [(f.y + f.radius).max() for f in frames]
    return (min(xs) - pad, max(xs) + pad), (min(ys) - pad, max(ys) + pad)


def nice_max(values: Sequence[np.ndarray], percentile: float = 99.0) -> float:
    """A round colour-scale maximum covering ``percentile`` % of all values."""
    v = np.concatenate([np.asarray(a)[np.isfinite(a)] for a in values] or [np.zeros(1)])
    top = float(np.percentile(v, percentile)) if v.size else 0.0
    if top <= 0:
        return 1.0
    mag = 10 ** np.floor(np.log10(top))
    return float(min(s * mag for s in (1, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10) if s * mag >= top))


def _field_on_frame(field: StrainField, frame: Frame, values: np.ndarray):
    """Positions (current config), radii and values of the field's discs."""
    i_field, i_frame = match_ids(field.ids, frame.ids)
    return field.cur_xy[i_field], frame.radius[i_frame], values[i_field], frame["type"][i_frame]


@dataclass
class PanelRow:
    """One row of the paper figure: geometry at ``frame`` and the strain
    accumulated since the previous stage (``strain`` may be None)."""

    label: str
    frame: Frame
    markers: np.ndarray
    strain: Optional[StrainField] = None
    strain_label: str = ""


def _panel_height(xlim, ylim, panel_width: float) -> float:
    return max(panel_width * (ylim[1] - ylim[0]) / (xlim[1] - xlim[0]), 0.3)


def _figsize(nrows: int, ncols: int, xlim, ylim, panel_width: float, footer: float = 0.0) -> Tuple[float, float]:
    """Inches: panels plus room for titles and tick labels, and a footer row."""
    return ncols * panel_width + 1.0, nrows * (_panel_height(xlim, ylim, panel_width) + 0.75) + footer + 0.3


def paper_figure(rows: Sequence[PanelRow], path: str, materials: Optional[MaterialMap] = None,
                 strain_max: Optional[float] = None, xlim=None, ylim=None, dpi: int = 150,
                 title: Optional[str] = None, panel_width: float = PANEL_WIDTH,
                 growth_offset: Optional[int] = GROWTH_OFFSET) -> dict:
    """Multi-panel figure like the paper's Figs. 3-7: one row per stage, the
    marker geometry on the left and incremental maximum shear strain on the
    right, with shared limits and one colour scale for every strain panel.
    Growth strata (fix saltdem/sediment) are coloured by epoch on one scale
    for all rows."""
    materials = materials or MaterialMap()
    nepochs = max([int(growth_epochs(r.frame["type"], r.markers, materials, growth_offset).max(initial=0))
                   for r in rows] or [0])
    (x0, x1), (y0, y1) = extent([r.frame for r in rows], pad=0.0)
    xlim, ylim = xlim or (x0, x1), ylim or (y0, y1)
    with_strain = any(r.strain is not None for r in rows)
    ncols = 2 if with_strain else 1
    if strain_max is None:
        strain_max = nice_max([r.strain.max_shear for r in rows if r.strain is not None])
    norm = Normalize(0.0, strain_max)
    cmap = plt.get_cmap(STRAIN_CMAP).with_extremes(bad=UNMAPPED_COLOUR)
    # A footer row below the panels holds the marker legend and the colour bar.
    footer = 0.8
    fig = plt.figure(figsize=_figsize(len(rows), ncols, xlim, ylim, panel_width, footer), constrained_layout=True)
    grid = fig.add_gridspec(len(rows) + 1, ncols,
                            height_ratios=[_panel_height(xlim, ylim, panel_width)] * len(rows) + [footer * 0.45])
    axes = np.array([[fig.add_subplot(grid[k, c]) for c in range(ncols)] for k in range(len(rows))])
    mappable = None
    for k, row in enumerate(rows):
        last = k == len(rows) - 1
        ax = axes[k, 0]
        fr = row.frame
        draw_discs(ax, fr.xy, fr.radius,
                   facecolors=marker_colours(fr["type"], row.markers, materials, growth_offset, nepochs))
        ax.set_title(row.label, loc="left", fontsize=10)
        if with_strain:
            ax = axes[k, 1]
            if row.strain is not None:
                xy, r, val, typ = _field_on_frame(row.strain, fr, row.strain.max_shear)
                wall = materials.mask(typ, "wall")
                draw_discs(ax, xy[wall], r[wall], facecolors=WALL_COLOUR)
                mappable = draw_discs(ax, xy[~wall], r[~wall], values=val[~wall], cmap=cmap, norm=norm)
                ax.set_title(row.strain_label or "incremental maximum shear strain", loc="left", fontsize=10)
            else:
                ax.text(0.5, 0.5, "no earlier frame", transform=ax.transAxes, ha="center", va="center")
        for c in range(ncols):
            a = axes[k, c]
            a.set_xlim(xlim)
            a.set_ylim(ylim)
            a.set_aspect("equal")
            km_axes(a, xlabel=last, ylabel=c == 0)
    legend_ax = fig.add_subplot(grid[-1, 0])
    legend_ax.axis("off")
    legend_ax.legend(handles=marker_legend(nepochs), loc="center", ncol=5 if not nepochs else 4, fontsize=8,
                     frameon=False, handlelength=1.2)
    if mappable is not None:
        holder = fig.add_subplot(grid[-1, 1])
        holder.axis("off")
        cax = holder.inset_axes([0.15, 0.6, 0.7, 0.3])
        fig.colorbar(mappable, cax=cax, orientation="horizontal", extend="max",
                     label="incremental maximum shear strain γ")
    if title:
        fig.suptitle(title)
    fig.savefig(path, dpi=dpi)
    size = fig.get_size_inches() * dpi
    plt.close(fig)
    return {"path": str(path), "strain_max": strain_max, "pixels": [int(round(size[0])), int(round(size[1]))]}


def strain_figure(field: StrainField, frame: Frame, path: str, quantity: str = "max_shear",
                  materials: Optional[MaterialMap] = None, vmax: Optional[float] = None,
                  dpi: int = 150, title: Optional[str] = None) -> dict:
    """Map of one strain quantity on the later frame's geometry."""
    materials = materials or MaterialMap()
    table = field.table()
    if quantity not in table:
        raise KeyError(f"unknown strain quantity {quantity!r}; choose from {', '.join(table)}")
    values = np.asarray(table[quantity], dtype=float)
    xy, r, val, typ = _field_on_frame(field, frame, values)
    signed = quantity in ("dilatation", "rotation", "dilatation_small", "rotation_small", "exx", "eyy", "exy")
    vmax = vmax or nice_max([np.abs(val)])
    norm = Normalize(-vmax if signed else 0.0, vmax)
    cmap = plt.get_cmap("RdBu_r" if signed else STRAIN_CMAP).with_extremes(bad=UNMAPPED_COLOUR)
    xlim, ylim = extent([frame])
    fig, ax = plt.subplots(figsize=_figsize(1, 1, xlim, ylim, PANEL_WIDTH * 1.5), constrained_layout=True)
    wall = materials.mask(typ, "wall")
    draw_discs(ax, xy[wall], r[wall], facecolors=WALL_COLOUR)
    m = draw_discs(ax, xy[~wall], r[~wall], values=val[~wall], cmap=cmap, norm=norm)
    ax.set_xlim(xlim)
    ax.set_ylim(ylim)
    ax.set_aspect("equal")
    km_axes(ax)
    ax.set_title(title or f"{quantity}, steps {field.ref_timestep} → {field.cur_timestep}", loc="left")
    fig.colorbar(m, ax=ax, orientation="horizontal", location="bottom", shrink=0.6, aspect=40, label=quantity)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return {"path": str(path), "vmax": vmax}


def thickness_figure(profiles: Sequence[ThicknessProfile], path: str, labels: Optional[Sequence[str]] = None,
                     dpi: int = 150) -> dict:
    """Salt thickness along x, one line per frame; weld threshold dashed,
    the minimum of the last frame marked."""
    fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
    colours = plt.get_cmap("viridis")(np.linspace(0, 0.9, max(len(profiles), 1)))
    for k, p in enumerate(profiles):
        label = labels[k] if labels else f"step {p.timestep}"
        ax.plot(p.x, p.thickness, color=colours[k], lw=1.5, label=label)
    last = profiles[-1]
    ax.axhline(last.weld_thickness, color="k", ls="--", lw=1, label=f"weld < {last.weld_thickness:.0f} m")
    mn = last.minimum()
    if mn["x_m"] is not None:
        ax.plot([mn["x_m"]], [mn["thickness_m"]], "rv", ms=8,
                label=f"min {mn['thickness_m']:.0f} m at {mn['x_m'] / 1000:.2f} km")
    for w in last.welds():
        ax.axvspan(w["x_start_m"], w["x_end_m"], color="r", alpha=0.12, lw=0)
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v / 1000:g}"))
    ax.set_xlabel("x (km)")
    ax.set_ylabel("salt thickness (m)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8, ncol=2)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return {"path": str(path)}


def profile_figure(profiles: Sequence[VerticalProfile], path: str, unit: str = "", dpi: int = 150) -> dict:
    """One panel per vertical profile: disc samples, binned means, fit."""
    fig, axes = plt.subplots(1, len(profiles), figsize=(3.6 * len(profiles) + 0.5, 4.5),
                             squeeze=False, constrained_layout=True)
    for ax, p in zip(axes[0], profiles):
        ax.plot(p.u, p.y, ".", color="0.7", ms=3, label="discs")
        if len(p.bins.get("y", [])):
            ax.plot(p.bins["mean"], p.bins["y"], "o", color="C0", ms=4, label="binned mean")
        if p.fit is not None:
            yy = np.linspace(p.fit.base, p.fit.top, 100)
            f = p.fit
            ax.plot(f.predict(yy), yy, "C3-", lw=1.5,
                    label=f"fit: Couette {f.couette:.3g}\nPoiseuille {f.poiseuille:.3g}\nR² {f.r2:.3f}")
            ax.axhline(f.base, color="k", lw=0.6, ls=":")
            ax.axhline(f.top, color="k", lw=0.6, ls=":")
        ax.set_title(f"x = {p.x / 1000:.2f} km, step {p.timestep}", fontsize=10)
        ax.set_xlabel(f"{p.quantity}{f' ({unit})' if unit else ''}")
        ax.set_ylabel("y (m)")
        ax.legend(fontsize=7)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return {"path": str(path)}
