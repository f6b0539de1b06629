"""fix saltdem/fault: the hanging wall moves down-dip at its rate, stops at its target."""
import math

import pytest

from lmprun import assert_error, check_ok

DECK = """
units si
dimension 2
atom_style sphere
atom_modify map array
boundary f f p
comm_modify vel yes
region box block -100 100 -100 100 -1 1
create_box 1 box
create_atoms 1 single 0 0 0
create_atoms 1 single 20 0 0
set type 1 diameter 10
set type 1 density/disc 2200
group hw id 2
pair_style saltdem/cohesive
pair_coeff * * 1e9 0 0.5 0 0 0
fix fault hw saltdem/fault dip 60 rate 2 target 1 ${extra}
timestep 0.1
variable x2 equal x[2]
variable y2 equal y[2]
variable vx2 equal vx[2]
thermo_style custom step f_fault[1] f_fault[2] f_fault[3] v_x2 v_y2 v_vx2
thermo 1
run ${n}
"""


def test_moves_down_dip_then_stops(lmp):
    r = lmp(DECK, extra="", n=10)
    check_ok(r)
    t = r.thermo()
    # 0.2 m per step: 1 m after 5 steps, then no more
    assert t["f_fault[1]"][3] == pytest.approx(0.6)
    assert t["f_fault[1]"][-1] == pytest.approx(1.0)
    assert t["f_fault[2]"][-1] == pytest.approx(math.cos(math.radians(60)))     # heave
    assert t["f_fault[3]"][-1] == pytest.approx(math.sin(math.radians(60)))     # throw
    assert t["v_x2"][-1] == pytest.approx(20 + 0.5)
    assert t["v_y2"][-1] == pytest.approx(-math.sin(math.radians(60)))
    assert t["v_vx2"][2] == pytest.approx(2 * 0.5)     # the disc carries the fault velocity
    assert t["v_vx2"][-1] == 0.0
    assert "target displacement 1 m reached at step 5" in r.out


def test_toward_left_and_end_of_run(lmp):
    r = lmp(DECK, extra="toward left at_target end", n=100)
    check_ok(r)
    t = r.thermo()
    assert t["Step"][-1] < 10      # the run ended at the target, not after 100 steps
    assert t["v_x2"][-1] == pytest.approx(20 - 0.5)


def test_restart_continues_displacement(lmp):
    deck = DECK + """
write_restart f.restart
clear
read_restart f.restart
comm_modify vel yes
group hw id 2
fix fault hw saltdem/fault dip 60 rate 2 target 1
timestep 0.1
thermo_style custom step f_fault[1]
run 10
"""
    r = lmp(deck, extra="", n=3)
    check_ok(r)
    assert r.thermo(0)["f_fault[1]"][-1] == pytest.approx(0.6)
    t = r.thermo(1)
    assert t["f_fault[1]"][0] == pytest.approx(0.6)
    assert t["f_fault[1]"][-1] == pytest.approx(1.0)


@pytest.mark.parametrize("extra,words", [
    ("toward up", ["toward 'up'"]),
    ("at_target maybe", ["at_target 'maybe'"]),
    ("bogus 1", ["unknown keyword 'bogus'"]),
    ("dip", ["saltdem/fault dip"]),
])
def test_errors(lmp, extra, words):
    assert_error(lmp(DECK, extra=extra, n=1), "saltdem/fault", *words)


@pytest.mark.parametrize("old,new,words", [
    ("dip 60", "dip 90", ["dip = 90"]),
    ("rate 2", "rate -2", ["rate = -2"]),
    ("target 1", "target 0", ["target = 0"]),
    ("group hw id 2", "group hw id 3", ["has no atoms"]),
])
def test_bad_values(lmp, old, new, words):
    assert_error(lmp(DECK.replace(old, new), extra="", n=1), "saltdem/fault", *words)
