"""Outcomes of a scene run: the statements the reference paper makes by eye
about its Figs. 3-7, measured per frame.

For a frame, its first frame (finite strain, rigid motion, initial walls and
salt top) and the frame one increment earlier (incremental strain):

1. salt thickness profile, its minimum and where it lies relative to the
   basement fault tips and the footwall edge (``salt``, ``basement``);
2. welds (salt thinner than one salt-disc diameter);
3. relief of the salt-cover interface and whether a cover fault offsets it;
4. cover faults: localised bands of high maximum shear strain (``bands``),
   with their surface and interface positions, dip, sense, throw from the
   marker layers (``faults``);
5. rigid-block motion of the cover thirds, gaps, collapse and salt rise at
   the end walls (``walls``);
6. keystone: width of the deformed cover either side of the graben; tilted:
   rotation of the blocks between faults and the fault spacing (``scenes``);
7. salt flow character (Couette / Poiseuille, direction) from the salt bands
   (``flow``).

``frame_outcomes`` returns a JSON-ready dict; ``outcomes_markdown`` turns a
list of them into tables for the docs.  Methods and thresholds:
docs/outcomes.md.
"""

from .bands import (MAX_BANDS_PER_CLUSTER, Band, connected_clusters, detect_bands, extract_lines, fit_band_line,
                    fit_line, merge_bands, same_fault, strong_discs)
from .basement import BasementTip, basement_tips, block_displacements, block_slip, relative_to_tips
from .faults import CoverGeometry, describe_fault, marker_throw
from .flow import BandFlow, classify_flow, flow_regions, region_names, salt_band_flows
from .frame import cover_strain, frame_outcomes
from .geometry import Columns
from .markdown import outcomes_markdown
from .options import DIRECTIONS, SCENES, Lengths, OutcomeOptions
from .salt import interface_outcome, salt_outcome
from .scenes import block_rotations, deformed_widths
from .walls import cover_thirds, end_wall_outcome, wall_faces

__all__ = [
    "Band", "BandFlow", "BasementTip", "Columns", "CoverGeometry", "DIRECTIONS", "Lengths", "MAX_BANDS_PER_CLUSTER",
    "OutcomeOptions", "SCENES", "basement_tips", "block_displacements", "block_rotations", "block_slip",
    "classify_flow", "connected_clusters", "cover_strain", "cover_thirds", "deformed_widths", "describe_fault",
    "detect_bands", "end_wall_outcome", "extract_lines", "fit_band_line", "fit_line", "flow_regions",
    "frame_outcomes", "interface_outcome", "marker_throw", "merge_bands", "outcomes_markdown", "region_names",
    "relative_to_tips", "salt_band_flows", "salt_outcome", "same_fault", "strong_discs", "wall_faces",
]
