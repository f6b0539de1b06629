"""Synthetic scenes with known answers, written in the decks' dump format.

Used by the tests and to make the small fixture in ``tests/python/data``:
a hexagonal packing of discs -- basement (wall) row, salt layer, cover -- cut
by a basement normal fault.  Each frame is a prescribed, smooth deformation
(a fault-propagation monocline over the fault plus a Couette + Poiseuille
flow in the salt) so velocities and displacements are known exactly.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

import numpy as np

from .dump import Box, Frame, write_dump

COVER, SALT, WALL = 1, 2, 3


@dataclass
class SceneSpec:
    width: float = 2000.0            # m
    salt_thickness: float = 240.0    # m
    cover_thickness: float = 360.0   # m
    r_max: float = 25.0              # m, discs have r in [0.8, 1] r_max
    fault_x: float = 1000.0          # m, where the fault cuts the top of the basement
    fault_dip: float = 60.0          # degrees, dipping towards +x (hanging wall on the right)
    marker_spacing: float = 60.0     # m
    couette: float = 0.4             # salt-top displacement per metre of fault slip
    poiseuille: float = 0.3          # extra mid-salt displacement per metre of slip
    slip_rate: float = 1e-9          # m/s of fault slip
    metres_per_step: float = 0.01    # fault slip per timestep
    seed: int = 1

    @property
    def salt_top(self) -> float:
        return self.salt_thickness


def reference_scene(spec: SceneSpec = SceneSpec()) -> Frame:
    """Undeformed layered packing (y = 0 is the top of the basement)."""
    rng = np.random.default_rng(spec.seed)
    a = 2.0 * spec.r_max                                    # lattice spacing: discs never overlap
    dy = a * np.sqrt(3.0) / 2.0
    rows = np.arange(-1, int((spec.salt_thickness + spec.cover_thickness) / dy))
    xs, ys = [], []
    for k in rows:
        x = np.arange(spec.r_max + (a / 2 if k % 2 else 0.0), spec.width - spec.r_max + 1e-9, a)
        xs.append(x)
        ys.append(np.full(len(x), spec.r_max + k * dy))
    x, y = np.concatenate(xs), np.concatenate(ys)
    r = spec.r_max * rng.uniform(0.8, 1.0, len(x))
    typ = np.where(y < 0, WALL, np.where(y < spec.salt_top, SALT, COVER))
    marker = np.where(typ == COVER, np.floor((y - spec.salt_top) / spec.marker_spacing),
                      np.where(typ == SALT, np.floor(x / spec.marker_spacing), 0)).astype(np.int64)
    n = len(x)
    box = Box(np.array([0.0, -2 * spec.r_max, -0.5]),
              np.array([spec.width, spec.salt_thickness + spec.cover_thickness + 4 * spec.r_max, 0.5]),
              boundary=("ff", "ff", "pp"))
    data = {"id": np.arange(1, n + 1), "type": typ, "x": x, "y": y,
            "vx": np.zeros(n), "vy": np.zeros(n), "radius": r, "i_marker": marker}
    return Frame(0, box, data)


def salt_flow(spec: SceneSpec, y_ref: np.ndarray) -> np.ndarray:
    """Horizontal salt displacement per metre of slip: Couette + Poiseuille."""
    eta = np.clip(y_ref / spec.salt_thickness, 0.0, 1.0)
    return spec.couette * eta + spec.poiseuille * 4.0 * eta * (1.0 - eta)


def displacement_per_slip(spec: SceneSpec, ref: Frame) -> np.ndarray:
    """Displacement of every disc per metre of fault slip (linear in slip)."""
    x, y, typ = ref.x, ref.y, ref["type"]
    dip = np.radians(spec.fault_dip)
    slip_dir = np.array([np.cos(dip), -np.sin(dip)])          # hanging wall down-dip
    # Basement: rigid blocks either side of the fault plane.
    fault_at_y = spec.fault_x - y / np.tan(dip)
    s = (x > fault_at_y).astype(float)
    # Salt and cover: a monocline that widens upwards over the fault tip.
    soft = typ != WALL
    width = 40.0 + 0.5 * np.maximum(y, 0.0)
    s[soft] = 0.5 * (1.0 + np.tanh((x[soft] - spec.fault_x) / width[soft]))
    u = s[:, None] * slip_dir[None, :]
    u[typ == SALT, 0] += salt_flow(spec, y[typ == SALT])
    u[typ == COVER, 0] += spec.couette                       # cover rides on the salt top
    return u


def scene_frames(slips: Sequence[float], spec: SceneSpec = SceneSpec(), shuffle: bool = True) -> List[Frame]:
    """Frames at the given fault slips (m), atoms in random order like LAMMPS."""
    ref = reference_scene(spec)
    per_slip = displacement_per_slip(spec, ref)
    rng = np.random.default_rng(spec.seed + 1)
    frames = []
    for k, slip in enumerate(slips):
        data = dict(ref.data)
        data["x"] = ref.x + slip * per_slip[:, 0]
        data["y"] = ref.y + slip * per_slip[:, 1]
        data["vx"] = spec.slip_rate * per_slip[:, 0]
        data["vy"] = spec.slip_rate * per_slip[:, 1]
        order = rng.permutation(ref.natoms) if shuffle else np.arange(ref.natoms)
        frame = Frame(int(round(slip / spec.metres_per_step)), ref.box, {c: v[order] for c, v in data.items()})
        frame.index = k
        frames.append(frame)
    return frames


def displaced(frame: Frame, mask: np.ndarray, u, timestep: Optional[int] = None) -> Frame:
    """A copy of ``frame`` with the discs of ``mask`` moved by ``u`` (a 2-vector or N x 2)."""
    data = dict(frame.data)
    u = np.broadcast_to(np.asarray(u, float), (int(np.count_nonzero(mask)), 2))
    for axis, name in enumerate("xy"):
        col = frame.data[name].astype(float).copy()
        col[mask] += u[:, axis]
        data[name] = col
    return Frame(frame.timestep if timestep is None else timestep, frame.box, data, frame.path, frame.index,
                 frame.time)


def planted_cover_fault(spec: SceneSpec, x_interface: float, dip: float, throw: float,
                        direction: str = "right") -> Tuple[Frame, Frame]:
    """The reference scene and a copy in which a planar cover fault has
    slipped: the fault meets the salt-cover interface at ``x_interface``,
    dips ``dip`` degrees towards ``direction`` (right: +x), and its
    hanging-wall cover has moved down-dip by ``throw / sin(dip)`` (salt and
    basement stay).  The fault's surface trace is at
    ``x_interface -/+ cover_thickness / tan(dip)``."""
    ref = reference_scene(spec)
    a = np.radians(dip)
    sign = 1.0 if direction == "right" else -1.0
    plane_x = x_interface - sign * (ref.y - spec.salt_top) / np.tan(a)
    hanging = (ref["type"] == COVER) & (sign * (ref.x - plane_x) > 0)
    slip = throw / np.sin(a)
    cur = displaced(ref, hanging, slip * np.array([sign * np.cos(a), -np.sin(a)]), timestep=1000)
    cur.index = 1
    return ref, cur


def write_fixture(path: str, slips: Sequence[float] = (0.0, 50.0, 100.0, 150.0),
                  spec: SceneSpec = SceneSpec()) -> List[Frame]:
    """Write the small test scene (multi-frame, gzip if ``*.gz``)."""
    frames = scene_frames(slips, spec)
    write_dump(path, frames)
    return frames
