"""Fuzzer of every SaltDEM style (engine: fuzzlib.py).  For each style a valid line of a tiny
deck (100 discs, 10 steps) is mutated argument by argument - dropped, repeated, 0, negative,
nan, inf, 1e300, -1e300, 1e-300, text, unknown keyword, invalid type index or group - and line
by line (an extra value, an unknown keyword, no arguments, the style in a 3d deck, other
combinations of laws).  Every mutation must end in a clean LAMMPS error or be accepted with
finite thermo output over its 10 steps; a crash (signal, abort, uncaught exception,
segmentation fault, exit without an ERROR line, hang) or a non-finite thermo value fails.

Every keyword of every style is in at least one target line (a style whose keywords exclude
each other has a line per mode): fix saltdem/sediment in a box closed in x and y with room above
the cover, fix saltdem/checksum beside a restart command, saltdem/read_restart of a file the
deck writes first (then clear, the read, the set-up again and the usual run).  The other values
of the keywords that choose a mode (toward left, at_target end, noslip centre, checksum
optional, ...) are whole decks in COMBOS.  1645 cases (991 before the keyword targets).

Cases run one lmp each, SALTDEM_FUZZ_JOBS at a time (default 2); SALTDEM_FUZZ_MAX N runs an
evenly spread subset of N cases.  docs/reliability.md (Fuzzer) has the counts."""
import collections
import os

import pytest

from fuzzlib import Case, Line, classify, mutations, run_cases
from lmprun import lmp_path

# ---------------------------------------------------------------------------------------------
# the deck: 10 x 10 touching discs, type 1 salt, type 2 cover, the lowest two rows type 3
# walls (left half group 'key', right half 'rb'); a pair setup, integrators, a motion fix,
# fix saltdem/viscosity, saltdem/timestep.  Each slot holds one line (or several) and one slot
# is replaced by the mutated line.
# ---------------------------------------------------------------------------------------------

HEAD2 = """units si
dimension 2
atom_style sphere
atom_modify map array
boundary p f p
comm_modify vel yes
region box block 0 200 -50 200 -0.5 0.5
create_box 3 box
region inner block 0 200 0 200 -0.5 0.5
lattice sq 20
create_atoms 1 region inner
region low block INF INF INF 25 INF INF units box
region high block INF INF 150 INF INF INF units box
set region high type 2
set region low type 3
set group all diameter 21
set group all density/disc 2200
"""
HEAD3 = HEAD2.replace("dimension 2", "dimension 3").replace(
    "lattice sq 20", "lattice sc 20").replace("density/disc", "density").replace(
    "boundary p f p", "boundary p f f").replace("block 0 200 -50 200 -0.5 0.5", "block 0 200 -50 200 -25 25")
GROUPS = """group mobile type 1 2
group salt type 1
group cover type 2
group walls type 3
region left block INF 100 INF INF INF INF units box
group lw region left
group key intersect walls lw
group rb subtract walls key
group ks union key rb
"""

COH = "2.5e9 8e8 0.5 1e6 1e6 0.1 damp 0.1 0.1 rolling 1e8 0.1"
FLUID = "5e8 1e7 fluid 28 1e8"
CONTACT = "5e8 5e9 contact 0.5 tangential 0.5"

# pair setups: (pair_style line, [pair_coeff lines]); hybrid keeps its sub-style name
PAIRS = {
    "hybrid": ("pair_style hybrid saltdem/cohesive saltdem/viscous",
               [f"pair_coeff 2 2 saltdem/cohesive {COH}", f"pair_coeff 2 3 saltdem/cohesive {COH}",
                f"pair_coeff 1 1 saltdem/viscous {FLUID}", f"pair_coeff 1 2 saltdem/viscous {CONTACT}",
                f"pair_coeff 1 3 saltdem/viscous {CONTACT}", "pair_coeff 3 3 none"]),
    "viscous-both": ("pair_style saltdem/viscous correction 1.047 calibration 1 dtfactor 0.2 "
                     "viscfactor 0.5",
                     [f"pair_coeff 1 1 {FLUID}", f"pair_coeff 2 2 {CONTACT}",
                      f"pair_coeff 3 3 {CONTACT}", f"pair_coeff 1 2 {CONTACT}",
                      f"pair_coeff 1 3 {CONTACT}"]),
    "viscous-contact": ("pair_style saltdem/viscous", [f"pair_coeff * * {CONTACT}"]),
    "cohesive": ("pair_style saltdem/cohesive dtfactor 0.2", [f"pair_coeff * * {COH}"]),
}
SLOTS = {
    "nve": ["fix is salt saltdem/nve inertia 20 check 1", "fix ic cover saltdem/nve inertia 20 check 1"],
    "motion": ["fix mv rb saltdem/fault dip 60 rate 1 target 5 toward right at_target stop"],
    "viscosity": ["fix vs salt saltdem/viscosity lambda 1 model 5e8 rate 1 length 100 "
                  "density 2200 inertia 20 warn 10"],
    "wall": [],
    "timestep": ["saltdem/timestep 0.85"],
    "extra": [],    # after the fixes: fix saltdem/sediment, saltdem/checksum (and their set-up)
}
TAIL = """thermo 2
thermo_style custom step dt pe ke
run 10
"""


