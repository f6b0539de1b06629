"""Reading a section description (TOML) into a Section, with every check that names the
problem before anything is written."""
from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

from .model import (DEFAULT_MATERIAL, MATERIAL_KEYS, ROOT, Block, Fault, Section, SectionError, Unit, check_keys, number,
                    formula_value)


def parse(text: str, source: str = "section") -> Section:
    try:
        d = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise SectionError(f"{source}: not a valid description: {e}") from None
    check_keys(d, {"name", "title", "width", "target", "rate", "tilt", "frames", "salt", "cover",
               "fault", "block", "walls", "vars", "wedge", "tiny", "restart_every"}, source)
    name = d.get("name") or Path(source).stem
    if not isinstance(name, str) or not name.replace("_", "").isalnum():
        raise SectionError(f"{source}: name {name!r} must be letters, digits and _ (it names the frames)")
    width = number(d, "width", source, positive=True)
    salt_d = d.get("salt")
    if not isinstance(salt_d, dict):
        raise SectionError(f"{source}: the [salt] table is missing (give thickness, or a profile)")
    check_keys(salt_d, {"thickness", "profile", "pillow"}, f"{source} [salt]")
    cover_d = d.get("cover")
    if not isinstance(cover_d, dict):
        raise SectionError(f"{source}: the [cover] table is missing (give its thickness)")
    check_keys(cover_d, {"thickness", "unit"}, f"{source} [cover]")
    cover = number(cover_d, "thickness", f"{source} [cover]", positive=True)
    units = _units(cover_d.get("unit", []), cover, source)
    profile, pillow, salt = _salt(salt_d, width, source)
    faults = _faults(d.get("fault", []), width, source)
    blocks = _blocks(d.get("block", []), faults, source)
    s = Section(name=name, title=d.get("title", name), width=width, cover=cover, salt=salt,
                faults=faults, blocks=blocks, profile=profile, pillow=pillow, source=source, units=units)
    s.target = number(d, "target", source, 1000.0, positive=True)
    if "rate" in d:
        s.rate = number(d, "rate", source, positive=True)
    s.tilt = number(d, "tilt", source, 0.0)
    if not -45 < s.tilt < 45:
        raise SectionError(f"{source}: tilt {s.tilt:g} must be in (-45, 45) degrees")
    walls = d.get("walls", {})
    check_keys(walls, {"left", "right", "right_move"}, f"{source} [walls]")
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
        s.restart_every = number(d, "restart_every", source, positive=True)
    if "wedge" in d:
        w = d["wedge"]
        where = f"{source} [wedge]"
        check_keys(w, {"front0", "rate", "load", "foreset_dip", "every"}, where)
        s.wedge = {"front0": number(w, "front0", where, 0.0), "rate": number(w, "rate", where, positive=True),
                   "load": number(w, "load", where, positive=True),
                   "foreset_dip": number(w, "foreset_dip", where, positive=True),
                   "every": number(w, "every", where, positive=True)}
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




def _salt(salt_d: dict, width: float, source: str):
    """The salt body: a profile, a pillow, and the nominal thickness."""
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
        check_keys(p, {"x", "width", "height"}, f"{source} [salt] pillow")
        pillow = {k: number(p, k, f"{source} [salt] pillow", positive=(k != "x")) for k in ("x", "width", "height")}
        if pillow["x"] - pillow["width"] / 2 < 0 or pillow["x"] + pillow["width"] / 2 > width:
            raise SectionError(f"{source} [salt]: the pillow (x {pillow['x']:g} +- {pillow['width'] / 2:g} m) "
                               f"lies outside the box (0 to {width:g} m)")
    if profile is None and "thickness" not in salt_d:
        raise SectionError(f"{source} [salt]: give its thickness or a profile")
    # the nominal salt thickness (the box's height is it plus the cover): the layer's, or the
    # profile's largest; a pillow rises into the cover
    salt = max(t for _, t in profile) if profile else number(salt_d, "thickness", f"{source} [salt]", positive=True)

    return profile, pillow, salt


