"""Prescribed-motion fixes saltdem/keystone and saltdem/tiltwall, and the saltdem/wall command.

Kinematics are checked against their formulas from positions dumped at full precision; restarts,
split runs and two MPI ranks must reproduce an uninterrupted serial run; bad input must give a
clean LAMMPS error that names the offending item."""
import math

import numpy as np
import pytest

from lmprun import assert_error, check_ok, lmp_path, run_cmd

HEAD = """
units si
dimension 2
atom_style sphere
atom_modify map array
boundary f f p
comm_modify vel yes
region box block -100 100 -100 100 -1 1
create_box 1 box
"""


def read_dump(path):
    """A write_dump custom file as {column: array}, rows sorted by id."""
    lines = path.read_text().splitlines()
    head = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))    # (after TIME)
    cols = lines[head].split()[2:]
    data = np.array([[float(v) for v in l.split()] for l in lines[head + 1:]], ndmin=2)
    data = data[np.argsort(data[:, cols.index("id")])]
    return {c: data[:, k] for k, c in enumerate(cols)}


DUMP = "write_dump all custom {} id x y vx vy omegaz modify format float %.17g\n"


def test_help_lists_the_new_styles():
    out = run_cmd([lmp_path(), "-h"], capture_output=True, text=True).stdout
    fixes = out.split("* Fix styles")[1].split("* Compute styles:")[0].split()
    commands = out.split("* Command styles")[1].split()
    assert "saltdem/keystone" in fixes and "saltdem/tiltwall" in fixes
    assert "saltdem/wall" in commands

# ---------------------------------------------------------------------------------------------
# fix saltdem/keystone
# ---------------------------------------------------------------------------------------------

# left block (static): id 1; keystone: ids 2, 3; right block: ids 4, 5.  The discs are far apart
# (no contacts).  Keystone disc 2 starts at x = -5 and crosses x = 0, the boundary between the
# two sub-domains of the MPI run.
START = {1: (-60.0, 0.0), 2: (-5.0, 0.0), 3: (-15.0, 10.0), 4: (40.0, 0.0), 5: (50.0, -5.0)}
KEY_ATOMS = "".join(f"create_atoms 1 single {x} {y} 0\n" for x, y in START.values())
KEY_SETUP = HEAD + KEY_ATOMS + """
set type 1 diameter 2
set type 1 density/disc 2200
set group all omega 0 0 3
group left id 1
group key id 2 3
group right id 4 5
group moving union key right
pair_style saltdem/cohesive
pair_coeff * * 1e9 0 0.5 0 0 0
"""
RATE, DT = 20.0, 0.1          # 2 m per step
TARGET = 25.0                 # reached at step 13, by a shortened last step of 1 m
KEY_FIX = "fix ks moving saltdem/keystone dip ${dip} keystone key rate 20 target 25 ${extra}\n"
KEY_THERMO = """
timestep 0.1
variable x2 equal x[2]
variable y2 equal y[2]
variable x4 equal x[4]
variable y4 equal y[4]
variable vx2 equal vx[2]
variable vy2 equal vy[2]
variable vx4 equal vx[4]
variable vy4 equal vy[4]
thermo_style custom step f_ks[1] f_ks[2] f_ks[3] f_ks[4] f_ks[5] v_x2 v_y2 v_x4 v_y4 &
             v_vx2 v_vy2 v_vx4 v_vy4
thermo_modify format float %.17g
thermo 1
"""


def keystone_deck(*runs, out="final.txt"):
    return KEY_SETUP + KEY_FIX + KEY_THERMO + "".join(f"run {n}\n" for n in runs) + DUMP.format(out)


def drive(step):
    """Drive displacement after `step` steps."""
    return min(RATE * DT * step, TARGET)