def deck(pair="hybrid", dim=2, **slots):
    """The deck with the given pair setup; a slot given replaces the default lines (a list, or
    one line); pair_style=/pair_coeff= replace those of the setup."""
    style, coeffs = PAIRS[pair]
    style = slots.pop("pair_style", style)
    coeffs = slots.pop("pair_coeff", coeffs)
    s = {k: list(v) for k, v in SLOTS.items()}
    if pair == "cohesive":
        s["viscosity"] = []    # needs the viscous pair style
    if dim == 3:
        s["motion"] = []       # 2d only (a motion target puts its line back)
    for k, v in slots.items():
        s[k] = [v] if isinstance(v, str) else list(v)
    lines = [HEAD2 if dim == 2 else HEAD3, GROUPS, *s["wall"], "neighbor 2.8 bin", style,
             *coeffs, "neigh_modify exclude type 3 3", "velocity mobile create 1e-3 7 loop geom",
             *s["nve"], *s["motion"], *s["viscosity"], *s["extra"]]
    if dim == 2:
        lines.append("fix e2d all enforce2d")
    lines += [*s["timestep"], TAIL]
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# targets: (name, the valid line, how it is split, how it goes into the deck)
# ---------------------------------------------------------------------------------------------

def put_coeff(pair, k):
    """A function of a line that puts it as pair_coeff line k of the setup."""
    def f(line, dim=2):
        coeffs = list(PAIRS[pair][1])
        coeffs[k] = line
        return deck(pair, dim=dim, pair_coeff=coeffs)
    return f


def put_slot(slot, pair="hybrid", index=0, keep_others=True):
    def f(line, dim=2):
        lines = list(SLOTS[slot]) if keep_others else []
        if index < len(lines):
            lines[index] = line
        else:
            lines.append(line)
        return deck(pair, dim=dim, **{slot: lines})
    return f


def put_style(pair):
    def f(line, dim=2):
        return deck(pair, dim=dim, pair_style=line)
    return f


def put_lines(slot, before=(), after=(), pair="hybrid", edit=None):
    """A function of a line that puts it in the slot between the given set-up lines (they
    stay valid); edit(deck, dim) changes the whole deck after."""
    def f(line, dim=2):
        d = deck(pair, dim=dim, **{slot: [*before, line, *after]})
        return edit(d, dim) if edit else d
    return f


# fix saltdem/sediment needs a box closed in x and y, with room above the cover for the new
# discs (type 2, the cover law; radii within the cover's 10.5 and the neighbour skin's half, and
# at least 0.95 of its mass: 10.3-10.5); an epoch property, a drive variable and a window end
# and an erosion envelope for the keywords that name them
SED_PRE = ["fix ep all property/atom i_epoch ghost yes", "variable drv equal step",
           "variable front equal 190", "variable env atom 170+0*x"]


def sediment_box(d, dim):
    if dim != 2:
        return d    # refused in 3d before the box is looked at
    return (d.replace("boundary p f p", "boundary f f p")
            .replace("region box block 0 200 -50 200", "region box block -20 220 -50 300")
            .replace("region inner block 0 200 0 200", "region inner block 0 190 0 190"))


# saltdem/read_restart needs a restart file and its checksum: the deck writes them (restart
# every 2 steps of a 4-step run, fix saltdem/checksum), clears, reads the older file and sets
# up again what a restart file does not hold; the deck ends with the usual run
RESTART_WRITE = ["restart 2 r.a r.b", "fix cs all saltdem/checksum"]


