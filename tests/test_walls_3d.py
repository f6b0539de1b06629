"""3D building blocks: saltdem/wall extrudes its line along z into a strip of touching spheres
(the section in x-y, y up; z along strike), and the motion fixes move such strips in the
section plane, the same at every z.  Checked against the strip's geometry and the closed-form
motion; serial against two MPI ranks; 2D-only and 3D-only input refused."""
import math

import numpy as np
import pytest

from lmprun import assert_error, check_ok
from test_motion_fixes import read_dump

HEAD3 = """
units si
dimension 3
atom_style sphere
atom_modify map array
boundary f f {zb}
comm_modify vel yes
region box block -100 200 -100 200 0 60
create_box 1 box
"""
DUMP = "write_dump all custom {} id x y z vx vy vz omegaz mass radius modify format float %.17g\n"


def wall_deck(cmd, zb="p", extra=""):
    return HEAD3.format(zb=zb) + cmd + "\n" + extra + DUMP.format("walls.txt")


def test_strip_tiles_a_periodic_z_evenly(lmp):
    # a 100 m line at R 5: 11 discs along it; the 60 m period at R 5: 6 rows, 10 m apart
    r = lmp(wall_deck("saltdem/wall 1 0 0 100 0 5 group base"))
    check_ok(r)
    assert "saltdem/wall: 66 wall spheres of radius 5 from (0, 0) to (100, 0) in 6 rows along z" in r.out
    f = read_dump(r.workdir / "walls.txt")
    zs = np.unique(np.round(f["z"], 9))
    np.testing.assert_allclose(zs, 5.0 + 10.0 * np.arange(6), atol=1e-9)
    xs = np.unique(np.round(f["x"], 9))
    np.testing.assert_allclose(xs, 10.0 * np.arange(11), atol=1e-9)
    # touching spheres of the default density 2200 kg/m^3
    np.testing.assert_allclose(f["mass"], 2200.0 * 4.0 / 3.0 * math.pi * 125.0, rtol=1e-14)
    assert np.all(f["radius"] == 5.0)


def test_strip_between_given_z_includes_both_ends(lmp):
    r = lmp(wall_deck("saltdem/wall 1 0 0 0 50 5 z 3 27 group w", zb="f"))
    check_ok(r)
    f = read_dump(r.workdir / "walls.txt")
    zs = np.unique(np.round(f["z"], 9))
    assert zs[0] == 3.0 and zs[-1] == 27.0 and len(zs) == 4      # 24 m at spacing <= 10: 3 gaps
    assert np.max(np.diff(zs)) <= 10.0 + 1e-9
    assert len(f["x"]) == 6 * 4


@pytest.mark.parametrize("cmd,zb,words", [
    ("saltdem/wall 1 0 0 100 0 5", "f", ["give 'z Z0 Z1' in a box that is not periodic in z"]),
    ("saltdem/wall 1 0 0 100 0 5 z 0 70", "f", ["z 0 to 70 lies outside the box"]),
    ("saltdem/wall 1 0 0 100 0 5 z 0", "f", ["saltdem/wall z"]),
])
def test_bad_3d_walls_are_refused(lmp, cmd, zb, words):
    assert_error(lmp(wall_deck(cmd, zb=zb)), *words)


HEAD2 = """units si
dimension 2
atom_style sphere
boundary f f p
region box block -100 200 -100 200 -1 1
create_box 1 box
"""


def test_z_keyword_in_a_2d_deck_is_refused(lmp):
    deck = HEAD2 + "saltdem/wall 1 0 0 100 0 5 z 0 10\n"
    assert_error(lmp(deck), "'z Z0 Z1' extrudes a wall along z in a 3D deck; this deck is 2D")


FAULT3 = """
saltdem/wall 1 -60 0 40 0 5 group foot
saltdem/wall 1 50 0 150 0 5 group hang
pair_style saltdem/cohesive
pair_coeff * * 1e9 0 0.5 0 0 0
timestep 0.1
fix f hang saltdem/{style}
thermo_style custom step f_f[1]
thermo 1
run 20
"""


@pytest.mark.parametrize("style", ["fault dip 30 rate 20 target 25",
                                   "blocks rate 20 target 25 block hang slip 30 right"])