def _faults(items: list, width: float, source: str) -> list:
    faults = []
    for k, fd in enumerate(items):
        where = f"{source} fault {k + 1}"
        check_keys(fd, {"name", "x", "dip", "toward"}, where)
        fname = fd.get("name", f"f{k + 1}")
        if not isinstance(fname, str) or not fname.replace("_", "").isalnum():
            raise SectionError(f"{where}: name {fname!r} must be letters, digits and _")
        dip = number(fd, "dip", where)
        if not 0 < dip <= 90:
            raise SectionError(f"{where} ({fname}): dip {dip:g} must be in (0, 90] degrees")
        toward = fd.get("toward", "right")
        if toward not in ("right", "left"):
            raise SectionError(f"{where} ({fname}): toward {toward!r} must be right or left")
        x = number(fd, "x", where)
        if not 0 < x < width:
            raise SectionError(f"{where} ({fname}): x {x:g} lies outside the box (0 to {width:g} m)")
        faults.append(Fault(fname, x, dip, toward))
    if len({f.name for f in faults}) != len(faults):
        raise SectionError(f"{source}: two faults share a name")
    if any(b.x <= a.x for a, b in zip(faults, faults[1:])):
        raise SectionError(f"{source}: give the faults left to right (increasing x)")

    return faults


def _blocks(items: list, faults: list, source: str) -> list:
    blocks = []
    for k, bd in enumerate(items):
        where = f"{source} block {k + 1}"
        check_keys(bd, {"name", "top", "slip", "move", "rotate", "scale", "from", "to", "static", "tilt"}, where)
        b = Block(bd.get("name", f"block{k + 1}"))
        b.top = number(bd, "top", where, 0.0)
        if b.top < 0:
            raise SectionError(f"{where} ({b.name}): top {b.top:g} must be >= 0 (the lowest block's top is 0)")
        b.static = bool(bd.get("static", False))
        if "slip" in bd:
            if bd["slip"] not in {f.name for f in faults}:
                raise SectionError(f"{where} ({b.name}): slip names fault {bd['slip']!r}, which is not given")
            b.slip = bd["slip"]
        if "move" in bd:
            b.move = tuple(formula_value(v, f"{where} ({b.name}) move") for v in bd["move"])
            if len(b.move) != 2:
                raise SectionError(f"{where} ({b.name}): move must be [vx, vy] (m per m of drive)")
        if "rotate" in bd:
            b.rotate = tuple(float(v) for v in bd["rotate"])
            if len(b.rotate) != 3:
                raise SectionError(f"{where} ({b.name}): rotate must be [px, py, degrees per m of drive]")
        if "tilt" in bd:
            b.tilt = number(bd, "tilt", where)
            if not 0 < b.tilt < 0.2:
                raise SectionError(f"{where} ({b.name}): tilt {b.tilt:g} must be in (0, 0.2) degrees per m of drive")
        b.scale = number(bd, "scale", where, 1.0)
        b.start = number(bd, "from", where, 0.0)
        b.stop = number(bd, "to", where, -1.0)
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

    return blocks


def _units(items: list, cover: float, source: str) -> list:
    """The cover's units, top first; each unit's material is a cover params file (the deck's
    own, potentials/cover_paper.params, stays type 1; every other material gets a type)."""
    units, types = [], {}
    for k, u in enumerate(items):
        where = f"{source} [cover] unit {k + 1}"
        if not isinstance(u, dict):
            raise SectionError(f"{where}: give name, thickness and material")
        check_keys(u, {"name", "thickness", "material", "density"}, where)
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
        unit = Unit(name, number(u, "thickness", where, positive=True), path.resolve())
        if "density" in u:
            unit.density = number(u, "density", where, positive=True)
        if unit.material != DEFAULT_MATERIAL.resolve():
            unit.type = types.setdefault(unit.material, 4 + len(types))
        material_values(unit.material, where)
        units.append(unit)
    if units and abs(sum(u.thickness for u in units) - cover) > 1e-6 * cover:
        raise SectionError(f"{source} [cover]: its units add up to {sum(u.thickness for u in units):g} m, "
                           f"not the cover's {cover:g} m")
    if len({u.name for u in units}) != len(units):
        raise SectionError(f"{source} [cover]: two units share a name")
    return units


def material_values(path: Path, where: str) -> dict:
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


def _place_blocks(s: Section):
    """Each block's base between its faults; faults may not cross inside the basement's travel."""
    xs = [0.0] + [f.x for f in s.faults] + [s.width]
    for b, lo, hi in zip(s.blocks, xs, xs[1:]):
        b.left, b.right = lo, hi
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


