"""The plain LAMMPS deck of a section, on the scene includes of examples/scene."""
from __future__ import annotations

import math
import re
from pathlib import Path

from .describe import material_values
from .geometry import (block_args, base_top_formula, domino_extension, face_depths, fmt, salt_top_formula,
                       wall_lines)
from .model import MATERIAL_KEYS, Section, SectionError


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
        for k, v in material_values(u.material, u.name).items():
            if k not in MATERIAL_KEYS:
                continue
            v = re.sub(r"v_(\w+)_cover\b", lambda m: m.group(0) if m.group(1) == "rscale" else f"v_{m.group(1)}_u{t}", v)
            head.append(f"variable        {k}_u{t} index {v}")
    top = "v_H"
    for k, u in enumerate(s.units):
        low = f"{top}-{fmt(u.thickness)}"
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
            assign.append(f"set             group unit_{u.name} ${{dens}} {fmt(u.density)}")
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


def deck(s: Section) -> str:
    """The plain LAMMPS deck of section s."""
    faults = s.faults_by_name
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
    travel = f"${{target}}*{fmt(speed)}"
    rot = any(b.rotate or b.tilt for b in s.blocks)
    right_x = travel if rot or any(v[0] > 0 for v in vel) else "0"
    ext = domino_extension(s)
    if ext != "0":     # the domino crests move right faster than the turn's speed bound says
        right_x = f"ternary(({ext})>({right_x}),({ext}),({right_x}))"
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
         + (f"--fault-x {' '.join(fmt(f.x) for f in s.faults)} " if s.faults else "")
         + "--at 100 250 500 750 1000",
         "",
         "variable        root        index .",
         ] + (["variable        preset      index full",
               'if "${preset} == tiny" then ' + " ".join(f'"variable {k} index {v}"' for k, v in s.tiny.items())]
              if s.tiny else []) + [
         f"variable        width       index {fmt(s.width)}",
         f"variable        salt        index {fmt(s.salt)}",
         f"variable        cover       index {fmt(s.cover)}"]
    # the section's drive, except at the tiny preset (its smoke-test drive: 2 m at 2 m/s)
    drive = []
    if s.wedge:
        w = s.wedge
        L += [f"variable        front0      index {fmt(w['front0'])}",
              f"variable        front_rate  index {fmt(w['rate'])}",
              f"variable        load        index {fmt(w['load'])}",
              f"variable        foreset_dip index {fmt(w['foreset_dip'])}"]
        drive.append("variable rate index ${front_rate}")
    if s.target != 1000.0:
        drive.append(f"variable target index {fmt(s.target)}")
    if s.rate is not None:
        drive.append(f"variable rate index {fmt(s.rate)}")
    if s.frames:
        drive.append(f"variable f index {' '.join(fmt(v) for v in s.frames)}")
    if s.restart_every:
        drive.append(f"variable restart_disp index {fmt(s.restart_every)}")
    if s.wedge:
        drive.append(f"variable sed_every index {fmt(s.wedge['every'])}")
    if drive:
        L += (["variable        preset      index full"] if not s.tiny else []) + [
              'if "${preset} != tiny" then ' + " ".join(f'"{d}"' for d in drive)]
    for k, v in s.extra_vars.items():
        L.append(f"variable        {k} index {v}")
    uhead, uassign, ucoeffs = _unit_lines(s)
    L += ["include         ${root}/examples/scene/params.in"] + uhead + ([
          "# (a unit's own material is calibrated on discs: 3D decks use the cover's, scaled in spheres.in)",
          'if "${dim} == 3" then &',
          f"  \"print 'section {s.name}: its cover units have materials of their own, calibrated "
          f"in 2D only; run it in 2D (dim 2)'\" \"quit 1\""] if ucoeffs else []) + [
          "# the preset must resolve the section: a disc radius across salt and cover, ten along it",
          'if "${salt} < ${rmax} || ${cover} < ${rmax} || ${width} < $(10*v_rmax)" then &',
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
        deep = down
        for d in face_depths(s):     # a moving block's fault face may reach deeper (3 rmax margin)
            d = f"{d}-3*${{rmax}}"
            deep = f"ternary(({d})>({deep}),({d}),({deep}))"
        L += [(f"variable        bylo equal -{deep}-6*${{rmax}}" if deep != "0"
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
    L += ["# 3D between end walls: the basement's wall spheres span the slab's depth",
          'variable        wallz string ""',
          'if "${zends} == walls" then "variable wallz string \'z $(v_rw) $(v_depth-v_rw)\'"',
          "",
          "# ---- basement: wall discs (type 3), block by block ---------------------------------------------"]
    L += wall_lines(s)
    L += ["jump            SELF laws",
          "label           resume",
          "include         ${root}/examples/scene/resume.in",
          "label           laws"]
    if s.tilt:
        L.append(f"fix             grav pack gravity 9.81 vector $(sin({fmt(s.tilt)}*PI/180)) "
                 f"$(-cos({fmt(s.tilt)}*PI/180)) 0")
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
    args = block_args(s)
    L += ['variable        taperopt string ""',
          'if "${taper_from} != ${taper_to}" then "variable taperopt string \'taper ${taper_from} ${taper_to}\'"']
    L.append(f"fix             blocks {grp} saltdem/blocks rate ${{rate}} target ${{target}} ${{taperopt}} &")
    for k, a in enumerate(args):
        L.append(f"                {a}" + (" &" if k < len(args) - 1 else ""))
    if s.tilt:
        # the tilted gravity from here on, after the motion (the order examples/expt3.in has)
        L += ["unfix           grav",
              f"fix             grav pack gravity 9.81 vector $(sin({fmt(s.tilt)}*PI/180)) "
              f"$(-cos({fmt(s.tilt)}*PI/180)) 0"]
    L += ["variable        disp equal f_blocks[1]",
          f"variable        name index {s.name}",
          'variable        progress index "' + " ".join(f"f_blocks[{k + 1}][3]" for k in range(len(moving))) + '"',
          "include         ${root}/examples/scene/sediment.in    # off unless -var sediment / erosion_level",
          "include         ${root}/examples/scene/frames.in",
          ""]
    return "\n".join(L)


