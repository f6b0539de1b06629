"""A section description (TOML) -> a plain LAMMPS deck on the scene includes.

A section is a box of salt and cover over a basement of rigid blocks separated by planar faults.
Its description names the box, the faults (where each cuts the top of the basement, its dip and
the side it dips toward), the blocks between them (left to right: their top, their kinematics and
their window of the drive), the end walls, the salt body (a layer, a thickness profile, a pillow)
and the run (preset defaults from examples/scene/params.in, target, rate, tilt, frames).
`build()` checks it and writes a deck that `lmp -in` runs like examples/expt1.in (same includes,
frames, restart files and outcomes); docs/sections.md is the user's page.
"""
from .cli import build, main
from .deck import deck
from .describe import parse
from .model import Block, Fault, Section, SectionError, Unit

__all__ = ["Block", "Fault", "Section", "SectionError", "Unit", "build", "deck", "main", "parse"]
