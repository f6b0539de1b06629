"""A section description (TOML) -> a plain LAMMPS deck on the scene includes.

A section is a box of salt and cover over a basement of rigid blocks separated by planar faults.
Its description names the box, the faults (where each cuts the top of the basement, its dip and
the side it dips toward), the blocks between them (left to right: their top, their kinematics and
their window of the drive), the end walls, the salt body (a layer, a thickness profile, a pillow)
and the run (preset defaults from examples/scene/params.in, target, rate, tilt, frames).
`build()` checks it and writes a deck that `lmp -in` runs like examples/expt1.in (same includes,
frames, restart files and outcomes); docs/sections.md is the user's page.
"""
from __future__ import annotations

import argparse
import math
import re
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from .checkout import repo


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


def _num(d: dict, key: str, where: str, default=None, positive=False):
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


def _known(d: dict, keys: set, where: str):
    unknown = set(d) - keys
    if unknown:
        raise SectionError(f"{where}: unknown key(s) {', '.join(sorted(unknown))}; "
                           f"known: {', '.join(sorted(keys))}")


def _value(v, where: str) -> float:
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


def parse(text: str, source: str = "section") -> Section:
    try:
        d = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise SectionError(f"{source}: not a valid description: {e}") from None
    _known(d, {"name", "title", "width", "target", "rate", "tilt", "frames", "salt", "cover",
               "fault", "block", "walls", "vars", "wedge", "tiny", "restart_every"}, source)
    name = d.get("name") or Path(source).stem
    if not isinstance(name, str) or not name.replace("_", "").isalnum():
        raise SectionError(f"{source}: name {name!r} must be letters, digits and _ (it names the frames)")
    width = _num(d, "width", source, positive=True)
    salt_d = d.get("salt")
    if not isinstance(salt_d, dict):
        raise SectionError(f"{source}: the [salt] table is missing (give thickness, or a profile)")
    _known(salt_d, {"thickness", "profile", "pillow"}, f"{source} [salt]")
    cover_d = d.get("cover")
    if not isinstance(cover_d, dict):
        raise SectionError(f"{source}: the [cover] table is missing (give its thickness)")
    _known(cover_d, {"thickness", "unit"}, f"{source} [cover]")
    cover = _num(cover_d, "thickness", f"{source} [cover]", positive=True)
    units = _units(cover_d.get("unit", []), cover, source)

    profile = None
    if "profile" in salt_d:
        try:
            profile = [(float(x), float(t)) for x, t in salt_d["profile"]]
        except (TypeError, ValueError):
            raise SectionError(f"{source} [salt]: profile must be a list of [x, thickness] pairs") from None
        if len(profile) < 2 or any(b[0] <= a[0] for a, b in zip(profile, profile[1:])):
            raise SectionError(f"{source} [salt]: profile needs 2 or more points with increasing x")
        if any(t < 0 for _, t in profile):
            raise SectionError(f"{source} [salt]: profile thickness must be >= 0 (0: pinched out)")
        if profile[0][0] > 0 or profile[-1][0] < width:
            raise SectionError(f"{source} [salt]: profile must span the box, x 0 to {width:g}")
    pillow = None
    if "pillow" in salt_d:
        p = salt_d["pillow"]
        if not isinstance(p, dict):
            raise SectionError(f"{source} [salt]: pillow must be a table {{x, width, height}}")
        _known(p, {"x", "width", "height"}, f"{source} [salt] pillow")
        pillow = {k: _num(p, k, f"{source} [salt] pillow", positive=(k != "x")) for k in ("x", "width", "height")}
        if pillow["x"] - pillow["width"] / 2 < 0 or pillow["x"] + pillow["width"] / 2 > width:
            raise SectionError(f"{source} [salt]: the pillow (x {pillow['x']:g} +- {pillow['width'] / 2:g} m) "
                               f"lies outside the box (0 to {width:g} m)")
    if profile is None and "thickness" not in salt_d:
        raise SectionError(f"{source} [salt]: give its thickness or a profile")
    # the nominal salt thickness (the box's height is it plus the cover): the layer's, or the
    # profile's largest; a pillow rises into the cover
    salt = max(t for _, t in profile) if profile else _num(salt_d, "thickness", f"{source} [salt]", positive=True)

    faults = []
    for k, fd in enumerate(d.get("fault", [])):
        where = f"{source} fault {k + 1}"
        _known(fd, {"name", "x", "dip", "toward"}, where)
        fname = fd.get("name", f"f{k + 1}")
        dip = _num(fd, "dip", where)
        if not 0 < dip <= 90:
            raise SectionError(f"{where} ({fname}): dip {dip:g} must be in (0, 90] degrees")
        toward = fd.get("toward", "right")
        if toward not in ("right", "left"):
            raise SectionError(f"{where} ({fname}): toward {toward!r} must be right or left")
        x = _num(fd, "x", where)
        if not 0 < x < width:
            raise SectionError(f"{where} ({fname}): x {x:g} lies outside the box (0 to {width:g} m)")
        faults.append(Fault(fname, x, dip, toward))
    if len({f.name for f in faults}) != len(faults):
        raise SectionError(f"{source}: two faults share a name")
    if any(b.x <= a.x for a, b in zip(faults, faults[1:])):
        raise SectionError(f"{source}: give the faults left to right (increasing x)")

    blocks = []
    for k, bd in enumerate(d.get("block", [])):
        where = f"{source} block {k + 1}"
        _known(bd, {"name", "top", "slip", "move", "rotate", "scale", "from", "to", "static", "tilt"}, where)
        b = Block(bd.get("name", f"block{k + 1}"))
        b.top = _num(bd, "top", where, 0.0)
        if b.top < 0:
            raise SectionError(f"{where} ({b.name}): top {b.top:g} must be >= 0 (the lowest block's top is 0)")
        b.static = bool(bd.get("static", False))
        if "slip" in bd:
            if bd["slip"] not in {f.name for f in faults}:
                raise SectionError(f"{where} ({b.name}): slip names fault {bd['slip']!r}, which is not given")
            b.slip = bd["slip"]
        if "move" in bd:
            b.move = tuple(_value(v, f"{where} ({b.name}) move") for v in bd["move"])
            if len(b.move) != 2:
                raise SectionError(f"{where} ({b.name}): move must be [vx, vy] (m per m of drive)")
        if "rotate" in bd:
            b.rotate = tuple(float(v) for v in bd["rotate"])
            if len(b.rotate) != 3:
                raise SectionError(f"{where} ({b.name}): rotate must be [px, py, degrees per m of drive]")
        if "tilt" in bd:
            b.tilt = _num(bd, "tilt", where)
            if not 0 < b.tilt < 0.2:
                raise SectionError(f"{where} ({b.name}): tilt {b.tilt:g} must be in (0, 0.2) degrees per m of drive")
        b.scale = _num(bd, "scale", where, 1.0)
        b.start = _num(bd, "from", where, 0.0)
        b.stop = _num(bd, "to", where, -1.0)
        if b.stop < 0:
            b.stop = None
        moving = b.slip or b.move or b.rotate or b.tilt
        if b.tilt and (b.slip or b.move or b.rotate or "from" in bd or "to" in bd or "scale" in bd):
            raise SectionError(f"{where} ({b.name}): a domino block (tilt) takes no other kinematics")
        if b.static and moving:
            raise SectionError(f"{where} ({b.name}): static and moving at once")
        if not b.static and not moving:
            raise SectionError(f"{where} ({b.name}): no kinematics: give slip = FAULT, move = [vx, vy], "
                               f"rotate = [px, py, w], tilt = W or static = true")
        blocks.append(b)
    if len(blocks) != len(faults) + 1:
        raise SectionError(f"{source}: {len(faults)} fault(s) cut the basement into {len(faults) + 1} "
                           f"blocks; {len(blocks)} are given (list them left to right)")
    if len({b.name for b in blocks}) != len(blocks):
        raise SectionError(f"{source}: two blocks share a name")

    s = Section(name=name, title=d.get("title", name), width=width, cover=cover, salt=salt,
                faults=faults, blocks=blocks, profile=profile, pillow=pillow, source=source, units=units)
    s.target = _num(d, "target", source, 1000.0, positive=True)
    if "rate" in d:
        s.rate = _num(d, "rate", source, positive=True)
    s.tilt = _num(d, "tilt", source, 0.0)
    if not -45 < s.tilt < 45:
        raise SectionError(f"{source}: tilt {s.tilt:g} must be in (-45, 45) degrees")
    walls = d.get("walls", {})
    _known(walls, {"left", "right", "right_move"}, f"{source} [walls]")
    s.left_wall = walls.get("left", "block")
    s.right_wall = walls.get("right", "block")
    if s.left_wall not in ("block", "static"):
        raise SectionError(f"{source} [walls]: left {s.left_wall!r} must be block or static")
    if s.right_wall not in ("block", "static", "move"):
        raise SectionError(f"{source} [walls]: right {s.right_wall!r} must be block, static or move")
    if "right_move" in walls:
        s.right_move = tuple(float(v) for v in walls["right_move"])
    if "frames" in d:
        s.frames = [float(v) for v in d["frames"]]
    s.extra_vars = dict(d.get("vars", {}))
    s.tiny = dict(d.get("tiny", {}))
    if "restart_every" in d:
        s.restart_every = _num(d, "restart_every", source, positive=True)
    if "wedge" in d:
        w = d["wedge"]
        where = f"{source} [wedge]"
        _known(w, {"front0", "rate", "load", "foreset_dip", "every"}, where)
        s.wedge = {"front0": _num(w, "front0", where, 0.0), "rate": _num(w, "rate", where, positive=True),
                   "load": _num(w, "load", where, positive=True),
                   "foreset_dip": _num(w, "foreset_dip", where, positive=True),
                   "every": _num(w, "every", where, positive=True)}
        if s.rate is not None:
            raise SectionError(f"{where}: the drive of a wedge is its front: give its rate here, not 'rate'")
        if not 0 <= s.wedge["front0"] < width:
            raise SectionError(f"{where}: front0 {s.wedge['front0']:g} lies outside the box (0 to {width:g} m)")
        if any(not b.static for b in blocks) or s.right_wall == "move":
            raise SectionError(f"{where}: a wedge section's basement is static (its drive is the front)")
    for b in blocks:
        if b.stop is not None and b.stop > s.target:
            raise SectionError(f"{source} block {b.name}: to {b.stop:g} is beyond the target {s.target:g} m")
        if b.start >= (b.stop if b.stop is not None else s.target):
            raise SectionError(f"{source} block {b.name}: from {b.start:g} must come before its end")
    _place_blocks(s)
    return s


