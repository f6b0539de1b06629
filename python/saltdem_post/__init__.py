"""SaltDEM post-processing: read the package's LAMMPS dumps frame by frame and
turn them into strain fields, salt-thickness and flow measurements, and
paper-style figures.  Command line: ``saltdem-post`` (see ``cli``); the
calibration of materials is the subpackage ``calibration``
(``saltdem-calibrate``).  ``checkout`` finds the SaltDEM checkout and its
``lmp``; ``channel`` and ``rayleigh_taylor`` read the validation runs that
bench/ and tests/ share."""

__version__ = "0.1.0"

from .dump import (Box, Frame, FrameSelection, expand_paths, iter_frames, read_ave_chunk, read_ave_time,  # noqa: E402
                   read_frame, scan_frames, write_dump)
from .materials import MaterialMap, markers  # noqa: E402
from .measure import fault_displacement, fit_couette_poiseuille, salt_thickness, vertical_profile  # noqa: E402
from .strain import StrainField, strain_between  # noqa: E402

__all__ = [
    "Box", "Frame", "FrameSelection", "expand_paths", "iter_frames", "read_ave_chunk", "read_ave_time",
    "read_frame", "scan_frames", "write_dump",
    "MaterialMap", "markers", "fault_displacement", "fit_couette_poiseuille", "salt_thickness",
    "vertical_profile", "StrainField", "strain_between",
]
