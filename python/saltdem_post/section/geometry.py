"""The deck's geometry and motion: the salt body and basement formulas, the wall lines of every
block, and the blocks' kinematics for fix saltdem/blocks (domino blocks in phases)."""
from __future__ import annotations

import math
from typing import Optional

from .model import Expr, Section


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


def fmt(v: float) -> str:
    if isinstance(v, Expr):
        return f"$({v.text})"
    return f"{v:.12g}"


def _lining(s: Section, top: float, target: str, dw: str) -> str:
    """The length of a moving block's fault-face lining, as a deck expression in the given
    spellings of the target and the wall discs' diameter: the largest slip a fault sees over
    the drive, two discs more, and the block's top."""
    scale = fmt(max([1.0, _domino_slip(s)] + [abs(b.scale) for b in s.blocks]))
    return f"({target}*{scale}+2*{dw}+{fmt(top)})"


def face_depths(s: Section) -> list:
    """How far below the lowest block's top each moving block's fault face reaches at the end of
    the drive (deck expressions in target and rmin, for the box): its lining plus the block's
    descent.  (The lining of wall_lines(); rmin is the wall discs' radius.)"""
    faults = s.faults_by_name
    out = []
    n = len(s.blocks)
    for k, b in enumerate(s.blocks):
        if b.static:
            continue
        down = max(0.0, -b.velocity(faults)[1]) if not b.tilt else 0.0
        for f, side in ((s.faults[k - 1] if k else None, "left"), (s.faults[k] if k < n - 1 else None, "right")):
            if f is None or not ((side == "right") == (f.toward == "right")):
                continue
            lface = _lining(s, b.top, "${target}", "(2*${rmin})")
            out.append(f"{lface}*sin({fmt(f.dip)}*PI/180)+${{rmin}}*cos({fmt(f.dip)}*PI/180)-{fmt(b.top)}"
                       f"+${{target}}*{fmt(down)}")
    return out


def wall_lines(s: Section) -> list:
    """saltdem/wall commands, block by block, in the order the paper's decks lay them (each
    fault's sine and cosine as equal-style variables, as the decks have them: LAMMPS evaluates
    those to other bits than the same formula inline)."""
    lines = [f"variable        sd_{f.name} equal sin({fmt(f.dip)}*PI/180)\n"
             f"variable        cd_{f.name} equal cos({fmt(f.dip)}*PI/180)" for f in s.faults]
    wtop = "${wtop}" if s.wedge else "$(v_H+v_salt)"     # a wedge's walls reach above its load
    n = len(s.blocks)
    for k, b in enumerate(s.blocks):
        g = b.name
        fl = s.faults[k - 1] if k > 0 else None          # the fault on its left
        fr = s.faults[k] if k < n - 1 else None          # the fault on its right
        # base: from its left end to its right end, short of a fault face it meets
        if fl is None:
            x0 = "$(-v_rw)"
        elif fl.toward == "right":                       # it is the hanging wall of fl
            x0 = f"$({fmt(fl.x)}+v_rw)"
        else:                                            # footwall of a fault dipping left
            x0 = f"$({fmt(fl.x)}+v_rw*(1-v_cd_{fl.name})/v_sd_{fl.name})"
        if fr is None:
            x1 = "$(v_width+v_rw)"
            if s.right_wall == "move":
                x1 = f"$(v_width+v_target*{fmt(abs(s.right_move[0]))}+3*v_rw)"    # under the gap
        elif fr.toward == "right":                       # footwall of fr
            x1 = f"$({fmt(fr.x)}-v_rw*(1-v_cd_{fr.name})/v_sd_{fr.name})"
        else:
            x1 = f"$({fmt(fr.x)}-v_rw)"
        y = f"$({fmt(b.top)}-v_rw)"
        lines.append(f"saltdem/wall    3 {x0} {y} {x1} {y} ${{rw}} group {g} ${{wallz}}")
        if k == 0:
            lw = g if s.left_wall == "block" else "wall_left"
            lines.append(f"saltdem/wall    3 $(-v_rw) $({fmt(b.top)}+v_rw) $(-v_rw) {wtop} ${{rw}} group {lw} ${{wallz}}")
        if k == n - 1 and s.right_wall == "block" and b.tilt:
            lines.append(f"saltdem/wall    3 $(v_width+v_rw) $({fmt(b.top)}+v_rw) $(v_width+v_rw) "
                         f"{wtop} ${{rw}} group wall_right ${{wallz}}")
        elif k == n - 1 and s.right_wall == "block":
            lines.append(f"saltdem/wall    3 $(v_width+v_rw) $({fmt(b.top)}+v_rw) $(v_width+v_rw) "
                         f"{wtop} ${{rw}} group {g} ${{wallz}}")
        # the face it exposes: the footwall lines its fault face from its top down-dip
        for f, side in ((fl, "left"), (fr, "right")):
            if f is None:
                continue
            footwall = (side == "right" and f.toward == "right") or (side == "left" and f.toward == "left")
            if not footwall:
                continue
            sd, cd = f"v_sd_{f.name}", f"v_cd_{f.name}"
            # the face starts a disc inside the footwall's corner and runs down-dip
            back, down = ("-", "+") if f.toward == "right" else ("+", "-")
            top = fmt(b.top)
            other = s.blocks[k + 1] if side == "right" else s.blocks[k - 1]
            if b.static and other.static:     # a static step: lined down to the lower block
                lface = f"(2*v_dw+{fmt(b.top - other.top)})"
            else:
                lface = _lining(s, b.top, "v_target", "v_dw")
            lines.append(f"saltdem/wall    3 $({fmt(f.x)}{back}v_rw*{sd}) $({top}-v_rw*{cd}) "
                         f"$({fmt(f.x)}{back}v_rw*{sd}{down}{lface}*{cd}) $({top}-v_rw*{cd}-{lface}*{sd}) "
                         f"${{rw}} group {g} ${{wallz}}")
    if s.right_wall in ("static", "move"):
        lines.append("saltdem/wall    3 $(v_width+v_rw) $(v_rw) $(v_width+v_rw) $(v_H+v_salt) ${rw} group wall_right ${wallz}")
    return lines