def _units(items: list, cover: float, source: str) -> list:
    """The cover's units, top first; each unit's material is a cover params file (the deck's
    own, potentials/cover_paper.params, stays type 1; every other material gets a type)."""
    units, types = [], {}
    for k, u in enumerate(items):
        where = f"{source} [cover] unit {k + 1}"
        if not isinstance(u, dict):
            raise SectionError(f"{where}: give name, thickness and material")
        _known(u, {"name", "thickness", "material", "density"}, where)
        name = u.get("name", f"unit{k + 1}")
        if not str(name).replace("_", "").isalnum():
            raise SectionError(f"{where}: name {name!r} must be letters, digits and _")
        if "material" not in u:
            raise SectionError(f"{where} ({name}): no material file: give material = "
                               f"\"potentials/cover_paper.params\" or a calibrated file of your own")
        m = Path(u["material"])
        path = m if m.is_absolute() else (Path(source).resolve().parent / m)
        if not path.is_file():
            path = ROOT / m
        if not path.is_file():
            raise SectionError(f"{where} ({name}): material file {u['material']} not found "
                               f"(looked beside the description and in the repository)")
        unit = Unit(name, _num(u, "thickness", where, positive=True), path.resolve())
        if "density" in u:
            unit.density = _num(u, "density", where, positive=True)
        if unit.material != DEFAULT_MATERIAL.resolve():
            unit.type = types.setdefault(unit.material, 4 + len(types))
        _material(unit.material, where)
        units.append(unit)
    if units and abs(sum(u.thickness for u in units) - cover) > 1e-6 * cover:
        raise SectionError(f"{source} [cover]: its units add up to {sum(u.thickness for u in units):g} m, "
                           f"not the cover's {cover:g} m")
    if len({u.name for u in units}) != len(units):
        raise SectionError(f"{source} [cover]: two units share a name")
    return units


