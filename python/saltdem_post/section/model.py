"""The section model: faults, blocks, cover units and the section, and the checks of single
values (numbers, known keys, formulas)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from ..checkout import repo


class SectionError(ValueError):
    """A description that cannot be built; the message names the problem and the fix."""


@dataclass
class Fault:
    name: str
    x: float
    dip: float
    toward: str        # right: dips toward +x (its hanging wall is the block to its right)

    @property
    def sense(self) -> float:
        return 1.0 if self.toward == "right" else -1.0


@dataclass
class Block:
    name: str
    top: float = 0.0
    slip: Optional[str] = None           # the fault it slides down
    move: Optional[tuple] = None         # (vx, vy) per m of drive
    rotate: Optional[tuple] = None       # (px, py, degrees per m of drive)
    scale: float = 1.0
    start: float = 0.0
    stop: Optional[float] = None
    static: bool = False
    tilt: Optional[float] = None         # domino: degrees of tilt per m of drive (bookshelf)
    left: float = 0.0                    # x extent of its base (set from the faults)
    right: float = 0.0

    def velocity(self, faults: dict) -> tuple:
        vx = vy = 0.0
        if self.slip:
            f = faults[self.slip]
            a = f.dip * math.pi / 180.0
            vx, vy = f.sense * math.cos(a), -math.sin(a)
        if self.move:
            vx, vy = vx + self.move[0], vy + self.move[1]
        return vx * self.scale, vy * self.scale


@dataclass
class Unit:
    name: str
    thickness: float
    material: Path
    density: Optional[float] = None
    type: int = 1                        # 1: the deck's own cover material; 4, 5, ...: its own


ROOT = repo()
DEFAULT_MATERIAL = ROOT / "potentials" / "cover_paper.params"
MATERIAL_KEYS = ("kn", "kt", "mu", "coh", "ten", "rng", "zn", "zt", "kr", "mur")


@dataclass
class Section:
    name: str
    title: str
    width: float
    cover: float
    salt: float                          # the thickness of the salt layer (the nominal: its max)
    faults: list
    blocks: list
    target: float = 1000.0
    rate: Optional[float] = None
    tilt: float = 0.0
    left_wall: str = "block"             # block: rides with the first block; static
    right_wall: str = "block"            # block, static, or move: a wall of its own
    right_move: tuple = (1.0, 0.0)
    profile: Optional[list] = None       # [(x, thickness)] of the salt
    pillow: Optional[dict] = None        # {x, width, height}
    frames: Optional[list] = None
    source: str = ""
    extra_vars: dict = field(default_factory=dict)
    units: list = field(default_factory=list)   # cover units, from the top down
    wedge: Optional[dict] = None         # a prograding sediment wedge: the drive is its front
    tiny: dict = field(default_factory=dict)    # variables at the tiny preset only
    restart_every: Optional[float] = None

    @property
    def faults_by_name(self) -> dict:
        return {f.name: f for f in self.faults}


def number(d: dict, key: str, where: str, default=None, positive=False):
    if key not in d:
        if default is None:
            raise SectionError(f"{where}: '{key}' is missing")
        return default
    v = d[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise SectionError(f"{where}: '{key}' = {v!r} must be a number")
    if positive and v <= 0:
        raise SectionError(f"{where}: '{key}' = {v} must be > 0")
    return float(v)


def check_keys(d: dict, keys: set, where: str):
    unknown = set(d) - keys
    if unknown:
        raise SectionError(f"{where}: unknown key(s) {', '.join(sorted(unknown))}; "
                           f"known: {', '.join(sorted(keys))}")


def formula_value(v, where: str) -> float:
    """A number, or a formula of the LAMMPS deck language such as "2*cos(60*PI/180)"."""
    if isinstance(v, str):
        try:
            x = float(eval(v.replace("^", "**"), {"__builtins__": {}},
                           {"PI": math.pi, "cos": math.cos, "sin": math.sin, "tan": math.tan,
                            "sqrt": math.sqrt}))
        except Exception:
            raise SectionError(f"{where}: {v!r} is not a number or a formula of PI, cos, sin, tan, sqrt") from None
        return Expr(x, v)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise SectionError(f"{where}: {v!r} must be a number")
    return float(v)


class Expr(float):
    """A number given as a formula: the deck writes the formula (LAMMPS evaluates it)."""

    def __new__(cls, value, text):
        obj = super().__new__(cls, value)
        obj.text = text
        return obj