def resume_setup(dim=2):
    """What the deck gives again after saltdem/read_restart (the same fix IDs; pair hybrid
    keeps no coefficients)."""
    lines = ["comm_modify vel yes", "neighbor 2.8 bin", *PAIRS["hybrid"][1],
             "neigh_modify exclude type 3 3", *SLOTS["nve"]]
    if dim == 2:
        lines += [*SLOTS["motion"]]
    lines += [*SLOTS["viscosity"]]
    if dim == 2:
        lines.append("fix e2d all enforce2d")
    return "\n".join(lines + [*SLOTS["timestep"], TAIL])


def put_resume(line, dim=2):
    d = deck("hybrid", dim=dim, extra=RESTART_WRITE)
    assert d.endswith(TAIL)
    return d[:-len(TAIL)] + "run 4\nclear\n" + line + "\n" + resume_setup(dim)


TARGETS = [
    # pair styles: settings
    ("pair_style saltdem/cohesive", Line.parse(PAIRS["cohesive"][0], fixed=2), put_style("cohesive")),
    ("pair_style saltdem/viscous", Line.parse(PAIRS["viscous-both"][0], fixed=2),
     put_style("viscous-both")),
    ("pair_style hybrid", Line.parse(PAIRS["hybrid"][0], fixed=2, styles=(2, 3)), put_style("hybrid")),
    # pair coefficients of each law, alone and as a hybrid sub-style
    ("pair_coeff saltdem/cohesive", Line.parse(PAIRS["cohesive"][1][0], types=(1, 2)),
     put_coeff("cohesive", 0)),
    ("pair_coeff hybrid saltdem/cohesive", Line.parse(PAIRS["hybrid"][1][0], types=(1, 2),
                                                      styles=(3,), alt_style="saltdem/viscous"),
     put_coeff("hybrid", 0)),
    ("pair_coeff saltdem/viscous fluid", Line.parse(PAIRS["viscous-both"][1][0], types=(1, 2)),
     put_coeff("viscous-both", 0)),
    ("pair_coeff saltdem/viscous contact", Line.parse(PAIRS["viscous-both"][1][3], types=(1, 2)),
     put_coeff("viscous-both", 3)),
    ("pair_coeff hybrid saltdem/viscous fluid", Line.parse(PAIRS["hybrid"][1][2], types=(1, 2),
                                                           styles=(3,), alt_style="saltdem/cohesive"),
     put_coeff("hybrid", 2)),
    # integrators and fixes
    ("fix saltdem/nve", Line.parse(SLOTS["nve"][0], fixed=4, groups=(2,)), put_slot("nve")),
    ("fix saltdem/viscosity", Line.parse(SLOTS["viscosity"][0], fixed=4, groups=(2,)),
     put_slot("viscosity")),
    ("fix saltdem/fault", Line.parse(SLOTS["motion"][0], fixed=4, groups=(2,)), put_slot("motion")),
    ("fix saltdem/keystone", Line.parse("fix mv ks saltdem/keystone dip 60 keystone key rate 1 "
                                        "target 5 at_target stop", fixed=4, groups=(2, 7)),
     put_slot("motion")),
    ("fix saltdem/tiltwall", Line.parse("fix mv rb saltdem/tiltwall tilt 5 rate 1 target 5 "
                                        "toward right gravity mobile g 9.81 at_target stop",
                                        fixed=4, groups=(2, 13)),
     put_slot("motion")),
    # commands
    ("saltdem/wall", Line.parse("saltdem/wall 3 10 -30 190 -30 10 group w density 2200",
                                types=(1,)), put_slot("wall")),
    ("saltdem/timestep", Line.parse(SLOTS["timestep"][0]), put_slot("timestep")),
    # the keywords the lines above leave out: one more line per style (per mode where
    # keywords exclude each other)
    ("pair_style saltdem/viscous fill substeps noslip",
     Line.parse("pair_style saltdem/viscous fill 4 substeps 2 noslip surface", fixed=2),
     put_style("viscous-both")),
    ("fix saltdem/viscosity natural contrast gravity",
     Line.parse("fix vs salt saltdem/viscosity lambda 1e10 natural 5e18 rate 1 length 100 "
                "density 2200 contrast 100 gravity 9.81", fixed=4, groups=(2,)),
     put_slot("viscosity")),
    ("saltdem/timestep substeps", Line.parse("saltdem/timestep 0.85 substeps 2"),
     put_slot("timestep")),
    ("fix saltdem/sediment fill", Line.parse(
        "fix sed cover saltdem/sediment fill type 2 base 230 every 5 rmin 10.3 rmax 10.5 "
        "dist paper density 2200 seed 7 overlap 0.05 epoch i_epoch offset 10 group mobile "
        "erode none x 10 190 foreset 0.1 settle 3 1e3 maxper 50", fixed=4, types=(6,), groups=(2, 28)),
     put_lines("extra", before=SED_PRE, edit=sediment_box)),
    ("fix saltdem/sediment rate", Line.parse(
        "fix sed cover saltdem/sediment rate 1e4 type 2 base 230 every 5 drive v_drv "
        "rmin 10.3 rmax 10.5 dist uniform density 2200 seed 7 length 100 x 10 v_front "
        "erode 260 erode_group cover down 0 -1", fixed=4, types=(7,), groups=(2, 32)),
     put_lines("extra", before=SED_PRE, edit=sediment_box)),
    ("fix saltdem/sediment none", Line.parse(
        "fix sed cover saltdem/sediment none every 5 erode v_env erode_group cover",
        fixed=4, groups=(2, 10)),
     put_lines("extra", before=SED_PRE, edit=sediment_box)),
    ("fix saltdem/checksum", Line.parse("fix cs all saltdem/checksum", fixed=4, groups=(2,)),
     put_lines("extra", before=["restart 5 r.a r.b"])),
    ("saltdem/read_restart", Line.parse("saltdem/read_restart r.a checksum required timeout 30"),
     put_resume),
]