def _material(path: Path, where: str) -> dict:
    """NAME -> value text of a cover params file ('variable NAME_cover index VALUE')."""
    vals = {}
    for line in path.read_text().splitlines():
        m = re.match(r"\s*variable\s+(\w+)_cover\s+index\s+(\S+)", line)
        if m:
            vals[m.group(1)] = m.group(2)
    missing = [k for k in MATERIAL_KEYS if k not in vals]
    if missing:
        raise SectionError(f"{where}: material file {path.name} lacks {', '.join(k + '_cover' for k in missing)} "
                           f"(a cover params file, as potentials/cover_paper.params)")
    return vals


def _unit_lines(s: Section) -> tuple:
    """Deck lines: the unit materials' variables (top of the deck), the units' types and
    densities (fresh runs, after assembly), and the pair coefficients file (before the laws)."""
    own = sorted({u.type: u for u in s.units if u.type > 1}.items())
    head, assign, coeffs = [], [], []
    if not s.units:
        return head, assign, coeffs
    head.append(f"variable        extra_types index {2 + len(own)}")
    for t, u in own:
        head.append(f"# cover type {t}: {u.material.name}")
        for k, v in _material(u.material, u.name).items():
            if k not in MATERIAL_KEYS:
                continue
            v = re.sub(r"v_(\w+)_cover\b", lambda m: m.group(0) if m.group(1) == "rscale" else f"v_{m.group(1)}_u{t}", v)
            head.append(f"variable        {k}_u{t} index {v}")
    top = "v_H"
    for k, u in enumerate(s.units):
        low = f"{top}-{_fmt(u.thickness)}"
        cond = f"y>=$({low})" if k < len(s.units) - 1 else "y>-1e30"
        if k:
            cond += f"&&y<$({top})"
        assign += [f"variable        unit_{u.name} atom {cond}",
                   f"group           unit_{u.name}_y variable unit_{u.name}",
                   f"group           unit_{u.name} intersect unit_{u.name}_y cover",
                   f"group           unit_{u.name}_y delete"]
        if u.type > 1:
            assign.append(f"set             group unit_{u.name} type {u.type}")
        if u.density:
            assign.append(f"set             group unit_{u.name} density/disc {_fmt(u.density)}")
        top = low
    if own:
        # an interface is as weak (and as soft) as its weaker side: the smaller of each value
        def pair(a, b):
            ka = "cover" if a == 1 else f"u{a}"
            kb = f"u{b}"
            v = {k: (f"${{{k}_{kb}}}" if a == b else f"$(ternary(v_{k}_{ka}<v_{k}_{kb},v_{k}_{ka},v_{k}_{kb}))") for k in MATERIAL_KEYS}
            return (f"pair_coeff {a} {b} saltdem/cohesive {v['kn']} {v['kt']} {v['mu']} {v['coh']} {v['ten']} "
                    f"{v['rng']} damp {v['zn']} {v['zt']} rolling {v['kr']} {v['mur']}")
        types = [t for t, _ in own]
        for i, t in enumerate(types):
            coeffs.append(pair(t, t))
            coeffs.append(pair(1, t))
            for t2 in types[i + 1:]:
                coeffs.append(pair(t, t2))
            coeffs.append(f"pair_coeff 2 {t} ${{unit_salt}}")
            coeffs.append(f"pair_coeff {t} 3 saltdem/cohesive ${{kn_wall}} ${{kt_u{t}}} 1.0 ${{coh_u{t}}} 0 0")
    return head, assign, coeffs