@pytest.mark.parametrize("dip", [30.0, 60.0, 75.0])
def test_keystone_kinematics(lmp, dip):
    r = lmp(keystone_deck(20), dip=dip, extra="")
    check_ok(r)
    c, s = math.cos(math.radians(dip)), math.sin(math.radians(dip))
    f = read_dump(r.workdir / "final.txt")
    xy = {int(i): np.array([x, y]) for i, x, y in zip(f["id"], f["x"], f["y"])}
    d = {i: xy[i] - np.array(START[i]) for i in START}

    # the left block does not move; the keystone moves target (cos D, -sin D), the right block
    # target (2 cos D, 0), both as rigid blocks
    assert np.all(d[1] == 0.0)
    for i in (2, 3):
        np.testing.assert_allclose(d[i], TARGET * np.array([c, -s]), rtol=0, atol=1e-12 * TARGET)
    for i in (4, 5):
        np.testing.assert_allclose(d[i], TARGET * np.array([2 * c, 0.0]), rtol=0, atol=1e-12 * TARGET)
    # both faults accumulate the target displacement: the keystone relative to the left block,
    # and relative to the right block
    left = np.hypot(*d[2])
    right = np.hypot(*(d[2] - d[4]))
    assert left == pytest.approx(TARGET, rel=1e-9)
    assert right == pytest.approx(TARGET, rel=1e-9)
    # the keystone slides down the right fault: its motion relative to the right block is
    # (-cos D, -sin D)
    np.testing.assert_allclose((d[2] - d[4]) / TARGET, [-c, -s], atol=1e-12)
    # stopped: no velocity left; moving discs do not rotate, the static one keeps its omega
    moving = f["id"] > 1
    assert np.all(f["vx"][moving] == 0.0) and np.all(f["vy"][moving] == 0.0)
    assert np.all(f["omegaz"][moving] == 0.0)
    assert f["omegaz"][~moving][0] == 3.0

    # step by step: displacement = rate * dt * steps until the target, then constant
    t = r.thermo()
    steps = np.array(t["Step"])
    disp = np.array([drive(k) for k in steps])
    assert r.out.count("target displacement 25 m reached at step 13") == 1
    np.testing.assert_allclose(t["f_ks[1]"], disp, rtol=1e-14, atol=0)
    np.testing.assert_allclose(np.array(t["v_x2"]) - START[2][0], disp * c, atol=1e-12 * TARGET)
    np.testing.assert_allclose(np.array(t["v_y2"]) - START[2][1], -disp * s, atol=1e-12 * TARGET)
    np.testing.assert_allclose(np.array(t["v_x4"]) - START[4][0], 2 * disp * c, atol=1e-12 * TARGET)
    assert np.all(np.array(t["v_y4"]) == START[4][1])
    # thermo vector: 1-2 fault displacements, 3 throw, 4 heave, 5 extension
    np.testing.assert_allclose(t["f_ks[2]"], disp, rtol=1e-14, atol=0)
    np.testing.assert_allclose(t["f_ks[3]"], disp * s, rtol=1e-14, atol=0)
    np.testing.assert_allclose(t["f_ks[4]"], disp * c, rtol=1e-14, atol=0)
    np.testing.assert_allclose(t["f_ks[5]"], 2 * disp * c, rtol=1e-14, atol=0)
    # the discs carry the block velocities while moving (from setup on), zero from the target on
    moving_steps = steps < 13
    assert moving_steps.sum() == 13 and steps[0] == 0
    np.testing.assert_allclose(np.array(t["v_vx2"])[moving_steps], RATE * c, rtol=1e-14)
    np.testing.assert_allclose(np.array(t["v_vy2"])[moving_steps], -RATE * s, rtol=1e-14)
    np.testing.assert_allclose(np.array(t["v_vx4"])[moving_steps], 2 * RATE * c, rtol=1e-14)
    for col in ("v_vx2", "v_vy2", "v_vx4", "v_vy4"):
        assert np.all(np.array(t[col])[~moving_steps] == 0.0), col
    assert np.all(np.array(t["v_vy4"]) == 0.0)


def test_keystone_at_target_end(lmp):
    r = lmp(keystone_deck(1000), dip=60, extra="at_target end")
    check_ok(r)
    t = r.thermo()
    assert t["Step"][-1] == 13      # ended at the step the target was reached, not after 1000
    assert t["f_ks[1]"][-1] == TARGET
    f = read_dump(r.workdir / "final.txt")
    assert f["x"][1] - START[2][0] == pytest.approx(TARGET * 0.5, rel=1e-12)


