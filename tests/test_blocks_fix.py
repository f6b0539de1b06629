"""fix saltdem/blocks: rigid basement blocks with translation, slip and rotation kinematics and
drive windows, checked against their closed forms; per-block reports; restart, split runs, two
MPI ranks and OpenMP against one uninterrupted serial run; the paper's motion fixes as instances
of it (bit for bit); bad input gives a clean error naming the block."""
import math

import numpy as np
import pytest

from lmprun import assert_error, check_ok
from test_motion_fixes import HEAD, DUMP, read_dump

# discs far apart (no contacts): a static one (1), block a (2, 3) translating, block b (4, 5)
# slipping down a 60 degree fault dipping left from drive 5 to 15 m, block c (6, 7) turning
# about (20, -30) while translating.  Disc 2 starts left of x = 0 and crosses it (the boundary
# of the two sub-domains in the MPI run).
START = {1: (-80.0, 0.0), 2: (-3.0, 0.0), 3: (-20.0, 10.0), 4: (40.0, 0.0), 5: (50.0, -5.0),
         6: (10.0, -40.0), 7: (30.0, -20.0)}
SETUP = HEAD + "".join(f"create_atoms 1 single {x} {y} 0\n" for x, y in START.values()) + """
set type 1 diameter 2
set type 1 density/disc 2200
set group all omega 0 0 3
group a id 2 3
group b id 4 5
group c id 6 7
group moving union a b c
pair_style saltdem/cohesive
pair_coeff * * 1e9 0 0.5 0 0 0
"""
RATE, DT, TARGET = 20.0, 0.1, 25.0     # 2 m of drive per step, target at step 13 (1 m step)
MOVE = (0.6, -0.3)
DIP, FROM_B, TO_B = 60.0, 5.0, 15.0
PIVOT, W, MOVE_C = (20.0, -30.0), 2.0, (0.25, 0.5)     # W degrees per m of drive
FIX = ("fix bl moving saltdem/blocks rate 20 target 25 ${extra} block a move 0.6 -0.3 "
       "block b slip 60 left from 5 to 15 block c rotate 20 -30 2 move 0.25 0.5\n")
THERMO = """
timestep 0.1
thermo_style custom step f_bl[1] f_bl[1][1] f_bl[1][2] f_bl[1][3] f_bl[1][5] &
   f_bl[2][1] f_bl[2][3] f_bl[2][5] f_bl[3][1] f_bl[3][4] f_bl[3][5]
thermo_modify format float %.17g
thermo 1
"""


def deck(*runs, out="final.txt", fix=FIX, thermo=THERMO):
    return SETUP + fix + thermo + "".join(f"run {n}\n" for n in runs) + DUMP.format(out)


def closed_form(d):
    """Positions {id: (x, y)} and velocities at drive displacement d (block windows applied)."""
    pos, vel = {1: np.array(START[1])}, {1: np.zeros(2)}
    for i in (2, 3):
        pos[i] = np.array(START[i]) + d * np.array(MOVE)
        vel[i] = RATE * np.array(MOVE) * (d < TARGET)
    ab = min(max(d - FROM_B, 0.0), TO_B - FROM_B)
    u = np.array([-math.cos(math.radians(DIP)), -math.sin(math.radians(DIP))])
    for i in (4, 5):
        pos[i] = np.array(START[i]) + ab * u
        vel[i] = RATE * u * (FROM_B <= d < TO_B)
    th = math.radians(W) * d
    rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
    p = np.array(PIVOT) + d * np.array(MOVE_C)
    for i in (6, 7):
        pos[i] = p + rot @ (np.array(START[i]) - np.array(PIVOT))
        r = pos[i] - p
        vel[i] = RATE * (np.array(MOVE_C) + math.radians(W) * np.array([-r[1], r[0]])) * (d < TARGET)
    return pos, vel