def _place_blocks(s: Section):
    """Each block's base between its faults; faults may not cross inside the basement's travel."""
    xs = [0.0] + [f.x for f in s.faults] + [s.width]
    for b, lo, hi in zip(s.blocks, xs, xs[1:]):
        b.left, b.right = lo, hi
    faults = {f.name: f for f in s.faults}
    # two faults that dip toward each other meet at depth: below the block's top, within the depth
    # the blocks travel (the keystone must stay a wedge over the whole drive)
    for a, b in zip(s.faults, s.faults[1:]):
        if a.toward == "right" and b.toward == "left" and a.dip < 90 and b.dip < 90:
            depth = (b.x - a.x) / (1 / math.tan(math.radians(a.dip)) + 1 / math.tan(math.radians(b.dip)))
            if depth < s.target:
                raise SectionError(f"{s.source}: faults {a.name} and {b.name} cross {depth:.0f} m below the "
                                   f"basement top, within the {s.target:g} m the blocks travel; "
                                   f"move them apart or steepen them")
    for f, left, right in zip(s.faults, s.blocks, s.blocks[1:]):
        hanging, footwall = (right, left) if f.toward == "right" else (left, right)
        if hanging.top > footwall.top:
            raise SectionError(f"{s.source}: block {hanging.name}, the hanging wall of {f.name}, stands higher "
                               f"than its footwall {footwall.name}: give the step to the footwall")
    dom = [k for k, b in enumerate(s.blocks) if b.tilt]
    if dom:
        first = dom[0]
        if dom != list(range(first, len(s.blocks))) or first == 0 or not s.blocks[first - 1].static:
            raise SectionError(f"{s.source}: domino blocks (tilt) must be the last blocks, right of a static "
                               f"footwall block")
        fs = s.faults[first - 1:]
        if any(f.toward != "right" or f.dip != fs[0].dip for f in fs):
            raise SectionError(f"{s.source}: domino blocks need parallel faults that dip toward right "
                               f"(the same dip); mirror the section for faults dipping left")
        if len({s.blocks[k].tilt for k in dom}) != 1:
            raise SectionError(f"{s.source}: domino blocks turn together: give them the same tilt")
        if any(s.blocks[k].top != 0 for k in range(first - 1, len(s.blocks))):
            raise SectionError(f"{s.source}: domino blocks and their footwall need top = 0")
        theta = math.radians(s.blocks[first].tilt * s.target)
        if theta >= math.radians(fs[0].dip) - math.radians(10):
            raise SectionError(f"{s.source}: the domino blocks would tilt {math.degrees(theta):.0f} degrees, "
                               f"to within 10 degrees of their faults' dip {fs[0].dip:g}: lower tilt or target")
    del faults


def salt_top_formula(s: Section) -> Optional[str]:
    """An atom-style formula, nonzero for discs inside the salt body (None: the plain layer)."""
    if s.profile is None and s.pillow is None and all(b.top == 0 for b in s.blocks):
        return None
    terms = []
    if s.profile:
        for (x0, t0), (x1, t1) in zip(s.profile, s.profile[1:]):
            terms.append(f"(x>={x0:g})*(x<{x1:g})*({t0:g}+({t1 - t0:g})*(x-{x0:g})/{x1 - x0:g})")
        thick = "+".join(terms) + f"+(x>={s.profile[-1][0]:g})*{s.profile[-1][1]:g}"
    else:
        thick = f"{s.salt:g}"
    if s.pillow:
        p = s.pillow
        thick = (f"({thick})+{p['height'] / 2:g}*(1+cos(2*PI*(x-{p['x']:g})/{p['width']:g}))"
                 f"*(abs(x-{p['x']:g})<{p['width'] / 2:g})")
    return f"y<({base_top_formula(s)})+({thick})"