def test_at_target_end_lets_later_runs_run(lmp):
    """The timeout that ends the run is cleared afterwards: a later run with the fix still at
    its target ends at its first step; after unfix a run goes its full length."""
    deck = keystone_deck(1000) + "run 50\nthermo_style custom step\nunfix ks\nrun 7\n"
    r = lmp(deck, dip=60, extra="at_target end")
    check_ok(r)
    steps = [r.thermo(k)["Step"][-1] for k in range(-3, 0)]
    assert steps == [13, 14, 21]


def test_keystone_split_runs_and_restart(lmp):
    whole = lmp(keystone_deck(20, out="whole.txt"), dip=60, extra="")
    check_ok(whole)
    ref = read_dump(whole.workdir / "whole.txt")

    split = lmp(keystone_deck(6, 14, out="split.txt"), dip=60, extra="")
    check_ok(split)
    got = read_dump(split.workdir / "split.txt")
    for col in ("x", "y", "vx", "vy"):
        np.testing.assert_array_equal(got[col], ref[col])

    deck = keystone_deck(6, out="first.txt") + """
write_restart ks.restart
clear
read_restart ks.restart
comm_modify vel yes
""" + KEY_FIX + KEY_THERMO + "run 14\n" + DUMP.format("restarted.txt")
    r = lmp(deck, dip=60, extra="")
    check_ok(r)
    assert r.thermo(0)["f_ks[1]"][-1] == pytest.approx(12.0)
    t = r.thermo(1)
    assert t["f_ks[1]"][0] == pytest.approx(12.0)     # the displacement came back from the file
    assert t["f_ks[1]"][-1] == TARGET
    got = read_dump(r.workdir / "restarted.txt")
    for col in ("x", "y", "vx", "vy"):
        np.testing.assert_array_equal(got[col], ref[col])


def test_keystone_two_ranks_match_serial(lmp):
    deck = "processors 2 1 1\n" + keystone_deck(20)
    serial = lmp(deck.replace("processors 2 1 1\n", ""), dip=60, extra="")
    check_ok(serial)
    ref = read_dump(serial.workdir / "final.txt")
    t1 = serial.thermo()
    r = lmp(deck, np=2, dip=60, extra="")
    check_ok(r)
    assert "2 by 1 by 1 MPI processor grid" in r.out
    got = read_dump(r.workdir / "final.txt")
    # disc 2 crossed from the left sub-domain (x < 0) to the right one
    assert START[2][0] < 0 < got["x"][1]
    np.testing.assert_array_equal(got["id"], ref["id"])
    for col in ("x", "y", "vx", "vy"):
        np.testing.assert_allclose(got[col], ref[col], rtol=0, atol=1e-12)
    t2 = r.thermo()
    for col in t1:
        np.testing.assert_allclose(t2[col], t1[col], rtol=1e-14, atol=1e-12)


# ---------------------------------------------------------------------------------------------
# fix saltdem/tiltwall
# ---------------------------------------------------------------------------------------------

# free disc id 1 (integrated, no contacts), end-wall discs ids 2 and 3, a static disc id 4
TILT_SETUP = HEAD + """
create_atoms 1 single 0 0 0
create_atoms 1 single 50 -20 0
create_atoms 1 single 50 -10 0
create_atoms 1 single -50 -20 0
set type 1 diameter 2
set type 1 density/disc 2200
group free id 1
group wall id 2 3
pair_style saltdem/cohesive
pair_coeff * * 100 0 0.5 0 0 0
fix nve free saltdem/nve
"""
TILT_FIX = "fix tw wall saltdem/tiltwall tilt ${tilt} rate 2 target 2.5 ${extra}\n"
TILT_THERMO = """
timestep 0.1
variable x2 equal x[2]
variable y2 equal y[2]
variable x3 equal x[3]
variable vx2 equal vx[2]
variable vx1 equal vx[1]
variable vy1 equal vy[1]
thermo_style custom step f_tw[1] f_tw[2] f_tw[3] v_x2 v_y2 v_x3 v_vx2 v_vx1 v_vy1
thermo_modify format float %.17g
thermo 1
"""
TRATE, TTARGET = 2.0, 2.5     # 0.2 m per step, target at step 13 (shortened last step)


