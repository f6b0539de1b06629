"""What the reference paper states about each of its scenes (Hardy's §2.3-2.5 and §3, Figs. 3-7),
one statement per line with its section and figure, for the gallery's side-by-side tables."""

from __future__ import annotations

import re
from typing import Dict, List, Tuple

# scene key -> (where, [statements])
STATEMENTS: Dict[str, Tuple[str, List[str]]] = {
    "expt1": ("§2.3, Fig. 3", [
        "100 m: subtle salt flow towards the downthrown side, concentrated in a wide zone above the "
        "fault tip; a steep extensional fault/dilational fracture in the upper cover, spatially "
        "related to but not linked with the basement fault",
        "250 m: salt flow over a wide region of the footwall towards the hanging wall, and in the "
        "hanging wall towards the fault plane; several sub-parallel cover faults above the basement "
        "fault, more faulting in the hanging wall; two conjugate normal faults adjacent to the "
        "right-hand end wall",
        "500 m: apart from close to the right-hand wall, most normal faulting is in the footwall; a "
        "central cover block stays essentially undeformed",
        "750 m: deformation propagates further into the footwall (a conjugate normal fault set); "
        "dominant salt flow from footwall to hanging wall; the main cover fault soft-linked to the "
        "basement fault, no discrete faulting in the salt",
        "1000 m: a wide zone of cover deformation; salt thinned to about 400 m near the edge of the "
        "footwall block; cover faults more closely aligned with the basement fault",
    ]),
    "expt2": ("§2.4, Fig. 4", [
        "100 m: almost symmetric salt flow towards the graben, gentle flexing of the cover, no "
        "visible faulting",
        "250 m: subtle rotational 'reverse' and more prominent normal cover faults; asymmetric: "
        "widely distributed normal faulting above the right-hand footwall, minor faulting above "
        "the left-hand footwall",
        "500 m: deformation propagates into the right footwall with prominent conjugate faulting; "
        "asymmetric salt flow, shear flow above much of the right footwall; viscous shear of the "
        "salt between the down-thrown keystone and the undeformed central cover",
        "750-1000 m: conjugate normal faults and mini-graben above the right footwall; faulting "
        "begins to propagate into the left footwall as it collapses; salt thinned to about 325 m "
        "immediately above the basement fault tips",
    ]),
    "expt3": ("§2.5, Fig. 5", [
        "100 m: down-dip salt flow towards the bottom right-hand corner over much of the salt, "
        "widely distributed, not localised; no visible cover faults, strain localised at the right "
        "end wall and in the central cover",
        "250 m: two major planar extensional faults near the right-hand edge, more minor faulting "
        "upslope",
        "500 m: extensional faulting migrates upslope: sub-parallel synthetic (downslope) normal "
        "faults, rotated fault blocks tilted upslope by 3-5°; minor antithetic faulting and a small "
        "graben near the right-hand edge",
        "750-1000 m: the right-hand graben grows while antithetic faulting migrates upslope; an "
        "essentially undeformed, sinking block squeezes out the salt at the right-hand end",
    ]),
    "expt1_slow": ("§3, Fig. 6a", [
        "the right-hand wall graben is no longer present, replaced by a prominent antithetic fault",
        "cover faulting more distributed and not clearly linked to the basement fault",
        "edge effects reduced but not gone; greater localisation of strain in the cover",
    ]),
    "expt2_slow": ("§3, Fig. 6b", [
        "some of the asymmetry of Expt 2 is reduced, but still present",
        "a noticeable reduction in reverse (rotational) faulting above the basement faults",
        "no viscous shear (Couette flow) in the salt above the central, downthrown block",
    ]),
    "expt3_slow": ("§3, Fig. 6c", [
        "deformation broadly similar to the standard rate",
        "antithetic faulting more apparent across much of the model: conjugate fault sets and a set "
        "of graben across the model rather than tilted fault blocks",
    ]),
    "fig7_salt1000": ("§3, Fig. 7a", [
        "65° fault, 1000 m salt: basement deformation essentially decoupled from the cover; cover "
        "deformation distributed and extending into the footwall",
    ]),
    "fig7_salt500": ("§3, Fig. 7b", [
        "65° fault, 500 m salt: linkage transitional between the 1000 m and 250 m end members",
    ]),
    "fig7_salt250": ("§3, Fig. 7c", [
        "65° fault, 250 m salt: deformation localised, closely related to the basement fault",
        "a salt weld in the region of the basement fault tip",
    ]),
    "general": ("§3", [
        "no localisation (no discrete faults) in the salt: diffuse ductile flow",
        "cover faults tip out at the salt-cover interface; the interface is never offset by "
        "faulting but develops moderate relief",
        "salt flow is Couette-like between planar boundaries, Poiseuille-like towards a subsiding "
        "basement block or a moving end wall",
    ]),
}


def scene_key(name: str) -> str:
    """The statements' key for a gallery run name: the longest key the name starts with, after
    the variant tags a series adds (``_contact``, ``_seedN``) are dropped; the study's variants
    (``e1_...``) are Expt 1; anything else is 'general'."""
    base = re.sub(r"_(contact|seed\d+)(?=_|$)", "", name)
    if base.startswith("e1_"):
        base = "expt1"
    keys = [k for k in STATEMENTS if k != "general" and (base == k or base.startswith(k + "_"))]
    return max(keys, key=len) if keys else "general"