def base_top_formula(s: Section) -> str:
    """The basement top under x (the blocks' tops, stepped at the faults' cut points)."""
    parts = [f"(x>={b.left:g})*(x<{b.right:g})*{b.top:g}" for b in s.blocks if b.top != 0]
    return "+".join(parts) if parts else "0"


def _fmt(v: float) -> str:
    if isinstance(v, Expr):
        return f"$({v.text})"
    return f"{v:.12g}"


def _walls(s: Section) -> list:
    """saltdem/wall commands, block by block, in the order the paper's decks lay them."""
    lines = []
    wtop = "${wtop}" if s.wedge else "$(v_H+v_salt)"     # a wedge's walls reach above its load
    n = len(s.blocks)
    travel = f"v_target*{_fmt(max([1.0, _domino_slip(s)] + [abs(b.scale) for b in s.blocks]))}"
    for k, b in enumerate(s.blocks):
        g = b.name
        fl = s.faults[k - 1] if k > 0 else None          # the fault on its left
        fr = s.faults[k] if k < n - 1 else None          # the fault on its right
        # base: from its left end to its right end, short of a fault face it meets
        if fl is None:
            x0 = "$(-v_rw)"
        elif fl.toward == "right":                       # it is the hanging wall of fl
            x0 = f"$({_fmt(fl.x)}+v_rw)"
        else:                                            # footwall of a fault dipping left
            x0 = f"$({_fmt(fl.x)}+v_rw*(1-cos({_fmt(fl.dip)}*PI/180))/sin({_fmt(fl.dip)}*PI/180))"
        if fr is None:
            x1 = "$(v_width+v_rw)"
            if s.right_wall == "move":
                x1 = f"$(v_width+v_target*{_fmt(abs(s.right_move[0]))}+3*v_rw)"    # under the gap
        elif fr.toward == "right":                       # footwall of fr
            x1 = f"$({_fmt(fr.x)}-v_rw*(1-cos({_fmt(fr.dip)}*PI/180))/sin({_fmt(fr.dip)}*PI/180))"
        else:
            x1 = f"$({_fmt(fr.x)}-v_rw)"
        y = f"$({_fmt(b.top)}-v_rw)"
        lines.append(f"saltdem/wall    3 {x0} {y} {x1} {y} ${{rw}} group {g}")
        if k == 0:
            lw = g if s.left_wall == "block" else "wall_left"
            lines.append(f"saltdem/wall    3 $(-v_rw) $({_fmt(b.top)}+v_rw) $(-v_rw) {wtop} ${{rw}} group {lw}")
        if k == n - 1 and s.right_wall == "block" and b.tilt:
            lines.append(f"saltdem/wall    3 $(v_width+v_rw) $({_fmt(b.top)}+v_rw) $(v_width+v_rw) "
                         f"{wtop} ${{rw}} group wall_right")
        elif k == n - 1 and s.right_wall == "block":
            lines.append(f"saltdem/wall    3 $(v_width+v_rw) $({_fmt(b.top)}+v_rw) $(v_width+v_rw) "
                         f"{wtop} ${{rw}} group {g}")
        # the face it exposes: the footwall lines its fault face from its top down-dip
        for f, side in ((fl, "left"), (fr, "right")):
            if f is None:
                continue
            footwall = (side == "right" and f.toward == "right") or (side == "left" and f.toward == "left")
            if not footwall:
                continue
            sd, cd = f"sin({_fmt(f.dip)}*PI/180)", f"cos({_fmt(f.dip)}*PI/180)"
            # the face starts a disc inside the footwall's corner and runs down-dip
            back, down = ("-", "+") if f.toward == "right" else ("+", "-")
            top = _fmt(b.top)
            other = s.blocks[k + 1] if side == "right" else s.blocks[k - 1]
            if b.static and other.static:     # a static step: lined down to the lower block
                lface = f"(2*v_dw+{_fmt(b.top - other.top)})"
            else:
                lface = f"({travel}+2*v_dw+{top})"
            lines.append(f"saltdem/wall    3 $({_fmt(f.x)}{back}v_rw*{sd}) $({top}-v_rw*{cd}) "
                         f"$({_fmt(f.x)}{back}v_rw*{sd}{down}{lface}*{cd}) $({top}-v_rw*{cd}-{lface}*{sd}) "
                         f"${{rw}} group {g}")
    if s.right_wall in ("static", "move"):
        lines.append("saltdem/wall    3 $(v_width+v_rw) $(v_rw) $(v_width+v_rw) $(v_H+v_salt) ${rw} group wall_right")
    return lines


DOMINO_PHASES = 20