def tilt_deck(*runs, out="final.txt"):
    return TILT_SETUP + TILT_FIX + TILT_THERMO + "".join(f"run {n}\n" for n in runs) + DUMP.format(out)


@pytest.mark.parametrize("tilt,toward,g", [(5.0, "right", None), (30.0, "left", 3.7)])
def test_tiltwall_motion_and_gravity(lmp, tilt, toward, g):
    extra = f"toward {toward} gravity free" + (f" g {g}" if g else "")
    r = lmp(tilt_deck(20), tilt=tilt, extra=extra)
    check_ok(r)
    g = g or 9.81
    sense = 1.0 if toward == "right" else -1.0
    a = math.radians(tilt)
    t = r.thermo()
    steps = np.array(t["Step"])
    disp = np.minimum(TRATE * DT * steps, TTARGET)
    # the wall moves along the base (+x or -x) by rate * time, then stops at the target
    np.testing.assert_allclose(t["f_tw[1]"], disp, rtol=1e-14, atol=0)
    np.testing.assert_allclose(np.array(t["v_x2"]) - 50.0, sense * disp, atol=1e-12)
    np.testing.assert_allclose(np.array(t["v_x3"]) - 50.0, sense * disp, atol=1e-12)
    assert np.all(np.array(t["v_y2"]) == -20.0)
    moving = steps < 13
    np.testing.assert_allclose(np.array(t["v_vx2"])[moving], sense * TRATE, rtol=1e-14)
    assert np.all(np.array(t["v_vx2"])[~moving] == 0.0)
    assert "target displacement 2.5 m reached at step 13" in r.out
    # the gravity vector of the tilted frame
    np.testing.assert_allclose(t["f_tw[2]"], sense * g * math.sin(a), rtol=1e-14)
    np.testing.assert_allclose(t["f_tw[3]"], -g * math.cos(a), rtol=1e-14)

    # the free disc accelerates at g along the tilted vertical: v = a t exactly (velocity Verlet
    # under a constant force)
    f = read_dump(r.workdir / "final.txt")
    vx, vy = f["vx"][0], f["vy"][0]
    time = 20 * DT
    assert math.atan2(sense * vx, -vy) == pytest.approx(a, rel=1e-12)
    assert math.hypot(vx, vy) / time == pytest.approx(g, rel=1e-12)
    assert f["x"][0] == pytest.approx(0.5 * sense * g * math.sin(a) * time**2, rel=1e-12)
    assert f["y"][0] == pytest.approx(-0.5 * g * math.cos(a) * time**2, rel=1e-12)
    # the static disc feels no gravity (not in the gravity group, not integrated anyway)
    assert f["x"][3] == -50.0 and f["vx"][3] == 0.0 and f["vy"][3] == 0.0


def test_tiltwall_no_gravity_without_keyword(lmp):
    deck = tilt_deck(20) + 'print "HASGRAV $(is_defined(fix,tw_GRAVITY))"\n'
    r = lmp(deck, tilt=10, extra="")
    check_ok(r)
    assert "HASGRAV 0" in r.out
    t = r.thermo()
    assert np.all(np.array(t["v_vx1"]) == 0.0) and np.all(np.array(t["v_vy1"]) == 0.0)
    assert t["f_tw[1]"][-1] == TTARGET