# other combinations of laws and setups, each a whole deck (expected: error or accepted)
COMBOS = {
    # two laws that cannot mix: a fluid and a contact type without their cross pair
    "viscous fluid 1 1 + contact 2 2, cross pairs not set": deck(
        "viscous-both", pair_coeff=[f"pair_coeff 1 1 {FLUID}", f"pair_coeff 2 2 {CONTACT}",
                                    f"pair_coeff 3 3 {CONTACT}"]),
    "viscous fluid everywhere (walls fluid too)": deck("viscous-both", pair_coeff=[f"pair_coeff * * {FLUID}"]),
    "viscous fluid without pressure (K 0)": deck(
        "viscous-both", pair_coeff=["pair_coeff * * 5e8 1e7 fluid 28 0"]),
    "cohesive without rolling or damping": deck(
        "cohesive", pair_coeff=["pair_coeff * * 2.5e9 8e8 0.5 1e6 1e6 0.1"]),
    "cohesive rolling on one type pair only": deck(
        "cohesive", pair_coeff=["pair_coeff * * 2.5e9 8e8 0.5 1e6 1e6 0.1",
                                f"pair_coeff 2 2 {COH}"]),
    "hybrid with the viscous pairs all contact": deck(
        "hybrid", pair_coeff=[f"pair_coeff 2 2 saltdem/cohesive {COH}",
                              f"pair_coeff 2 3 saltdem/cohesive {COH}",
                              f"pair_coeff 1 1 saltdem/viscous {CONTACT}",
                              f"pair_coeff 1 2 saltdem/viscous {CONTACT}",
                              f"pair_coeff 1 3 saltdem/viscous {CONTACT}", "pair_coeff 3 3 none"]),
    "hybrid with a type pair left unset": deck(
        "hybrid", pair_coeff=[f"pair_coeff 2 2 saltdem/cohesive {COH}",
                              f"pair_coeff 1 1 saltdem/viscous {FLUID}", "pair_coeff 3 3 none"]),
    "hybrid/overlay of both styles": deck(
        "hybrid", pair_style="pair_style hybrid/overlay saltdem/cohesive saltdem/viscous",
        pair_coeff=[f"pair_coeff * * saltdem/cohesive {COH}",
                    f"pair_coeff * * saltdem/viscous {CONTACT}"]),
    "hybrid with the same style twice": deck(
        "hybrid", pair_style="pair_style hybrid saltdem/cohesive saltdem/cohesive",
        pair_coeff=[f"pair_coeff * * saltdem/cohesive 1 {COH}",
                    f"pair_coeff 1 1 saltdem/cohesive 2 {COH}"],
        viscosity=[]),
    "saltdem/timestep before the pair coefficients": deck(
        "viscous-contact", wall=["pair_style saltdem/viscous", "saltdem/timestep 0.5"]),
    "saltdem/timestep with walls only integrated": deck("viscous-contact", nve=["fix iw walls nve/sphere"]),
    "saltdem/timestep with nothing integrated": deck("viscous-contact", nve=[], motion=[]),
    "two motion fixes on one block": deck("hybrid", motion=[
        SLOTS["motion"][0], "fix mv2 rb saltdem/tiltwall tilt 5 rate 1 target 5"]),
    "motion fix on integrated discs": deck("hybrid", motion=[
        "fix mv mobile saltdem/fault dip 60 rate 1 target 5"]),
    "viscosity fix twice": deck("hybrid", viscosity=[SLOTS["viscosity"][0],
                                                     SLOTS["viscosity"][0].replace("vs", "vs2")]),
    "viscosity fix before the pair style": deck("hybrid", wall=[SLOTS["viscosity"][0]]),
    "nve/omp variant and pair /omp": deck(
        "hybrid", wall=[],
        nve=[l.replace("saltdem/nve", "saltdem/nve/omp") for l in SLOTS["nve"]],
        pair_style="pair_style hybrid saltdem/cohesive/omp saltdem/viscous/omp",
        pair_coeff=[c.replace("saltdem/cohesive", "saltdem/cohesive/omp")
                    .replace("saltdem/viscous", "saltdem/viscous/omp") for c in PAIRS["hybrid"][1]],
        viscosity=[]).replace("units si", "units si\npackage omp 1"),
    "wall discs of the cover type": deck("hybrid", wall=["saltdem/wall 2 10 -30 190 -30 10"]),
    "wall of one disc (both ends equal)": deck("hybrid", wall=["saltdem/wall 3 100 -30 100 -30 10"]),
}