DOMINO_PHASES = 20


def _dominoes(s: Section) -> tuple:
    """The domino blocks, left to right, and the dip of their faults (None, None: none)."""
    dom = [b for b in s.blocks if b.tilt]
    if not dom:
        return None, None
    return dom, s.faults[s.blocks.index(dom[0]) - 1].dip


def _domino_crest_shift(s: Section, dom: list, k: int, th: str) -> str:
    """e_k(theta): how far domino block k's crest has moved right at the turn th (an expression
    in radians); k indexes dom, the domino blocks left to right."""
    dip = _dominoes(s)[1]
    terms = []
    for m in range(k + 1):
        L = fmt(dom[m].right - dom[m].left)
        deff = f"({fmt(dip)}*PI/180)" if m == 0 else f"({fmt(dip)}*PI/180-{th})"
        terms.append(f"{L}*(cos({th})-1+sin({th})*cos({deff})/sin({deff}))")
    return "+".join(terms)


def domino_extension(s: Section) -> str:
    """The last domino crest's shift at the end of the drive (a deck expression in target), the
    room the box needs on the right; '0' without domino blocks."""
    dom = _dominoes(s)[0]
    if not dom:
        return "0"
    return _domino_crest_shift(s, dom, len(dom) - 1, f"({fmt(dom[0].tilt)}*PI/180*${{target}})")


def _domino_args(s: Section) -> list:
    """Bookshelf (domino) blocks: each turns counterclockwise by theta about its crest (its top
    right corner, which stays at the basement top) and moves right by e_k(theta), so that its
    hanging-wall corner slides down the face of the block to its left (static for the first,
    turned by theta for the others).  The exact path, cut into DOMINO_PHASES phases of equal
    turn, each exact at its ends (a turn about the moving crest and a uniform translation)."""
    dom = _dominoes(s)[0]
    w = dom[0].tilt
    n = DOMINO_PHASES

    def e(k, th):                      # k: index into dom; th: an expression in radians
        return _domino_crest_shift(s, dom, k, th)

    out = []
    for j in range(n):
        ta = f"({fmt(w)}*PI/180*v_target*{j}/{n})"
        tb = f"({fmt(w)}*PI/180*v_target*{j + 1}/{n})"
        d0 = f"$(v_target*{j}/{n})" if j else "0"
        d1 = f"$(v_target*{j + 1}/{n})"
        for k, b in enumerate(dom):
            vx = f"$(({e(k, tb)}-({e(k, ta)}))/(v_target/{n}))"
            px = f"$({fmt(b.right)}+{e(k, ta)})"
            out.append(f"block {b.name} rotate {px} 0 {fmt(w)} move {vx} 0 from {d0} to {d1}")
            if b is s.blocks[-1]:     # the end wall rides on the last crest, upright
                out.append(f"block wall_right move {vx} 0 from {d0} to {d1}")
    return out


def _domino_slip(s: Section) -> float:
    """The largest slip on a domino fault per m of drive at the section's target."""
    dom, dip = _dominoes(s)
    if not dom:
        return 0.0
    d = math.radians(dip)
    th = math.radians(dom[0].tilt * s.target)
    return max((b.right - b.left) * math.sin(th) / math.sin(d - th * (k > 0))
               for k, b in enumerate(dom)) / s.target


def block_args(s: Section) -> list:
    faults = s.faults_by_name
    out = []
    if any(b.tilt for b in s.blocks):
        out += _domino_args(s)
    for b in s.blocks:
        if b.static or b.tilt:
            continue
        words = [f"block {b.name}"]
        if b.slip:
            f = faults[b.slip]
            words.append(f"slip {fmt(f.dip)} {f.toward}")
        if b.move:
            words.append(f"move {fmt(b.move[0])} {fmt(b.move[1])}")
        if b.rotate:
            words.append(f"rotate {fmt(b.rotate[0])} {fmt(b.rotate[1])} {fmt(b.rotate[2])}")
        if b.scale != 1.0:
            words.append(f"scale {fmt(b.scale)}")
        if b.start:
            words.append(f"from {fmt(b.start)}")
        if b.stop is not None:
            words.append(f"to {fmt(b.stop)}")
        out.append(" ".join(words))
    if s.right_wall == "move":
        out.append(f"block wall_right move {fmt(s.right_move[0])} {fmt(s.right_move[1])}")
    return out