def test_tiltwall_unfix_removes_gravity(lmp):
    deck = TILT_SETUP + TILT_FIX + TILT_THERMO + """
run 5
print "HASGRAV $(is_defined(fix,tw_GRAVITY))"
unfix tw
print "HASGRAV $(is_defined(fix,tw_GRAVITY))"
thermo_style custom step v_vx1 v_vy1 v_x2
thermo_modify format float %.17g
run 5
"""
    r = lmp(deck, tilt=10, extra="gravity free")
    check_ok(r)
    assert r.out.index("HASGRAV 1") < r.out.index("HASGRAV 0")
    t1, t2 = r.thermo(0), r.thermo(1)
    assert t1["v_vx1"][-1] > 0 and t1["v_vy1"][-1] < 0      # it fell while the fix was there
    # no force after unfix: the velocity stays, the wall stays
    assert np.all(np.array(t2["v_vx1"]) == t1["v_vx1"][-1])
    assert np.all(np.array(t2["v_vy1"]) == t1["v_vy1"][-1])
    assert np.all(np.array(t2["v_x2"]) == t1["v_x2"][-1])


def test_tiltwall_at_target_end(lmp):
    r = lmp(tilt_deck(1000), tilt=5, extra="at_target end gravity free")
    check_ok(r)
    t = r.thermo()
    assert t["Step"][-1] == 13
    assert t["f_tw[1]"][-1] == TTARGET


def test_tiltwall_restart_continues(lmp):
    whole = lmp(tilt_deck(20, out="whole.txt"), tilt=5, extra="gravity free")
    check_ok(whole)
    ref = read_dump(whole.workdir / "whole.txt")
    deck = tilt_deck(6, out="first.txt") + """
write_restart tw.restart
clear
read_restart tw.restart
comm_modify vel yes
fix nve free saltdem/nve
""" + TILT_FIX + TILT_THERMO + "run 14\n" + DUMP.format("restarted.txt")
    r = lmp(deck, tilt=5, extra="gravity free")
    check_ok(r)
    t = r.thermo(1)
    assert t["f_tw[1]"][0] == pytest.approx(1.2)
    assert t["f_tw[1]"][-1] == TTARGET
    got = read_dump(r.workdir / "restarted.txt")
    for col in ("x", "y", "vx", "vy"):
        np.testing.assert_allclose(got[col], ref[col], rtol=1e-14, atol=1e-14)
    assert got["x"][1] == pytest.approx(50.0 + TTARGET, rel=1e-14)


# ---------------------------------------------------------------------------------------------
# bad arguments of both fixes
# ---------------------------------------------------------------------------------------------

KEY_ERR = KEY_SETUP + "group none empty\n" + "fix ks ${fgroup} saltdem/keystone ${spec}\nrun 1\n"
KEY_OK = "dip 60 keystone key rate 20 target 25"


@pytest.mark.parametrize("fgroup,spec,words", [
    ("moving", KEY_OK.replace("dip 60", "dip 0"), ["dip = 0", "(0, 90)"]),
    ("moving", KEY_OK.replace("dip 60", "dip 90"), ["dip = 90"]),
    ("moving", KEY_OK.replace("dip 60", "dip -30"), ["dip = -30"]),
    ("moving", KEY_OK.replace("dip 60 ", ""), ["dip is required"]),
    ("moving", KEY_OK.replace("keystone key ", ""), ["keystone GROUP is required"]),
    ("moving", KEY_OK.replace("keystone key", "keystone nosuch"), ["group 'nosuch' does not exist"]),
    ("right", KEY_OK, ["keystone group key", "not in the fix group right"]),
    ("key", KEY_OK, ["right block", "has no atoms"]),
    ("moving", KEY_OK + " bogus 1", ["unknown keyword 'bogus'"]),
    ("moving", KEY_OK + " toward left", ["unknown keyword 'toward'"]),
    ("moving", KEY_OK.replace("rate 20", "rate 0"), ["rate = 0"]),
    ("moving", KEY_OK.replace("rate 20", "rate -1"), ["rate = -1"]),
    ("moving", KEY_OK.replace("target 25", "target 0"), ["target = 0"]),
    ("moving", KEY_OK.replace("rate 20 ", ""), ["rate = 0"]),
    ("moving", KEY_OK + " at_target never", ["at_target 'never'"]),
    ("moving", KEY_OK + " at_target", ["saltdem/keystone at_target"]),
    ("none", KEY_OK, ["group none has no atoms"]),
])
def test_keystone_errors(lmp, fgroup, spec, words):
    assert_error(lmp(KEY_ERR, fgroup=fgroup, spec=spec), "saltdem/keystone", *words)


