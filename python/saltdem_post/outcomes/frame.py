"""All outcomes of one frame, from the measurement modules."""

from __future__ import annotations

from dataclasses import asdict
from typing import Optional

import numpy as np

from ..dump import Frame
from ..materials import MaterialMap, markers
from ..measure import salt_thickness
from ..strain import StrainField, strain_between
from .bands import detect_bands, merge_bands
from .basement import basement_tips
from .faults import CoverGeometry, describe_fault, fault_position
from .flow import flow_regions, salt_band_flows
from .geometry import Columns
from .options import Lengths, OutcomeOptions
from .salt import interface_outcome, salt_outcome
from .scenes import deformed_widths, tilted_outcome
from .walls import cover_thirds, end_wall_outcome, wall_faces


def cover_strain(ref: Frame, cur: Frame, materials: MaterialMap, opts: OutcomeOptions) -> StrainField:
    """Strain of the cover discs from cover neighbours only, so that the
    salt's shear does not leak into the base of the cover."""
    return strain_between(ref.subset(materials.mask(ref["type"], "cover")),
                          cur.subset(materials.mask(cur["type"], "cover")),
                          opts.radius, opts.method, opts.min_neighbours)


def frame_outcomes(frame: Frame, first: Frame, previous: Optional[Frame], materials: MaterialMap,
                   opts: OutcomeOptions, displacement: Optional[float] = None,
                   previous_displacement: Optional[float] = None) -> dict:
    """All outcomes of one frame (see the package docstring)."""
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
    order = np.argsort([fault_position(f) for f in faults], kind="stable")
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
                                              cols, tips, opts.deformed_fraction, opts.deformed_basal * L.d,
                                              opts.deformed_gap * L.d)
                              if inc else None)
    if opts.scene == "tilted":
        result["tilted"] = tilted_outcome(bands, faults, first, frame, materials, opts, L)
    return result


def _strong_of(field: StrainField, stats: dict) -> np.ndarray:
    return np.nan_to_num(field.max_shear, nan=0.0) > stats["threshold"]
