"""The outcome options and their lengths in metres for one frame."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Tuple

from ..dump import Frame
from ..materials import DEFAULT_MARKER_COLUMN, MaterialMap
from ..measure import median_diameter

SCENES = ("fault", "keystone", "tilted")
DIRECTIONS = ("left", "right")

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
    deformed_basal: float = 3.0              # keystone: ... above its lowest this many disc diameters
    deformed_gap: float = 3.0                # keystone: the zone from the graben, gaps of at most this many d

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
        d = median_diameter(frame, materials.mask(types, "cover"))
        d_salt = median_diameter(frame, materials.mask(types, "salt"))

        def pick(value, multiple, unit=d):
            return float(value) if value is not None else multiple * unit
        return cls(d, d_salt, pick(opts.link, 2.0), pick(opts.band_halfwidth, 2.0), pick(opts.min_length, 6.0),
                   pick(opts.wall_margin, 3.0), pick(opts.tip_tolerance, 3.0), pick(opts.marker_window, 5.0),
                   pick(opts.flow_min, 1.0, d_salt), pick(opts.collapse_drop, 2.0))