def test_fault_moves_a_3d_strip_in_the_section_plane(lmp, style):
    r = lmp(wall_deck("", extra=FAULT3.format(style=style)))
    check_ok(r)
    f = read_dump(r.workdir / "walls.txt")
    hang = f["x"] > 45.0
    n_rows = 6
    assert hang.sum() == 11 * n_rows and (~hang).sum() == 11 * n_rows
    a = math.radians(30.0)
    # every sphere of the hanging wall moved 25 m down-dip, its z unchanged; the footwall rests
    x0 = np.tile(50.0 + 10.0 * np.arange(11), n_rows)
    np.testing.assert_allclose(np.sort(f["x"][hang]), np.sort(x0 + 25.0 * math.cos(a)), atol=1e-9)
    np.testing.assert_allclose(f["y"][hang], -25.0 * math.sin(a), atol=1e-9)
    np.testing.assert_allclose(np.unique(np.round(f["z"], 9)), 5.0 + 10.0 * np.arange(6), atol=1e-9)
    assert np.all(f["vx"] == 0.0) and np.all(f["vz"] == 0.0)
    assert np.all(f["y"][~hang] == 0.0)


def test_3d_strip_motion_two_ranks_match_serial(lmp):
    deck = wall_deck("", extra=FAULT3.format(style="blocks rate 20 target 25 block hang slip 30 right "
                                                  "rotate 100 0 0.5"))
    one = lmp(deck)
    check_ok(one)
    two = lmp("processors 2 1 1\n" + deck, np=2)
    check_ok(two)
    a, b = read_dump(one.workdir / "walls.txt"), read_dump(two.workdir / "walls.txt")
    for c in ("x", "y", "z", "vx", "vy", "omegaz"):
        np.testing.assert_allclose(a[c], b[c], rtol=0, atol=1e-12)


# the fault deck between given z (a box not periodic in z, as a taper needs)
TAPER = FAULT3.replace(" 5 group foot", " 5 z 5 55 group foot").replace(" 5 group hang", " 5 z 5 55 group hang")


@pytest.mark.parametrize("style", ["fault dip 30 rate 20 target 25 taper 15 45",
                                   "blocks rate 20 target 25 taper 15 45 block hang slip 30 right"])
def test_taper_lets_the_throw_die_out_along_strike(lmp, style):
    """taper 15 45: the whole slip at z <= 15, none at z >= 45, linear between (a fault that
    dies out along strike); velocities scale with it."""
    r = lmp(wall_deck("", zb="f", extra=TAPER.format(style=style)))
    check_ok(r)
    f = read_dump(r.workdir / "walls.txt")
    hang = f["x"] > 45.0
    z = f["z"][hang]
    frac = np.clip((45.0 - z) / 30.0, 0.0, 1.0)
    assert set(np.round(frac, 6)) > {0.0, 1.0}          # rows with the whole, part and no slip
    a = math.radians(30.0)
    x0 = 50.0 + 10.0 * np.round((f["x"][hang] - 25.0 * frac * math.cos(a) - 50.0) / 10.0)
    np.testing.assert_allclose(f["x"][hang], x0 + 25.0 * frac * math.cos(a), atol=1e-9)
    np.testing.assert_allclose(f["y"][hang], -25.0 * frac * math.sin(a), atol=1e-9)
    assert np.all(f["vx"] == 0.0)                       # at the target: at rest
    assert np.all(f["y"][~hang] == 0.0)


@pytest.mark.parametrize("style,zb,words", [
    ("fault dip 30 rate 20 target 25 taper 15 45", "p", ["taper in a box periodic in z"]),
    ("fault dip 30 rate 20 target 25 taper 15 15", "f", ["taper z0 = z1 = 15"]),
    ("blocks rate 20 target 25 taper 15 45 block hang rotate 100 0 0.5", "f",
     ["a block that turns (rotate, tilt) cannot be tapered"]),
])
def test_bad_taper_is_refused(lmp, style, zb, words):
    extra = TAPER.format(style=style)
    if zb == "p":
        extra = extra.replace(" z 5 55", "")
    assert_error(lmp(wall_deck("", zb=zb, extra=extra)), *words)


def test_taper_in_a_2d_deck_is_refused(lmp):
    deck = HEAD2 + """saltdem/wall 1 50 0 150 0 5 group hang
fix f hang saltdem/fault dip 30 rate 20 target 25 taper 0 10
"""
    assert_error(lmp(deck), "taper scales the motion along z (strike), a 3D option; this deck is 2D")