def test_keystone_empty_keystone_group(lmp):
    deck = KEY_SETUP + "group kempty empty\nfix ks moving saltdem/keystone dip 60 keystone kempty " \
        "rate 20 target 25\nrun 1\n"
    assert_error(lmp(deck), "saltdem/keystone", "kempty has no atoms")


TILT_ERR = TILT_SETUP + "group none empty\n" + "fix tw ${fgroup} saltdem/tiltwall ${spec}\nrun 1\n"
TILT_OK = "tilt 5 rate 2 target 2.5"


@pytest.mark.parametrize("fgroup,spec,words", [
    ("wall", TILT_OK.replace("tilt 5", "tilt 0"), ["tilt = 0", "(0, 90)"]),
    ("wall", TILT_OK.replace("tilt 5", "tilt 90"), ["tilt = 90"]),
    ("wall", TILT_OK.replace("tilt 5", "tilt -5"), ["tilt = -5"]),
    ("wall", TILT_OK.replace("tilt 5 ", ""), ["tilt is required"]),
    ("wall", TILT_OK + " toward up", ["toward 'up'"]),
    ("wall", TILT_OK + " gravity nosuch", ["gravity group 'nosuch' does not exist"]),
    ("wall", TILT_OK + " gravity wall", ["gravity group", "wall"]),
    ("wall", TILT_OK + " g 0", ["g = 0"]),
    ("wall", TILT_OK + " bogus 1", ["unknown keyword 'bogus'"]),
    ("wall", TILT_OK.replace("rate 2", "rate 0"), ["rate = 0"]),
    ("wall", TILT_OK.replace("target 2.5", "target -1"), ["target = -1"]),
    ("wall", TILT_OK + " at_target maybe", ["at_target 'maybe'"]),
    ("none", TILT_OK, ["group none has no atoms"]),
])
def test_tiltwall_errors(lmp, fgroup, spec, words):
    assert_error(lmp(TILT_ERR, fgroup=fgroup, spec=spec), "saltdem/tiltwall", *words)


@pytest.mark.parametrize("style,args", [
    ("saltdem/keystone", "dip 60 keystone key rate 1 target 1"),
    ("saltdem/tiltwall", "tilt 5 rate 1 target 1"),
])
def test_fixes_move_in_the_section_plane_in_3d(lmp, style, args):
    """In 3D the section is the x-y plane: the blocks move in it, z unchanged
    (tests/test_walls_3d.py has the strips)."""
    deck = """
units si
dimension 3
atom_style sphere
boundary f f f
region box block -10 10 -10 10 -10 10
create_box 1 box
create_atoms 1 single 0 0 3
create_atoms 1 single 5 0 -3
group key id 1
group moving id 1 2
timestep 0.1
""" + f"fix m moving {style} {args}\nrun 20\n" + DUMP.format("f.txt").replace(
        "id x y vx vy omegaz", "id x y z vx vy omegaz")
    r = lmp(deck)
    check_ok(r)
    f = read_dump(r.workdir / "f.txt")
    np.testing.assert_array_equal(f["z"], [3.0, -3.0])
    assert f["x"][1] == pytest.approx(5.0 + 1.0 * (1.0 if "tiltwall" in style else 2 * math.cos(math.radians(60))))


# ---------------------------------------------------------------------------------------------
# saltdem/wall
# ---------------------------------------------------------------------------------------------

WALL_HEAD = HEAD.replace("create_box 1 box", "create_box 2 box")
# (type, x0, y0, x1, y1, R, group, density or None)
WALLS = [
    (1, -10.0, 0.0, 10.0, 5.0, 0.7, "w1", None),         # slanted, L/2R = 14.72: 15 segments
    (2, -20.0, -30.0, 20.0, -30.0, 1.0, "w2", 1000.0),   # L/2R = 20 exactly: 20 segments
    (1, 50.0, -50.0, 50.0, -40.3, 0.25, "w3", 3000.0),   # vertical, L/2R = 19.4: 20 segments
]