def _domino_args(s: Section) -> list:
    """Bookshelf (domino) blocks: each turns counterclockwise by theta about its crest (its top
    right corner, which stays at the basement top) and moves right by e_k(theta), so that its
    hanging-wall corner slides down the face of the block to its left (static for the first,
    turned by theta for the others).  The exact path, cut into DOMINO_PHASES phases of equal
    turn, each exact at its ends (a turn about the moving crest and a uniform translation)."""
    dom = [b for b in s.blocks if b.tilt]
    first = s.blocks.index(dom[0])
    dip = s.faults[first - 1].dip
    w = dom[0].tilt
    n = DOMINO_PHASES

    def e(k, th):                      # k: index into dom; th: an expression in radians
        terms = []
        for m in range(k + 1):
            b = dom[m]
            L = _fmt(b.right - b.left)
            deff = f"({_fmt(dip)}*PI/180)" if m == 0 else f"({_fmt(dip)}*PI/180-{th})"
            terms.append(f"{L}*(cos({th})-1+sin({th})*cos({deff})/sin({deff}))")
        return "+".join(terms)

    out = []
    for j in range(n):
        ta = f"({_fmt(w)}*PI/180*v_target*{j}/{n})"
        tb = f"({_fmt(w)}*PI/180*v_target*{j + 1}/{n})"
        d0 = f"$(v_target*{j}/{n})" if j else "0"
        d1 = f"$(v_target*{j + 1}/{n})"
        for k, b in enumerate(dom):
            vx = f"$(({e(k, tb)}-({e(k, ta)}))/(v_target/{n}))"
            px = f"$({_fmt(b.right)}+{e(k, ta)})"
            out.append(f"block {b.name} rotate {px} 0 {_fmt(w)} move {vx} 0 from {d0} to {d1}")
            if b is s.blocks[-1]:     # the end wall rides on the last crest, upright
                out.append(f"block wall_right move {vx} 0 from {d0} to {d1}")
    return out


def _domino_slip(s: Section) -> float:
    """The largest slip on a domino fault per m of drive at the section's target."""
    dom = [b for b in s.blocks if b.tilt]
    if not dom:
        return 0.0
    first = s.blocks.index(dom[0])
    d = math.radians(s.faults[first - 1].dip)
    th = math.radians(dom[0].tilt * s.target)
    return max((b.right - b.left) * math.sin(th) / math.sin(d - th * (k > 0))
               for k, b in enumerate(dom)) / s.target


def _block_args(s: Section) -> list:
    faults = {f.name: f for f in s.faults}
    out = []
    if any(b.tilt for b in s.blocks):
        out += _domino_args(s)
    for b in s.blocks:
        if b.static or b.tilt:
            continue
        words = [f"block {b.name}"]
        if b.slip:
            f = faults[b.slip]
            words.append(f"slip {_fmt(f.dip)} {f.toward}")
        if b.move:
            words.append(f"move {_fmt(b.move[0])} {_fmt(b.move[1])}")
        if b.rotate:
            words.append(f"rotate {_fmt(b.rotate[0])} {_fmt(b.rotate[1])} {_fmt(b.rotate[2])}")
        if b.scale != 1.0:
            words.append(f"scale {_fmt(b.scale)}")
        if b.start:
            words.append(f"from {_fmt(b.start)}")
        if b.stop is not None:
            words.append(f"to {_fmt(b.stop)}")
        out.append(" ".join(words))
    if s.right_wall == "move":
        out.append(f"block wall_right move {_fmt(s.right_move[0])} {_fmt(s.right_move[1])}")
    return out