def test_kinematics_against_closed_form(lmp):
    r = lmp(deck(20), extra="")
    check_ok(r)
    f = read_dump(r.workdir / "final.txt")
    pos, vel = closed_form(TARGET)
    for k, i in enumerate(f["id"].astype(int)):
        np.testing.assert_allclose([f["x"][k], f["y"][k]], pos[i], rtol=0, atol=1e-11, err_msg=str(i))
        assert f["vx"][k] == 0.0 and f["vy"][k] == 0.0     # at rest from the target on
    # the turning block's distances from its pivot are kept (rigid), and it has turned 50 deg
    p = np.array(PIVOT) + TARGET * np.array(MOVE_C)
    for k in (5, 6):
        d0 = np.hypot(*(np.array(START[k + 1]) - PIVOT))
        assert np.hypot(f["x"][k] - p[0], f["y"][k] - p[1]) == pytest.approx(d0, rel=1e-13)
    # the static disc keeps its spin; moving discs carry their block's spin (0 once stopped)
    assert f["omegaz"][0] == 3.0 and np.all(f["omegaz"][1:] == 0.0)

    # step by step: positions of discs 2, 4 and 6, velocities and the reports
    t = r.thermo()
    steps = np.array(t["Step"])
    drive = np.minimum(RATE * DT * steps, TARGET)
    np.testing.assert_allclose(t["f_bl[1]"], drive, rtol=1e-14, atol=0)
    assert "target displacement 25 m reached at step 13" in r.out
    # block a: displacement, heave, throw, progress
    np.testing.assert_allclose(t["f_bl[1][1]"], drive * math.hypot(*MOVE), rtol=1e-13)
    np.testing.assert_allclose(t["f_bl[1][2]"], drive * MOVE[0], rtol=1e-13)
    np.testing.assert_allclose(t["f_bl[1][3]"], -drive * MOVE[1], rtol=1e-13)
    np.testing.assert_allclose(t["f_bl[1][5]"], drive / TARGET, rtol=1e-13)
    # block b: only inside its window 5-15 m of drive
    ab = np.clip(drive - FROM_B, 0, TO_B - FROM_B)
    np.testing.assert_allclose(t["f_bl[2][1]"], ab, rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(t["f_bl[2][3]"], ab * math.sin(math.radians(DIP)), rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(t["f_bl[2][5]"], ab / (TO_B - FROM_B), rtol=1e-13, atol=1e-13)
    # block c: pivot displacement and turn
    np.testing.assert_allclose(t["f_bl[3][1]"], drive * math.hypot(*MOVE_C), rtol=1e-13)
    np.testing.assert_allclose(t["f_bl[3][4]"], drive * W, rtol=1e-13)
    np.testing.assert_allclose(t["f_bl[3][5]"], drive / TARGET, rtol=1e-13)


def test_positions_and_velocities_every_step(lmp):
    watch = "".join(f"variable x{i} equal x[{i}]\nvariable y{i} equal y[{i}]\n"
                    f"variable vx{i} equal vx[{i}]\nvariable vy{i} equal vy[{i}]\n"
                    for i in (2, 5, 7))
    cols = " ".join(f"v_x{i} v_y{i} v_vx{i} v_vy{i}" for i in (2, 5, 7))
    d = SETUP + FIX + watch + f"""
timestep 0.1
thermo_style custom step f_bl[1] {cols}
thermo_modify format float %.17g
thermo 1
run 15
"""
    r = lmp(d, extra="")
    check_ok(r)
    t = r.thermo()
    # block b starts inside step 3 (drive 4 -> 6) and stops inside step 8 (14 -> 16): it moves
    # by the part of those steps inside its window
    for k, step in enumerate(t["Step"]):
        dr = min(RATE * DT * step, TARGET)
        pos, vel = closed_form(dr)
        for i in (2, 5, 7):
            got = np.array([t[f"v_x{i}"][k], t[f"v_y{i}"][k]])
            np.testing.assert_allclose(got, pos[i], rtol=0, atol=1e-11, err_msg=f"{i} at {step}")
            gotv = np.array([t[f"v_vx{i}"][k], t[f"v_vy{i}"][k]])
            np.testing.assert_allclose(gotv, vel[i], rtol=0, atol=1e-11, err_msg=f"v{i} at {step}")


def test_split_runs_restart_mpi_and_omp_match_serial(lmp):
    whole = lmp(deck(20, out="whole.txt"), extra="")
    check_ok(whole)
    ref = read_dump(whole.workdir / "whole.txt")

    split = lmp(deck(6, 14, out="split.txt"), extra="")
    check_ok(split)
    got = read_dump(split.workdir / "split.txt")
    for col in ("x", "y", "vx", "vy", "omegaz"):
        np.testing.assert_array_equal(got[col], ref[col])

    restarted = lmp(deck(6, out="first.txt") + """
write_restart bl.restart
clear
read_restart bl.restart
comm_modify vel yes
""" + FIX + THERMO + "run 14\n" + DUMP.format("restarted.txt"), extra="")
    check_ok(restarted)
    assert restarted.thermo(1)["f_bl[1]"][0] == pytest.approx(12.0)
    got = read_dump(restarted.workdir / "restarted.txt")
    for col in ("x", "y", "vx", "vy", "omegaz"):
        np.testing.assert_array_equal(got[col], ref[col])

    two = lmp("processors 2 1 1\n" + deck(20, out="two.txt"), np=2, extra="")
    check_ok(two)
    assert "2 by 1 by 1 MPI processor grid" in two.out
    got = read_dump(two.workdir / "two.txt")
    assert START[2][0] < 0 < got["x"][1]
    for col in ("x", "y", "vx", "vy"):
        np.testing.assert_allclose(got[col], ref[col], rtol=0, atol=1e-12)

    omp = lmp(deck(20, out="omp.txt"), omp=2, extra="")
    check_ok(omp)
    got = read_dump(omp.workdir / "omp.txt")
    for col in ("x", "y", "vx", "vy"):
        np.testing.assert_array_equal(got[col], ref[col])


def test_phases_of_one_block(lmp):
    """A block given again moves in phases: block a slides 0.6 m right per m of drive up to
    10 m, rests, then turns 3 degrees per m about (-10, 5), which is where it was at 10 m, from
    14 m to the target; the reports follow its reference point (its first pivot, here 0 0)."""
    fix = ("fix bl moving saltdem/blocks rate 20 target 25 block a move 0.6 0 to 10 "
           "block b move 0 -1 block c move 1 0 block a rotate -4 5 3 from 14\n")
    thermo = """timestep 0.1
thermo_style custom step f_bl[1] f_bl[1][1] f_bl[1][2] f_bl[1][3] f_bl[1][4] f_bl[1][5] f_bl[2][3]
thermo_modify format float %.17g
thermo 1
"""
    r = lmp(deck(20, fix=fix, thermo=thermo), extra="")
    check_ok(r)
    f = read_dump(r.workdir / "final.txt")
    th = math.radians(3.0 * (TARGET - 14.0))
    rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
    p = np.array([-4.0, 5.0])
    for k, i in ((1, 2), (2, 3)):
        x10 = np.array(START[i]) + [6.0, 0.0]
        want = p + rot @ (x10 - p)
        np.testing.assert_allclose([f["x"][k], f["y"][k]], want, rtol=0, atol=1e-11)
    t = r.thermo()
    last = {c: t[c][-1] for c in t}
    ref = p + rot @ (np.array([6.0, 0.0]) - p)     # the reference point (0, 0) carried along
    assert last["f_bl[1][2]"] == pytest.approx(ref[0], abs=1e-11)
    assert last["f_bl[1][3]"] == pytest.approx(-ref[1], abs=1e-11)
    assert last["f_bl[1][1]"] == pytest.approx(np.hypot(*ref), abs=1e-11)
    assert last["f_bl[1][4]"] == pytest.approx(3.0 * 11.0, rel=1e-12)
    assert last["f_bl[1][5]"] == pytest.approx(1.0)
    assert last["f_bl[2][3]"] == pytest.approx(TARGET)
    # resting between the phases: drive 10-14 m is steps 5-7; progress 10/21 there
    steps = list(t["Step"])
    k6 = steps.index(6)
    assert t["f_bl[1][5]"][k6] == pytest.approx(10.0 / 21.0)
    assert t["f_bl[1][2]"][k6] == pytest.approx(6.0)


# the paper's motion fixes and their saltdem/blocks form give the same trajectories bit for bit
KEY = """
group left id 1
group key id 2 3
group right id 4 5 6 7
group mv union key right
"""


@pytest.mark.parametrize("old,new", [
    ("fix m mv saltdem/keystone dip 60 keystone key rate 20 target 25",
     "fix m mv saltdem/blocks rate 20 target 25 block key slip 60 right block right move $(2*cos(60*PI/180)) 0"),
    ("fix m right saltdem/fault dip 30 rate 20 target 25",
     "fix m right saltdem/blocks rate 20 target 25 block right slip 30 right"),
    ("fix m right saltdem/tiltwall tilt 5 rate 20 target 25 toward left",
     "fix m right saltdem/blocks rate 20 target 25 block right move -1 0"),
])
def test_paper_fixes_are_instances(lmp, old, new):
    runs = []
    for fix in (old, new):
        r = lmp(deck(20, out="f.txt", fix=KEY + fix + "\n",
                     thermo="timestep 0.1\nthermo_style custom step f_m[1]\n"), extra="")
        check_ok(r)
        runs.append(read_dump(r.workdir / "f.txt"))
    for col in ("x", "y", "vx", "vy", "omegaz"):
        np.testing.assert_array_equal(runs[0][col], runs[1][col])
    assert not np.all(runs[0]["x"] == np.array([START[i][0] for i in sorted(START)]))


@pytest.mark.parametrize("fix,words", [
    ("fix bl moving saltdem/blocks rate 20 target 25", ["no block given"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a", ["block a has no kinematics"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a from 3", ["block a has no kinematics"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block nosuch move 1 0", ["block group 'nosuch' does not exist"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a move 1 0 block a move 0 1 block b move 1 0 block c move 1 0",
     ["block a is given again with a window (from 0 to 25) that starts before its previous one ends"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a move 1 0 to 30", ["beyond the target 25"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a move 1 0 from 10 to 5", ["from 10 to 5"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a move 1 0 from 25", ["not before the target"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a slip 95 right", ["slip dip 95"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a slip 30 up", ["right or left"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a rotate 1 2", ["'rotate' needs 3 values"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a move 0 0", ["block a does not move"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a move 1 0 spin 3", ["unknown keyword 'spin'"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a move 1 0 block b move 1 0", ["atoms of the fix group moving are in no block"]),
    ("group ab union a b\nfix bl moving saltdem/blocks rate 20 target 25 block a move 1 0 block ab move 0 1 block c move 1 1",
     ["blocks a and ab overlap (2 atoms in both)"]),
    ("fix bl a saltdem/blocks rate 20 target 25 block a move 1 0 block b move 1 0", ["atoms of block b are not in the fix group a"]),
    ("fix bl moving saltdem/blocks rate -1 target 25 block a move 1 0", ["rate = -1 must be > 0"]),
    ("fix bl moving saltdem/blocks rate 20 target 25 block a move 1e300 0", ["move VX"]),
])
def test_bad_input_names_the_problem(lmp, fix, words):
    r = lmp(SETUP + fix + "\ntimestep 0.1\nrun 1\n", extra="")
    assert_error(r, *words)


@pytest.mark.parametrize("fix", [
    "fix bl moving saltdem/blocks rate 20 target 25 block a move 5 0 block b move 1 0 block c move 1 0",
    "fix bl moving saltdem/blocks rate 20 target 25 block a move 1 0 block b move 1 0 block c rotate 20 60 7",
])
def test_a_motion_out_of_the_box_is_refused(lmp, fix):
    """Block a would cross x = 100 at the target (move 5: -3 + 125); block c, turned by 175
    degrees about (20, 60), would cross y = 100.  Refused before the first step."""
    r = lmp(SETUP + fix + "\ntimestep 0.1\nrun 1\n", extra="")
    assert_error(r, "the motion to the target 25 m takes wall discs out of the box")


def test_fast_turn_warns_of_jumps(lmp):
    # 50 degrees per m of drive at 2 m per step: the far disc of block c jumps by metres
    fix = FIX.replace("rotate 20 -30 2", "rotate 20 -30 50")
    r = lmp(SETUP + fix + "timestep 0.1\nrun 1\n", extra="")
    check_ok(r)
    assert "the walls jump through discs" in r.out