def wall_cmd(w):
    typ, x0, y0, x1, y1, rad, grp, rho = w
    return f"saltdem/wall {typ} {x0} {y0} {x1} {y1} {rad} group {grp}" + \
        (f" density {rho}" if rho else "") + "\n"


def test_wall_geometry(lmp):
    deck = WALL_HEAD + "create_atoms 1 single 0 80 0\n" + "".join(wall_cmd(w) for w in WALLS) + \
        'print "COUNTS $(count(all)) $(count(w1)) $(count(w2)) $(count(w3))"\n' + \
        "".join(f"write_dump {w[6]} custom {w[6]}.txt id type x y radius mass "
                "modify format float %.17g\n" for w in WALLS)
    r = lmp(deck)
    check_ok(r)
    ns = []
    ids = []
    for typ, x0, y0, x1, y1, rad, grp, rho in WALLS:
        rho = rho or 2200.0
        length = math.hypot(x1 - x0, y1 - y0)
        nseg = math.ceil(length / (2 * rad))
        f = read_dump(r.workdir / f"{grp}.txt")
        assert len(f["id"]) == nseg + 1, grp
        ns.append(nseg + 1)
        ids += list(f["id"])
        # along the segment: both end points, equal spacing <= 2R, as few discs as that allows
        u = np.array([x1 - x0, y1 - y0]) / length
        p = np.stack([f["x"] - x0, f["y"] - y0], axis=1)
        along = p @ u
        order = np.argsort(along)
        along, p = along[order], p[order]
        np.testing.assert_allclose(np.abs(p[:, 0] * u[1] - p[:, 1] * u[0]), 0.0, atol=1e-12)
        assert along[0] == pytest.approx(0.0, abs=1e-12)
        assert along[-1] == pytest.approx(length, rel=1e-14)
        gaps = np.diff(along)
        np.testing.assert_allclose(gaps, length / nseg, rtol=1e-12)
        assert gaps.max() <= 2 * rad * (1 + 1e-12)
        assert length / (nseg - 1) > 2 * rad      # one disc fewer would leave a gap
        np.testing.assert_array_equal(f["type"], typ)
        np.testing.assert_array_equal(f["radius"], rad)
        np.testing.assert_allclose(f["mass"], rho * math.pi * rad**2, rtol=1e-14)
    assert ns == [16, 21, 21]
    assert f"COUNTS {1 + sum(ns)} 16 21 21" in r.out
    # new, unique, contiguous atom IDs after the one created before
    assert sorted(ids) == list(range(2, 2 + sum(ns)))
    assert "saltdem/wall: 16 wall discs of radius 0.7" in r.out


WALL_MPI = """
units si
dimension 2
atom_style sphere
atom_modify map array
boundary ${bnd} p
comm_modify vel yes
processors * 1 1
region box block -10 10 -10 10 -1 1
create_box 1 box
BEFOREsaltdem/wall 1 -10 0 9 0 0.5 group base
saltdem/wall 1 0 -9.5 0 8.5 0.5 group mid
pair_style saltdem/cohesive
pair_coeff * * 1e9 0 0.5 0 0 0
run 0
print "COUNTS $(count(all)) $(count(base)) $(count(mid))"
write_dump all custom walls.txt id x y modify format float %.17g
"""


@pytest.mark.parametrize("np_", [1, 2])
def test_wall_on_subdomain_boundary(lmp, np_):
    # the 'mid' wall lies on x = 0, the boundary of the two sub-domains; the 'base' wall has a
    # disc there and one on the lower box edge
    r = lmp(WALL_MPI.replace("BEFORE", ""), np=np_, bnd="f f")
    check_ok(r)
    assert f"{np_} by 1 by 1 MPI processor grid" in r.out
    assert "COUNTS 39 20 19" in r.out
    f = read_dump(r.workdir / "walls.txt")
    assert sorted(f["id"]) == list(range(1, 40))
    pts = {(x, y) for x, y in zip(f["x"], f["y"])}
    assert len(pts) == 39
    expect = {(float(x), 0.0) for x in range(-10, 10)} | {(0.0, y + 0.5) for y in range(-10, 9)}
    assert pts == expect