def deck(s: Section) -> str:
    """The plain LAMMPS deck of section s."""
    faults = {f.name: f for f in s.faults}
    moving = [b.name for b in s.blocks if not b.static] + (
        ["wall_right"] if s.right_wall == "move" or s.blocks[-1].tilt else [])
    if not moving and not s.wedge:
        raise SectionError(f"{s.source}: nothing moves: give a block (or the right wall) kinematics, or a [wedge]")
    # the room the blocks travel into: the fastest block's travel, toward each side it goes
    vel = [b.velocity(faults) for b in s.blocks if not b.static and not b.tilt]
    if s.right_wall == "move":
        vel.append(tuple(v * 1.0 for v in s.right_move))
    speed = max([1.0 if not moving else 0.0] + [math.hypot(*v) for v in vel])
    for b in s.blocks:
        if b.tilt:       # a domino block: its crest moves right, its far side turns
            reach = max(b.right - b.left, s.cover + s.salt)
            speed = max(speed, 2 * math.radians(b.tilt) * reach)
        if b.rotate:     # a turning block's far end moves by its turn times its reach
            reach = max(abs(b.left - b.rotate[0]), abs(b.right - b.rotate[0]), abs(b.top - b.rotate[1]))
            speed = max(speed, math.hypot(*b.velocity(faults)) + math.radians(abs(b.rotate[2] * b.scale)) * reach)
    travel = f"${{target}}*{_fmt(speed)}"
    rot = any(b.rotate or b.tilt for b in s.blocks)
    right_x = travel if rot or any(v[0] > 0 for v in vel) else "0"
    left_x = travel if rot or any(v[0] < 0 for v in vel) else "0"
    down = travel if rot or any(v[1] < 0 for v in vel) else "0"
    sf = salt_top_formula(s)
    L = [f"# SaltDEM section '{s.name}': {s.title}",
         f"# Written by python/saltdem-section from {Path(s.source).name}; edit the description and",
         "# write it again rather than editing this deck.",
         "#",
         f"#   lmp -in {s.name}.in -var root <repository> -var preset quick",
         "#",
         f"# Output as examples/expt1.in: frames dump.{s.name}.STEP.txt, restart {s.name}.restart.a/b.",
         f"# Figure: python/saltdem-post figure 'dump.{s.name}.*.txt' "
         + (f"--fault-x {' '.join(_fmt(f.x) for f in s.faults)} " if s.faults else "")
         + "--at 100 250 500 750 1000",
         "",
         "variable        root        index .",
         ] + (["variable        preset      index full",
               'if "${preset} == tiny" then ' + " ".join(f'"variable {k} index {v}"' for k, v in s.tiny.items())]
              if s.tiny else []) + [
         f"variable        width       index {_fmt(s.width)}",
         f"variable        salt        index {_fmt(s.salt)}",
         f"variable        cover       index {_fmt(s.cover)}"]
    # the section's drive, except at the tiny preset (its smoke-test drive: 2 m at 2 m/s)
    drive = []
    if s.wedge:
        w = s.wedge
        L += [f"variable        front0      index {_fmt(w['front0'])}",
              f"variable        front_rate  index {_fmt(w['rate'])}",
              f"variable        load        index {_fmt(w['load'])}",
              f"variable        foreset_dip index {_fmt(w['foreset_dip'])}"]
        drive.append("variable rate index ${front_rate}")
    if s.target != 1000.0:
        drive.append(f"variable target index {_fmt(s.target)}")
    if s.rate is not None:
        drive.append(f"variable rate index {_fmt(s.rate)}")
    if s.frames:
        drive.append(f"variable f index {' '.join(_fmt(v) for v in s.frames)}")
    if s.restart_every:
        drive.append(f"variable restart_disp index {_fmt(s.restart_every)}")
    if s.wedge:
        drive.append(f"variable sed_every index {_fmt(s.wedge['every'])}")
    if drive:
        L += (["variable        preset      index full"] if not s.tiny else []) + [
              'if "${preset} != tiny" then ' + " ".join(f'"{d}"' for d in drive)]
    for k, v in s.extra_vars.items():
        L.append(f"variable        {k} index {v}")
    uhead, uassign, ucoeffs = _unit_lines(s)
    L += ["include         ${root}/examples/scene/params.in"] + uhead + [
          "# the preset must resolve the section: a disc radius across salt and cover, ten along it",
          f'if "${{salt}} < ${{rmax}} || ${{cover}} < ${{rmax}} || ${{width}} < $(10*v_rmax)" then &',
          f"  \"print 'section {s.name}: preset ${{preset}} cannot pack it: salt ${{salt}} m, cover ${{cover}} m "
          f"and width ${{width}} m need 1, 1 and 10 radii of its largest discs (${{rmax}} m); use a finer "
          f"preset'\" \"quit 1\"",
          "",
          "# the box leaves room for the blocks to travel the target displacement",
          f"variable        bxlo equal -3*${{rmax}}-{left_x}",
          f"variable        bxhi equal ${{width}}+3*${{rmax}}+{right_x}"]
    if s.wedge:     # room above for the load and the salt it expels
        L += ["variable        bylo equal -6*${rmax}",
              "variable        byhi equal ${salt}+${cover}+${load}+${salt}+6*${rmax}"]
    else:
        L += [(f"variable        bylo equal -{down}-6*${{rmax}}" if down != "0"
               else "variable        bylo equal -3*${rmax}"),
              "variable        byhi equal 1.5*(${salt}+${cover})"]
    L += ['if "${resuming}" then "jump SELF resume"']
    if sf is not None:
        L += ["# the salt body, and the basement discs under the blocks' tops (deleted)",
              "variable        has_saltbody index 1",
              f'variable        saltbody string "{sf}"']
        if any(b.top != 0 for b in s.blocks):
            L += ["variable        has_basement index 1",
                  f'variable        basement string "y-radius<({base_top_formula(s)})"']
    L += ["include         ${root}/examples/scene/assembly.in"]
    if uassign:
        L += ["# the cover's units, top first"] + uassign
    if s.wedge:
        L.append("variable        wtop equal ${H}+${load}+${salt}")
    L += ["",
          "# ---- basement: wall discs (type 3), block by block ---------------------------------------------"]
    L += _walls(s)
    L += ["jump            SELF laws",
          "label           resume",
          "include         ${root}/examples/scene/resume.in",
          "label           laws"]
    if s.tilt:
        L.append(f"fix             grav pack gravity 9.81 vector $(sin({_fmt(s.tilt)}*PI/180)) "
                 f"$(-cos({_fmt(s.tilt)}*PI/180)) 0")
    else:
        L.append("fix             grav pack gravity 9.81 vector 0 -1 0")
    if ucoeffs:
        if any(u.type > 1 for u in s.units):
            L += ["# the cover units' own materials: their pair coefficients, which laws.in reads",
                  'if "${endwall} != rough" then "print \'section: cover units take endwall rough\'" "quit 1"',
                  'if "${saltlaw} == sph" then &',
                  '  "variable unit_salt string \'saltdem/viscous ${eta} ${kn_cs} fluid $(1.3*sqrt(PI*v_r2salt/0.85)) ${K_salt}\'" &',
                  'else "variable unit_salt string \'saltdem/viscous ${eta} ${kn_wall} contact 0\'"',
                  'print           """']
            L += ucoeffs
            L += [f'""" file {s.name}.units.in screen no',
                  "variable        has_laws_hook index 1",
                  f"variable        laws_hook index {s.name}.units.in"]
    L += ["include         ${root}/examples/scene/laws.in", ""]
    if s.wedge:
        L += ["# ---- the front: migration starts after the settling (model time 0 from here) ---------------",
              'if "${resuming} == 0" then "reset_timestep 0 time 0"',
              "variable        disp equal ${rate}*time",
              "variable        front equal ${front0}+v_disp",
              f"variable        name index {s.name}",
              'variable        progress index "v_front"',
              "# sedimentation behind the front: fill to the base level from the box's left end to the",
              "# front, and a foreset ahead of it",
              "variable        sediment index fill",
              "variable        base_level index $(v_H+v_load)",
              "variable        sed_xlo index $(v_bxlo)",
              "variable        sed_xhi index v_front",
              "variable        sed_foreset index $(tan(v_foreset_dip*PI/180))",
              "include         ${root}/examples/scene/sediment.in",
              "include         ${root}/examples/scene/frames.in",
              ""]
        return "\n".join(L)
    L += ["# ---- the basement moves ---------------------------------------------------------------------"]
    if len(moving) > 1:
        L.append(f"group           moving union {' '.join(moving)}")
        grp = "moving"
    else:
        grp = moving[0]
    args = _block_args(s)
    L.append(f"fix             blocks {grp} saltdem/blocks rate ${{rate}} target ${{target}} &")
    for k, a in enumerate(args):
        L.append(f"                {a}" + (" &" if k < len(args) - 1 else ""))
    if s.tilt:
        # the tilted gravity from here on, after the motion (the order examples/expt3.in has)
        L += ["unfix           grav",
              f"fix             grav pack gravity 9.81 vector $(sin({_fmt(s.tilt)}*PI/180)) "
              f"$(-cos({_fmt(s.tilt)}*PI/180)) 0"]
    L += ["variable        disp equal f_blocks[1]",
          f"variable        name index {s.name}",
          'variable        progress index "' + " ".join(f"f_blocks[{k + 1}][3]" for k in range(len(moving))) + '"',
          "include         ${root}/examples/scene/sediment.in    # off unless -var sediment / erosion_level",
          "include         ${root}/examples/scene/frames.in",
          ""]
    return "\n".join(L)