# the styles without per-atom radii (atom_style atomic): the motion fixes run, the rest refuse
ATOMIC = """units si
dimension 2
atom_style atomic
boundary f f p
region box block -100 100 -100 100 -1 1
create_box 1 box
create_atoms 1 single 0 0 0
create_atoms 1 single 50 0 0
mass 1 1
group one id 1
pair_style {pair}
pair_coeff * * {coeff}
{line}
thermo 2
thermo_style custom step dt pe ke
run 10
"""
for label, pair, coeff, line in [
        ("fault", "zero 1", "", "fix f one saltdem/fault dip 60 rate 1 target 5"),
        ("keystone", "zero 1", "", "group k id 2\ngroup both id 1 2\n"
                                   "fix f both saltdem/keystone dip 60 keystone k rate 1 target 5"),
        ("tiltwall", "zero 1", "", "fix f one saltdem/tiltwall tilt 5 rate 1 target 5"),
        ("nve", "zero 1", "", "fix f all saltdem/nve"),
        ("wall", "zero 1", "", "saltdem/wall 1 -50 -50 50 -50 5"),
        ("cohesive", "saltdem/cohesive", "1e9 1e8 0.5 0 0 0", "fix f all nve"),
        ("viscous", "saltdem/viscous", "5e8 5e9 contact 0.5", "fix f all nve"),
        ("timestep", "saltdem/cohesive", "1e9 1e8 0.5 0 0 0", "fix f all nve\nsaltdem/timestep 0.5")]:
    COMBOS[f"atom_style atomic: {label}"] = ATOMIC.format(pair=pair, coeff=coeff, line=line)

# values that reach the styles only through extract() during a run (pair_coeff and the fixes
# refuse 'nan' and 'inf' as text): fix adapt sets the salt's viscosity from step 4 on
ADAPT = ("variable e equal ternary(step>=4,{v},5e8)\n"
         "fix ad all adapt 1 pair saltdem/viscous eta 1 1 v_e")
for label, v in [("0", "0"), ("negative", "-5e8"), ("inf", "1e300*1e300"),
                 ("nan", "(1e300*1e300)-(1e300*1e300)"), ("1e300", "1e300"), ("1e-300", "1e-300"),
                 ("x1000", "5e11"), ("x0.001", "5e5")]:
    COMBOS[f"fix adapt: salt viscosity {label} during the run"] = deck(
        "hybrid", viscosity=[ADAPT.format(v=v)])
    COMBOS[f"fix adapt: viscosity {label} during the run, viscous alone"] = deck(
        "viscous-both", viscosity=[ADAPT.format(v=v)])