@pytest.mark.parametrize("np_", [1, 2])
def test_wall_after_a_run(lmp, np_):
    # ghost atoms exist after a run; the new discs take their slots, so the command clears
    # them and the atom map first, as create_atoms does (without that, rebuilding the map read
    # uninitialised atom IDs: an error valgrind shows, this count need not)
    before = "create_atoms 1 random 30 4711 NULL overlap 1.0\nset type 1 diameter 1\n" \
             "set type 1 density/disc 2200\ncomm_modify cutoff 4\nrun 0\n"
    r = lmp(WALL_MPI.replace("BEFORE", before), np=np_, bnd="p p")
    check_ok(r)
    assert f"{np_} by 1 by 1 MPI processor grid" in r.out
    assert "COUNTS 69 20 19" in r.out
    f = read_dump(r.workdir / "walls.txt")
    assert sorted(f["id"]) == list(range(1, 70))
    walls = {(x, y) for i, x, y in zip(f["id"], f["x"], f["y"]) if i > 30}
    assert walls == {(float(x), 0.0) for x in range(-10, 10)} | {(0.0, y + 0.5) for y in range(-10, 9)}


def test_wall_end_on_upper_box_edge_is_an_error(lmp):
    # LAMMPS owns the box half-open: a disc at x = xhi would be lost at the next run
    deck = WALL_MPI.replace("BEFORE", "").replace("-10 0 9 0 0.5", "-10 0 10 0 0.5")
    assert_error(lmp(deck, bnd="f f"), "saltdem/wall", "end point (10, 0)", "outside the box")


WALL_ERR = WALL_HEAD + "create_atoms 1 single 0 0 0\nsaltdem/wall ${spec}\n"


@pytest.mark.parametrize("spec,words", [
    ("1 -120 0 10 0 1", ["end point (-120, 0)", "outside the box"]),
    ("1 -10 0 10 150 1", ["end point (10, 150)", "outside the box"]),
    ("0 -10 0 10 0 1", ["atom type 0"]),
    ("3 -10 0 10 0 1", ["atom type 3", "1..2"]),
    ("1 -10 0 10 0 0", ["radius R = 0"]),
    ("1 -10 0 10 0 -1", ["radius R = -1"]),
    ("1 -10 0 10 0 1 colour red", ["unknown keyword 'colour'"]),
    ("1 -10 0 10 0 1 density 0", ["density = 0"]),
    ("1 -10 0 10 0 1 group", ["saltdem/wall group"]),
    ("1 -10 0 10 0", ["saltdem/wall"]),
])
def test_wall_errors(lmp, spec, words):
    assert_error(lmp(WALL_ERR, spec=spec), "saltdem/wall", *words)


@pytest.mark.parametrize("head,words", [
    (HEAD.replace("dimension 2", "dimension 3").replace("boundary f f p", "boundary f f f"),
     ["give 'z Z0 Z1' in a box that is not periodic in z"]),
    (HEAD.replace("atom_style sphere", "atom_style atomic"), ["atom style sphere"]),
    ("units si\ndimension 2\natom_style sphere\n", ["before simulation box"]),
])
def test_wall_setup_errors(lmp, head, words):
    assert_error(lmp(head + "saltdem/wall 1 -10 0 10 0 1\n"), "saltdem/wall", *words)


@pytest.mark.parametrize("style", ["saltdem/nve/omp", "saltdem/nve"])
def test_messages_name_the_style_given(lmp, style):
    """A fix's messages name the style it was given as (the /omp variant included)."""
    deck = """units si
dimension 2
atom_style sphere
boundary p p p
region box block 0 10 0 10 -1 1
create_box 1 box
create_atoms 1 single 5 5 0
fix 1 all {} inertia 0.5
""".format(style)
    assert_error(lmp(deck), f"Fix {style}: inertia 0.5 must be >= 1")