def build(path: Path) -> str:
    s = parse(Path(path).read_text(), str(path))
    return deck(s)


USAGE = """Write the LAMMPS deck of a section description (docs/sections.md).

  saltdem-section SECTION.toml [-o DECK.in]   write the deck (default: NAME.in here)
  saltdem-section SECTION.toml --check        check the description, write nothing

Then: lmp -in DECK.in -var root <repository> -var preset quick
"""


def main(argv=None):
    ap = argparse.ArgumentParser(prog="saltdem-section", description=USAGE,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("section", type=Path, help="the section description (TOML)")
    ap.add_argument("-o", "--output", type=Path, help="the deck to write (default: NAME.in)")
    ap.add_argument("--check", action="store_true", help="check the description only")
    ap.add_argument("--faults", action="store_true",
                    help="print where the faults cut the basement top (x, m), for saltdem-post --fault-x")
    ap.add_argument("--types", action="store_true",
                    help="print the type map of its frames, for saltdem-post --types")
    a = ap.parse_args(argv)
    try:
        text = a.section.read_text()
    except OSError as e:
        print(f"saltdem-section: cannot read {a.section}: {e.strerror}", file=sys.stderr)
        return 2
    try:
        s = parse(text, str(a.section))
        out = deck(s)
    except SectionError as e:
        print(f"saltdem-section: {e}", file=sys.stderr)
        return 1
    if a.faults:
        print(" ".join(f"{f.x:g}" for f in s.faults))
        return 0
    if a.types:
        print("cover=" + ",".join(str(t) for t in sorted({1} | {u.type for u in s.units})) + ";salt=2;wall=3")
        return 0
    if a.check:
        print(f"saltdem-section: {a.section}: section '{s.name}' is fine "
              f"({len(s.faults)} fault(s), {len(s.blocks)} block(s))")
        return 0
    dest = a.output or Path(f"{s.name}.in")
    dest.write_text(out)
    print(f"saltdem-section: wrote {dest}")
    return 0