# the disc size changed during the run (not a coefficient: the limit is not checked again)
COMBOS["fix adapt: salt diameter halved during the run"] = deck(
    "hybrid", viscosity=["variable d equal ternary(step>=4,10.5,21)",
                         "fix ad salt adapt 1 atom diameter v_d"]).replace(
    "atom_style sphere", "atom_style sphere 1")

# the other values of the keywords that choose a mode (one deck each, not mutated): the motion
# fixes toward the left and ending the run at a target reached within it (the target 3.5 time
# steps of motion, after saltdem/timestep has set the step), the boundary of the fluid, the
# salt the denser, deposition driven by a fix's displacement, a checksum beside a single and a
# multi-file restart, restart files without or with a stale checksum
AT_END = "rate 1 target $(3.5*dt) at_target end"
for label, line in [
        ("fault toward left, at_target end reached", f"fix mv rb saltdem/fault dip 60 {AT_END} toward left"),
        ("keystone at_target end reached", f"fix mv ks saltdem/keystone dip 60 keystone key {AT_END}"),
        ("tiltwall toward left, g without gravity group",
         f"fix mv rb saltdem/tiltwall tilt 5 {AT_END} toward left g 9.81")]:
    COMBOS[f"{label} during the run"] = deck(
        "hybrid", motion=[], timestep=[*SLOTS["timestep"], line])
for v in ("centre", "center"):
    COMBOS[f"viscous noslip {v}"] = deck(
        "viscous-both", pair_style=f"pair_style saltdem/viscous fill 4 noslip {v}")
COMBOS["viscosity contrast negative (the salt the denser), default gravity"] = deck(
    "hybrid", viscosity=[SLOTS["viscosity"][0] + " contrast -100"])
COMBOS["sediment fill every drive displacement of the fault (f_mv[1])"] = sediment_box(deck(
    "hybrid", timestep=[*SLOTS["timestep"],
                        "fix sed cover saltdem/sediment fill type 2 base 230 every $(2*dt) "
                        "drive f_mv[1] rmin 10.3 rmax 10.5 density 2200 seed 3"]), 2)
COMBOS["sediment rate 0, erosion above an equal-style level"] = sediment_box(deck(
    "hybrid", extra=["variable sea equal 185", "fix sed cover saltdem/sediment rate 0 type 2 "
                     "base 230 every 5 rmin 10.3 rmax 10.5 density 2200 seed 3 erode v_sea"]), 2)
for label, rs in [("a single file per step (r.*)", "restart 3 r.*"),
                  ("one file name (r.bin: the step appended)", "restart 3 r.bin"),
                  ("a multi-file restart (r.%)", "restart 3 r.%"),
                  ("no restart command", "")]:
    COMBOS[f"checksum with {label}"] = deck(
        "hybrid", extra=[l for l in (rs, "fix cs all saltdem/checksum") if l])
for label, mid, read in [
        ("a file without checksum, checksum optional", "write_restart r.c",
         "saltdem/read_restart r.c checksum optional"),
        ("a file without checksum, checksum required", "write_restart r.c",
         "saltdem/read_restart r.c checksum required"),
        ("a file rewritten after its checksum", "write_restart r.a", "saltdem/read_restart r.a"),
        ("the newer file of the pair, no watchdog", "", "saltdem/read_restart r.b timeout 0"),
        ("a missing file", "", "saltdem/read_restart r.x"),
        ("plain read_restart of a checksummed file", "", "read_restart r.a")]:
    d = put_resume(read)
    if mid:
        d = d.replace("run 4\nclear\n", f"run 4\n{mid}\nclear\n")
    COMBOS[f"read_restart: {label}"] = d


def build_cases():
    cases = []
    for name, line, put in TARGETS:
        cases.append(Case(name, "valid", put(line.text()), line.text()))
        for label, text in mutations(line):
            cases.append(Case(name, label, put(text), text))
        cases.append(Case(name, "3d deck", put(line.text(), dim=3), line.text()))
    for label, d in COMBOS.items():
        cases.append(Case("combinations", label, d))
    n = int(os.environ.get("SALTDEM_FUZZ_MAX", "0") or 0)
    if 0 < n < len(cases):
        step = len(cases) / n
        cases = [cases[int(k * step)] for k in range(n)]
    return cases


CASES = build_cases()


@pytest.fixture(scope="module")
def outcomes():
    jobs = int(os.environ.get("SALTDEM_FUZZ_JOBS", "2"))
    return dict(zip(map(id, CASES), run_cases(lmp_path(), CASES, jobs=jobs)))


def report(cases, outcomes, kinds=("crash", "nonfinite")):
    bad = [(c, outcomes[id(c)]) for c in cases if outcomes[id(c)].kind in kinds]
    return "\n\n".join(f"[{o.kind}] {c.target} / {c.label}: {o.detail}\n  line: {c.line}\n"
                       f"  output tail:\n{o.tail[-1200:]}" for c, o in bad)


@pytest.mark.parametrize("target", sorted({c.target for c in CASES}))
def test_no_crash_no_nonfinite(outcomes, target):
    cases = [c for c in CASES if c.target == target]
    msg = report(cases, outcomes)
    assert not msg, msg
    infra = report(cases, outcomes, kinds=("infra",))
    if infra:    # lmp never ran for these cases: neither a pass nor a crash
        pytest.fail("INFRASTRUCTURE FAILURE, not a test result: Open MPI failed to start after "
                    "retries for\n" + infra, pytrace=False)


@pytest.mark.parametrize("target", sorted({c.target for c in CASES if c.label == "valid"}))
def test_valid_line_is_accepted(outcomes, target):
    """Control: the unmutated line of each target runs (so its mutations test that line)."""
    c = next(c for c in CASES if c.target == target and c.label == "valid")
    o = outcomes[id(c)]
    assert o.kind == "accepted", f"{o.kind}: {o.detail}\n{o.tail}"


def test_summary(outcomes, capsys):
    """The counts per target and class (shown with -s or -rA)."""
    per = collections.defaultdict(collections.Counter)
    for c in CASES:
        per[c.target][outcomes[id(c)].kind] += 1
    total = collections.Counter(outcomes[id(c)].kind for c in CASES)
    secs = sum(outcomes[id(c)].seconds for c in CASES)
    lines = [f"fuzz: {len(CASES)} cases, {secs:.1f} s of lmp time; " +
             ", ".join(f"{k} {v}" for k, v in sorted(total.items()))]
    for t in sorted(per):
        lines.append(f"  {t}: " + ", ".join(f"{k} {v}" for k, v in sorted(per[t].items())))
    with capsys.disabled():
        print("\n" + "\n".join(lines))
    assert len(CASES) >= 300 or os.environ.get("SALTDEM_FUZZ_MAX")


def test_classifier():
    """The classes, on made-up outputs."""
    assert classify(1, "ERROR: Pair style x: y (src/a.cpp:1)\n").kind == "error"
    assert classify(1, "ERROR on proc 0: z\nMPI_ABORT was invoked on rank 0\n").kind == "error"
    assert classify(-11, "").kind == "crash"
    assert classify(134, "terminate called after throwing an instance of 'std::out_of_range'").kind == "crash"
    assert classify(1, "no error line\n").kind == "crash"
    assert classify(0, "", timed_out=True).kind == "crash"
    ok = "Step Dt PotEng KinEng\n0 0.1 1 2\n10 0.1 1 2\nLoop time of 1 on 1 procs\n"
    assert classify(0, ok).kind == "accepted"
    assert classify(0, ok.replace("10 0.1 1 2", "10 0.1 -nan 2")).kind == "nonfinite"
    assert classify(0, ok.replace("10 0.1 1 2", "10 0.1 1 inf")).kind == "nonfinite"
    assert classify(0, "Total wall time: 0:00:00\n").kind == "crash"    # no run happened


def test_mutations_cover_every_argument():
    line = Line.parse("fix a g saltdem/nve inertia 20", fixed=4)
    labels = [l for l, _ in mutations(line)]
    assert "4:inertia drop" in labels and "4:inertia unknown" in labels
    for m in ("drop", "repeat", "0", "neg", "nan", "inf", "1e300", "-1e300", "1e-300", "text"):
        assert f"5:20 {m}" in labels
    texts = dict(mutations(line))
    assert texts["5:20 neg"] == "fix a g saltdem/nve inertia -20"
    assert texts["line no-arguments"] == "fix a g saltdem/nve"
