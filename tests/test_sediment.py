"""fix saltdem/sediment: syn-tectonic sedimentation and erosion.

A settled bed of about 60 cover discs (radii 20-30 m) with a basin in the middle, between wall
discs, made once per module; the decks below deposit into it.  "Frozen" decks integrate nothing
(the discs stay where the fix puts them: overlaps at insertion, bit-for-bit comparisons); the
others run with gravity.  Checked: fill to the base level, the area per interval at a rate,
overlaps, epochs in dumps and across restart files, a restart in the middle of deposition, 2 MPI
ranks and 2 OpenMP threads against 1, erosion, bad input, the scene decks' variables and the
figure's growth strata.

The decks step at 1/12 of the stable limit: the step the tests were designed at (0.5 of the
cover-wall limit 0.2 sqrt(m/kn_wall) of that time, 0.00166 s), which the measured limits now
report as 0.6 sqrt(m/kn_cover) = 1.2 sqrt(m/kn_wall); the rate and restart cases are tuned to
that step (at twice it the basin fills before the last interval)."""
import math
import os
import re
import subprocess

import numpy as np
import pytest

from lmprun import ROOT, assert_error, check_ok, lmp_path, run_lmp, run_cmd

RMIN, RMAX = 20.0, 30.0
TOL = 0.01                    # the fix's default overlap tolerance (fraction of the smaller radius)

# the bed: discs on a hexagonal lattice (radii from their IDs, so any number of ranks builds the
# same), a basin carved out of the middle, settled under gravity
BED = """
units si
dimension 2
atom_style sphere
atom_modify map array
boundary f f p
comm_modify vel yes
region box block -100 1100 -100 800 -1 1
create_box 3 box
lattice hex 62 origin 0.25 0.25 0
region fill block 31 969 31 340 -0.5 0.5 units box
create_atoms 1 region fill
variable d atom 2*(20+10*(0.5+0.5*sin(id*7.31)))
set type 1 diameter v_d
variable basin atom (x>300)&&(x<700)&&(y>150)
group basin variable basin
delete_atoms group basin
set type 1 density/disc 2200
saltdem/wall 3 -20 -20 1020 -20 20
saltdem/wall 3 -20 20 -20 700 20
saltdem/wall 3 1020 20 1020 700 20
group cover type 1
group pack type 1 2
LAWS
fix integ cover saltdem/nve
fix grav pack gravity 9.81 vector 0 -1 0
saltdem/timestep 0.08333333333333333
run 4000
fix calm cover viscous 1e7
run 12000
unfix calm
run 2000
velocity all set 0 0 0
write_data bed.data
"""

# cover 1 (saltdem/cohesive), salt 2 (saltdem/viscous, no discs unless a test makes some),
# walls 3
COEFFS = """
pair_coeff 1 1 saltdem/cohesive 2.5e9 8e8 0.5 1e8 1e8 0.5 damp 0.3 0.3
pair_coeff 1 3 saltdem/cohesive 1e10 8e8 1.0 1e8 0 0
pair_coeff 2 2 saltdem/viscous 5e8 1e10 contact 0
pair_coeff 1 2 saltdem/viscous 5e8 1e10 contact 0
pair_coeff 2 3 saltdem/viscous 5e8 1e10 contact 0
pair_coeff 3 3 none
neighbor 4 bin
neigh_modify exclude type 3 3
"""
LAWS = "pair_style hybrid saltdem/cohesive saltdem/viscous\n" + COEFFS

HEAD = """
units si
dimension 2
atom_style sphere
atom_modify map array
boundary f f p
comm_modify vel yes
fix ep all property/atom i_epoch ghost yes
read_data ${data}
reset_timestep 0
group cover type 1
group pack type 1 2
group wall type 3
""" + LAWS

DT_FROZEN = 0.0015625          # 1/640 s: a drive step of 10 m/s x dt = 1/64 m is exact
FROZEN = HEAD + f"timestep {DT_FROZEN}\n"
DYNAMIC = HEAD + """
fix integ cover saltdem/nve
fix grav pack gravity 9.81 vector 0 -1 0
saltdem/timestep 0.08333333333333333
"""
# the resumed half of a run (after read_restart: the same fixes with the same IDs)
RESUMED = """
read_restart ${restart}
comm_modify vel yes
fix ep all property/atom i_epoch ghost yes
""" + COEFFS + """
fix integ cover saltdem/nve
fix grav pack gravity 9.81 vector 0 -1 0
"""
SED = "fix sed cover saltdem/sediment ${mode} type 1 every ${every} rmin 20 rmax 30 " \
      "density 2200 seed 7 epoch i_epoch group pack ${extra}\n"
THERMO = "thermo_style custom step time atoms f_sed[1] f_sed[2] f_sed[3] f_sed[4] f_sed[5] " \
         "f_sed[6] f_sed[8] f_sed[9] f_sed[10] f_sed[11]\nthermo_modify format float %.17g\nthermo ${every_t}\n"
DUMP = "write_dump all custom {} id type x y radius i_epoch modify format float %.17g\n"


@pytest.fixture(scope="module")
def bed(tmp_path_factory):
    wd = tmp_path_factory.mktemp("bed")
    r = run_lmp(BED.replace("LAWS", LAWS), wd)
    check_ok(r)
    return wd / "bed.data"


def lmp_sed(bed, wd, deck, np=1, omp=0, mode="fill", every=10, extra="base 150", **var):
    """Run deck (with ${data} the bed) in wd; the fix line is SED with these values."""
    wd.mkdir(parents=True, exist_ok=True)
    return run_lmp(deck, wd, np=np, omp=omp, data=bed, mode=mode, every=every,
                   every_t=var.pop("every_t", every), extra=extra or "seed 7", **var)


def read_dump(path):
    lines = path.read_text().splitlines()
    head = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[head].split()[2:]
    data = np.array([[float(v) for v in l.split()] for l in lines[head + 1:]], ndmin=2)
    data = data[np.argsort(data[:, cols.index("id")])]
    return {c: data[:, k] for k, c in enumerate(cols)}


def epochs_logged(out):
    """(epoch, step, discs, area) of each interval, from the fix's log lines."""
    pat = r"fix saltdem/sediment sed: epoch (\d+) at step (\d+): deposited (\d+) discs \(([-+.\deE]+) m\^2\)"
    return [(int(e), int(s), int(n), float(a)) for e, s, n, a in re.findall(pat, out)]


def max_overlap(d, new):
    """Largest overlap of a new disc with any other disc, as a fraction of the smaller radius."""
    xy, r = np.c_[d["x"], d["y"]], d["radius"]
    worst = 0.0
    for k in np.flatnonzero(new):
        dist = np.hypot(*(xy - xy[k]).T)
        dist[k] = np.inf
        ov = (r + r[k] - dist) / np.minimum(r, r[k])
        worst = max(worst, ov.max())
    return worst


# ---------------------------------------------------------------------------------------------
# deposition
# ---------------------------------------------------------------------------------------------

def test_fill_to_the_base_level_without_overlaps(bed, tmp_path):
    deck = FROZEN + SED + THERMO + DUMP.format("before.txt") + "run 10\n" + DUMP.format("after.txt") + "run 10\n"
    r = lmp_sed(bed, tmp_path, deck, mode="fill", every=10, extra="base 250")
    check_ok(r)
    a, b = read_dump(tmp_path / "before.txt"), read_dump(tmp_path / "after.txt")
    new = ~np.isin(b["id"], a["id"])
    n = new.sum()
    ep = epochs_logged(r.out)
    assert [e[:3] for e in ep] == [(1, 10, n), (2, 20, 0)]    # filled at once: no room left after
    assert n > 30
    # cover discs of the radius law, at rest below the base level, epoch 1
    assert np.all(b["type"][new] == 1) and np.all(b["i_epoch"][new] == 1) and np.all(b["i_epoch"][~new] == 0)
    assert np.all((b["radius"][new] >= RMIN) & (b["radius"][new] <= RMAX))
    assert b["y"][new].max() <= 250.0 + 1e-9
    assert b["y"][new].max() > 250.0 - RMAX
    # the accounting: the fix's area is the new discs' area
    assert ep[0][3] == pytest.approx(np.sum(np.pi * b["radius"][new] ** 2), rel=1e-9)    # (10 digits)
    # no new disc overlaps another by more than the tolerance, and the old discs did not move
    assert max_overlap(b, new) <= TOL + 1e-9
    old = np.isin(b["id"], a["id"])
    assert np.array_equal(b["x"][old], a["x"]) and np.array_equal(b["y"][old], a["y"])
    # every column between the walls is filled to within a disc of the base level
    for x0 in range(40, 1000, 40):
        col = (np.abs(b["x"] - x0) < 30) & (b["type"] == 1)
        assert (b["y"][col] + b["radius"][col]).max() > 250.0 - 2 * RMAX, x0


def test_overlap_tolerance_is_kept(bed, tmp_path):
    """A larger tolerance admits more discs, none beyond it."""
    deck = FROZEN + SED + THERMO + "run 10\n" + DUMP.format("after.txt")
    counts, worst = {}, {}
    for tol in (0.0, 0.5):
        wd = tmp_path / str(tol)
        r = lmp_sed(bed, wd, deck, extra=f"base 250 overlap {tol}")
        check_ok(r)
        b = read_dump(wd / "after.txt")
        new = b["i_epoch"] > 0
        counts[tol], worst[tol] = new.sum(), max_overlap(b, new)
        assert worst[tol] <= tol + 1e-9
    assert counts[0.5] > counts[0.0] and worst[0.5] > 0.1


def test_rate_deposits_the_requested_area_per_interval(bed, tmp_path):
    R, L, every, n = 100.0, 1000.0, 100, 10
    deck = DYNAMIC + SED + THERMO + f"run {every * n}\n" + DUMP.format("after.txt")
    r = lmp_sed(bed, tmp_path, deck, mode=f"rate {R}", every=every, extra=f"base 500 length {L} settle 50 1e7")
    check_ok(r)
    dt = float(re.search(r"Time step\s*:\s*([-+.\deE]+)", r.out).group(1))
    ep = epochs_logged(r.out)
    assert len(ep) == n
    disc = math.pi * RMAX ** 2
    per = R * L * every * dt                    # requested area per interval
    assert per > 5 * disc                       # (several discs per interval)
    for k, (e, step, nd, area) in enumerate(ep):
        assert e == k + 1 and nd > 0
        assert abs(area - per) < disc, (k, area, per)
        # the shortfall carried over stays below one disc: the total keeps the rate
        assert abs(sum(a for *_, a in ep[:k + 1]) - per * (k + 1)) < disc
    th = r.thermo()
    assert th["f_sed[3]"][-1] == pytest.approx(sum(a for *_, a in ep), rel=1e-9)
    b = read_dump(tmp_path / "after.txt")
    new = b["i_epoch"] > 0
    assert new.sum() == sum(e[2] for e in ep) == th["f_sed[2]"][-1]
    assert np.sum(np.pi * b["radius"][new] ** 2) == pytest.approx(th["f_sed[3]"][-1], rel=1e-12)
    # settled gently: nothing was thrown out of the basin, the new discs lie on the bed
    assert b["y"][new].max() < 500 and b["y"][new].min() > 0


def test_rate_stops_at_the_base_level(bed, tmp_path):
    """More than the room below the base level: the rest is reported as bypassed."""
    deck = FROZEN + SED + THERMO + "run 20\n" + DUMP.format("after.txt")
    r = lmp_sed(bed, tmp_path, deck, mode="rate 1e7", every=10, extra="base 150")
    check_ok(r)
    th = r.thermo()
    b = read_dump(tmp_path / "after.txt")
    assert b["y"][b["i_epoch"] > 0].max() <= 150 + 1e-9
    requested = 1e7 * 1200 * 20 * DT_FROZEN   # rate x box length x time
    assert th["f_sed[6]"][-1] == pytest.approx(requested - th["f_sed[3]"][-1], rel=1e-9)


def test_drive_interval_from_a_motion_fix(bed, tmp_path):
    """every D drive f_ID[1]: one interval per D of the fix's displacement."""
    deck = FROZEN + """
variable rw atom (type==3)&&(x>1000)
group right variable rw
fix ext right saltdem/tiltwall tilt 5 rate 10 target 60
""" + SED + THERMO + "run 40\n"
    # 10 m/s x 1/640 s = 1/64 m per step: 0.125 m of drive every 8 steps, exactly
    r = lmp_sed(bed, tmp_path, deck, mode="rate 1", every=0.125, every_t=10, extra="base 150 drive f_ext[1]")
    check_ok(r)
    steps = [s for _, s, _, _ in epochs_logged(r.out)]
    # the drive reaches k x 0.125 m at the end of step 8 k; the discs come the step after
    assert steps == [8 * k + 1 for k in range(1, 5)]


# ---------------------------------------------------------------------------------------------
# a window that moves: deposition behind a migrating front (the prograding wedge), and a foreset
# ---------------------------------------------------------------------------------------------

# the front at 50 + 20 x step m: 250, 450, 650, 850 m at the intervals of steps 10, 20, 30, 40
FRONT = "variable front equal 50+20*step\n"


def front_at(step):
    return 50.0 + 20.0 * step


@pytest.mark.parametrize("foreset", [None, 0.5])
def test_fill_behind_a_migrating_front(bed, tmp_path, foreset):
    """x 0 v_front: each interval fills the window 0 to the front's position at that step, to the
    base level; with a foreset the deposit runs on past the front below a base level that falls
    by 0.5 per m.  A fix that kept the window of its first interval, or the box, fails."""
    extra = "base 400 x -100 v_front" + (f" foreset {foreset}" if foreset is not None else "")
    deck = FROZEN + FRONT + SED + THERMO + "run 40\n" + DUMP.format("after.txt")
    r = lmp_sed(bed, tmp_path, deck, mode="fill", every=10, extra=extra)
    check_ok(r)
    ep = epochs_logged(r.out)
    assert [e[:2] for e in ep] == [(k, 10 * k) for k in range(1, 5)]
    assert all(n > 0 for _, _, n, _ in ep)          # each move of the front opens room
    assert "in x -100 to 250 m" in r.out and "in x -100 to 850 m" in r.out
    b = read_dump(tmp_path / "after.txt")
    th = r.thermo()
    assert th["f_sed[10]"][-1] == -100 and th["f_sed[11]"][-1] == front_at(40)
    for k in range(1, 5):
        sel = b["i_epoch"] == k
        x, y, rad = b["x"][sel], b["y"][sel], b["radius"][sel]
        xf = front_at(10 * k)
        assert sel.sum() == ep[k - 1][2]
        if foreset is None:
            assert np.all(x + rad <= xf + 1e-9), k            # inside the window of its step
            assert np.all(y <= 400 + 1e-9)
        else:
            assert np.all(y <= 400 - foreset * np.maximum(0.0, x - xf) + 1e-9), k
        if k > 1:                                            # the deposit follows the front
            assert np.any(x > front_at(10 * (k - 1))), k
    # behind the last front every column is filled to within a disc of the base level
    for x0 in range(40, int(front_at(40)) - 60, 40):
        col = (np.abs(b["x"] - x0) < 30) & (b["type"] == 1)
        assert (b["y"][col] + b["radius"][col]).max() > 400.0 - 2 * RMAX, x0
    if foreset is None:
        assert not np.any((b["x"] + b["radius"] > front_at(40) + 1e-9) & (b["i_epoch"] > 0))
    else:
        # foresets: the first three epochs' fronts stand over the basin (floor at 150 m), where
        # the level falling 0.5 per m leaves room hundreds of m ahead of the front
        for k in range(1, 4):
            sel = b["i_epoch"] == k
            assert np.any(b["x"][sel] > front_at(10 * k) + 100), k


def test_rate_per_length_of_a_growing_window(bed, tmp_path):
    """Rate mode without 'length': R x (the window's length at the interval) x time."""
    R, every = 200.0, 100
    deck = FROZEN + "variable front equal 100+step\n" + SED + THERMO + f"run {4 * every}\n"
    r = lmp_sed(bed, tmp_path, deck, mode=f"rate {R}", every=every, extra="base 500 x 0 v_front")
    check_ok(r)
    ep = epochs_logged(r.out)
    assert len(ep) == 4
    disc = math.pi * RMAX ** 2
    total = 0.0
    for k, (_, step, _, area) in enumerate(ep):
        per = R * (100.0 + step) * every * DT_FROZEN
        total += per
        assert abs(area - per) < disc, (k, area, per)
        assert abs(sum(a for *_, a in ep[:k + 1]) - total) < disc
    # the requests differ by the window's growth: a fixed length would not see it
    assert ep[3][3] - ep[0][3] > 2 * disc


def test_restart_with_a_migrating_window_continues_exactly(bed, tmp_path):
    """The window is evaluated at each interval from its variables (here of the model time,
    which the restart file keeps): a run split at step 25 deposits what the whole run does."""
    front = f"variable front equal 250+20*time/{DT_FROZEN}\n"     # 250 + 20 x step m
    resumed = RESUMED.replace("fix integ cover saltdem/nve\n", "")
    kw = dict(mode="fill", every=10, extra="base 400 x -100 v_front foreset 1")
    r = lmp_sed(bed, tmp_path / "whole", FROZEN + front + SED + THERMO + "run 40\n" + DUMP.format("w.txt"), **kw)
    check_ok(r)
    r1 = lmp_sed(bed, tmp_path / "split", FROZEN + front + SED + THERMO + "run 25\nwrite_restart h.restart\n", **kw)
    check_ok(r1)
    r2 = lmp_sed(bed, tmp_path / "split", resumed + front + SED + THERMO + "run 15\n" + DUMP.format("s.txt"),
                 restart="h.restart", **kw)
    check_ok(r2)
    assert len(epochs_logged(r.out)) == 4
    assert epochs_logged(r1.out) + epochs_logged(r2.out) == epochs_logged(r.out)
    a, b = read_dump(tmp_path / "whole" / "w.txt"), read_dump(tmp_path / "split" / "s.txt")
    for c in a:
        assert np.array_equal(a[c], b[c]), c
    t1, t2 = r.thermo(), r2.thermo()
    assert t2["f_sed[11]"][-1] == t1["f_sed[11]"][-1] == 1050.0
    # the split run's resumed half reports the window of the interval before the restart
    assert t2["f_sed[11]"][0] == t1["f_sed[11]"][t1["Step"].index(20.0)] == 650.0


def test_two_ranks_fill_behind_a_front_as_one(bed, tmp_path):
    deck = FROZEN + FRONT + SED + THERMO + "run 30\n" + DUMP.format("after.txt")
    out = {}
    for np_ in (1, 2):
        wd = tmp_path / f"np{np_}"
        r = lmp_sed(bed, wd, deck, np=np_, mode="fill", every=10, extra="base 400 x -100 v_front foreset 0.5")
        check_ok(r)
        out[np_] = (read_dump(wd / "after.txt"), epochs_logged(r.out))
    (a, ea), (b, eb) = out[1], out[2]
    assert ea == eb and len(ea) == 3
    for c in a:
        assert np.array_equal(a[c], b[c]), c


# ---------------------------------------------------------------------------------------------
# epochs, restart, MPI, OpenMP
# ---------------------------------------------------------------------------------------------

def test_epochs_in_dumps_and_restart_files(bed, tmp_path):
    deck = DYNAMIC + SED + THERMO + "run 300\n" + DUMP.format("a.txt") + "write_restart sed.restart\n"
    r = lmp_sed(bed, tmp_path, deck, mode="rate 30", every=100, extra="base 500 length 1000 offset 1000")
    check_ok(r)
    a = read_dump(tmp_path / "a.txt")
    new = a["i_epoch"] > 0
    assert set(np.unique(a["i_epoch"][new])) == {1001, 1002, 1003}
    assert np.all(a["i_epoch"][~new] == 0)
    # later epochs, later IDs
    order = np.argsort(a["id"][new])
    assert np.all(np.diff(a["i_epoch"][new][order]) >= 0)
    back = RESUMED + "run 0\n" + DUMP.format("b.txt")
    r = run_lmp(back, tmp_path, restart="sed.restart")
    check_ok(r)
    b = read_dump(tmp_path / "b.txt")
    assert np.array_equal(a["id"], b["id"]) and np.array_equal(a["i_epoch"], b["i_epoch"])


@pytest.mark.parametrize("model", ["frozen", "moving"])
@pytest.mark.parametrize("interval", ["steps", "drive"])
def test_restart_in_the_middle_of_deposition_continues_exactly(bed, tmp_path, interval, model):
    """Split at step 399 of 600: a deposition is due at step 400 (decided at the end of step
    399, before the restart file is written) and the discs of step 300 are still settling.  The
    resumed run deposits the same discs: the same intervals, IDs, radii (the generator's state)
    and epochs.  With the model at rest it places them bit for bit; in a moving model the
    positions agree to the round-off of a restart (the neighbour lists are built again, which
    changes the order forces are summed in; a settling granular pack amplifies that)."""
    drive = "" if interval == "steps" else "drive v_drv"
    every = 100 if interval == "steps" else 0.125
    drv = "variable drv equal (step+1)/800\n"      # 0.125 at the end of steps 99, 199, ...: exact
    if model == "frozen":
        setup, resumed, mode = FROZEN, RESUMED.replace("fix integ cover saltdem/nve\n", ""), "rate 100"
        extra = f"base 500 {drive}"
    else:
        setup, resumed, mode = DYNAMIC, RESUMED, "rate 100"
        extra = f"base 500 length 1000 settle 150 1e7 {drive}"
    whole = setup + drv + SED + THERMO + "run 600\n" + DUMP.format("whole.txt")
    r = lmp_sed(bed, tmp_path / "whole", whole, mode=mode, every=every, every_t=100, extra=extra)
    check_ok(r)
    first = setup + drv + SED + THERMO + "run 399\nwrite_restart half.restart\n"
    r1 = lmp_sed(bed, tmp_path / "split", first, mode=mode, every=every, every_t=100, extra=extra)
    check_ok(r1)
    second = resumed + drv + SED + THERMO + "run 201\n" + DUMP.format("split.txt")
    r2 = lmp_sed(bed, tmp_path / "split", second, mode=mode, every=every, every_t=100, extra=extra,
                 restart="half.restart")
    check_ok(r2)
    e_whole = epochs_logged(r.out)
    e_split = epochs_logged(r1.out) + epochs_logged(r2.out)
    assert len(e_whole) == 6 and all(n > 2 for _, _, n, _ in e_whole)
    assert e_split == e_whole
    a, b = read_dump(tmp_path / "whole" / "whole.txt"), read_dump(tmp_path / "split" / "split.txt")
    assert np.array_equal(a["id"], b["id"]) and np.array_equal(a["type"], b["type"])
    assert np.array_equal(a["radius"], b["radius"]) and np.array_equal(a["i_epoch"], b["i_epoch"])
    if model == "frozen":
        assert np.array_equal(a["x"], b["x"]) and np.array_equal(a["y"], b["y"])
    else:
        np.testing.assert_allclose(b["x"], a["x"], rtol=0, atol=1e-3)
        np.testing.assert_allclose(b["y"], a["y"], rtol=0, atol=1e-3)
    t1, t2 = r.thermo(), r2.thermo()
    for k in ("f_sed[1]", "f_sed[2]", "f_sed[3]", "f_sed[6]"):
        assert t2[k][-1] == t1[k][-1], k


def test_restart_between_intervals_keeps_the_next_drive_displacement(bed, tmp_path):
    """Split at step 350, half-way to the next drive interval: the resumed run waits for it."""
    drv = "variable drv equal (step+1)/800\n"
    resumed = RESUMED.replace("fix integ cover saltdem/nve\n", "")
    kw = dict(mode="rate 100", every=0.125, every_t=50, extra="base 500 drive v_drv")
    r = lmp_sed(bed, tmp_path / "whole", FROZEN + drv + SED + THERMO + "run 600\n", **kw)
    check_ok(r)
    r1 = lmp_sed(bed, tmp_path / "split", FROZEN + drv + SED + THERMO + "run 350\nwrite_restart half.restart\n", **kw)
    check_ok(r1)
    r2 = lmp_sed(bed, tmp_path / "split", resumed + drv + SED + THERMO + "run 250\n", restart="half.restart", **kw)
    check_ok(r2)
    steps = [s for _, s, _, _ in epochs_logged(r.out)]
    assert steps == [100, 200, 300, 400, 500, 600]
    assert epochs_logged(r1.out) + epochs_logged(r2.out) == epochs_logged(r.out)


def test_two_ranks_place_the_same_discs_as_one(bed, tmp_path):
    """The candidates are decided from the gathered surface discs, sorted by ID, and one
    generator: with the model at rest 2 ranks place every disc bit for bit as 1 rank."""
    deck = FROZEN + SED + THERMO + "run 30\n" + DUMP.format("after.txt")
    out = {}
    for np_ in (1, 2):
        wd = tmp_path / f"np{np_}"
        r = lmp_sed(bed, wd, deck, np=np_, mode="rate 1000", every=10, extra="base 500")
        check_ok(r)
        assert f"{np_} by 1 by 1 MPI processor grid" in r.out
        out[np_] = (read_dump(wd / "after.txt"), epochs_logged(r.out))
    (a, ea), (b, eb) = out[1], out[2]
    assert len(ea) == 3 and all(n > 3 for _, _, n, _ in ea)
    assert ea == eb
    for c in a:
        assert np.array_equal(a[c], b[c]), c


def test_two_ranks_agree_with_one_in_a_moving_model(bed, tmp_path):
    deck = DYNAMIC + SED + THERMO + "run 400\n" + DUMP.format("after.txt")
    out = {}
    for np_ in (1, 2):
        wd = tmp_path / f"np{np_}"
        r = lmp_sed(bed, wd, deck, np=np_, mode="rate 30", every=100, extra="base 500 length 1000 settle 50 1e7")
        check_ok(r)
        out[np_] = (read_dump(wd / "after.txt"), epochs_logged(r.out))
    (a, ea), (b, eb) = out[1], out[2]
    assert [e[:3] for e in ea] == [e[:3] for e in eb] and len(ea) == 4
    assert np.array_equal(a["id"], b["id"]) and np.array_equal(a["radius"], b["radius"])
    assert np.array_equal(a["i_epoch"], b["i_epoch"])
    # the ranks sum forces in another order: round-off only
    np.testing.assert_allclose(b["x"], a["x"], rtol=0, atol=1e-6)
    np.testing.assert_allclose(b["y"], a["y"], rtol=0, atol=1e-6)


def test_openmp_threads_agree_with_serial(bed, tmp_path):
    deck = DYNAMIC + SED + THERMO + "run 300\n" + DUMP.format("after.txt")
    out = {}
    for omp in (0, 2):
        wd = tmp_path / f"omp{omp}"
        r = lmp_sed(bed, wd, deck, omp=omp, mode="rate 30", every=100, extra="base 500 length 1000")
        check_ok(r)
        if omp:
            assert "Last active /omp style is pair_style saltdem/viscous" in r.out
        out[omp] = (read_dump(wd / "after.txt"), epochs_logged(r.out))
    (a, ea), (b, eb) = out[0], out[2]
    assert [e[:3] for e in ea] == [e[:3] for e in eb] and len(ea) == 3
    assert np.array_equal(a["id"], b["id"]) and np.array_equal(a["radius"], b["radius"])
    np.testing.assert_allclose(b["y"], a["y"], rtol=0, atol=1e-6)


# ---------------------------------------------------------------------------------------------
# erosion
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("level", ["120", "v_env"])
def test_erosion_removes_only_discs_above_the_level(bed, tmp_path, level):
    """Cover discs whose centre lies above the level go; walls above it and everything below stay."""
    deck = FROZEN + "variable env atom 60+0.15*x\n" + SED + THERMO + DUMP.format("before.txt") + "run 5\n" \
        + DUMP.format("after.txt")
    r = lmp_sed(bed, tmp_path, deck, mode="none", every=5, every_t=5, extra=f"erode {level}")
    check_ok(r)
    a, b = read_dump(tmp_path / "before.txt"), read_dump(tmp_path / "after.txt")
    lev = 120.0 if level == "120" else 60 + 0.15 * a["x"]
    above = (a["type"] == 1) & (a["y"] > lev)
    assert above.sum() > 5 and (~above & (a["type"] == 1)).sum() > 5
    assert np.array_equal(b["id"], a["id"][~above])
    assert (b["type"] == 3).sum() == (a["type"] == 3).sum()      # walls reach far above: kept
    th = r.thermo()
    assert th["f_sed[4]"][-1] == above.sum()
    assert th["f_sed[5]"][-1] == pytest.approx(np.sum(np.pi * a["radius"][above] ** 2), rel=1e-12)
    assert th["Atoms"][-1] == len(b["id"])


def test_erosion_then_deposition_in_one_interval(bed, tmp_path):
    """Erosion first, then the fill: the new discs stay below both levels' lower one."""
    deck = FROZEN + SED + THERMO + "run 10\n" + DUMP.format("after.txt")
    r = lmp_sed(bed, tmp_path, deck, mode="fill", every=10, extra="base 100 erode 100")
    check_ok(r)
    b = read_dump(tmp_path / "after.txt")
    assert b["y"][b["type"] == 1].max() <= 100 + 1e-9
    assert (b["i_epoch"] > 0).sum() > 3


# ---------------------------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------------------------

BAD = [
    ("fill", "base 5000", ["saltdem/sediment", "base level = 5000", "outside the box"]),
    ("fill", "base -500", ["saltdem/sediment", "base level = -500", "outside the box"]),
    ("rate -1", "base 150", ["saltdem/sediment", "rate = -1", "must be >= 0"]),
    ("fill", "base 150 rmax 60", ["saltdem/sediment", "rmax = 60", "largest disc of type 1"]),
    ("fill", "base 150 rmin 10", ["saltdem/sediment", "lightest new disc", "type 1"]),
    ("fill", "base 150 rmin 29 rmax 25", ["saltdem/sediment", "rmin = 29", "rmax = 25"]),
    ("fill", "base 150 epoch i_nothere", ["saltdem/sediment", "epoch i_nothere"]),
    ("fill", "base 150 drive v_nothere", ["saltdem/sediment", "drive variable nothere"]),
    ("fill", "base 150 drive f_nothere[1]", ["saltdem/sediment", "drive fix ID nothere"]),
    ("fill", "base v_atomic", ["saltdem/sediment", "base level v_atomic", "equal-style"]),
    ("fill", "base 150 erode 9000", ["saltdem/sediment", "erode level = 9000", "outside the box"]),
    ("fill", "base 150 dist lognormal", ["saltdem/sediment", "dist 'lognormal'"]),
    ("fill", "base 150 overlap 1.5", ["saltdem/sediment", "overlap = 1.5"]),
    ("fill", "base 150 x 500 100", ["saltdem/sediment", "x 500 100"]),
    ("fill", "base 150 x 0 v_nothere", ["saltdem/sediment", "x window variable nothere", "does not exist"]),
    ("fill", "base 150 x v_atomic 500", ["saltdem/sediment", "x window variable atomic", "equal-style"]),
    ("fill", "base 150 x 0 five", ["saltdem/sediment", "x window end 'five'", "v_NAME"]),
    ("fill", "base 150 x 0 500 foreset -1", ["saltdem/sediment", "foreset = -1", ">= 0"]),
    ("fill", "base 150 foreset 0.5", ["saltdem/sediment", "foreset needs the window"]),
    ("fill", "base 150 colour red", ["saltdem/sediment", "unknown keyword 'colour'"]),
    ("fill", "", ["saltdem/sediment", "'base'", "required"]),
    ("sprinkle", "base 150", ["saltdem/sediment", "mode 'sprinkle'"]),
    ("none", "base 150", ["saltdem/sediment", "mode none needs 'erode LEVEL'"]),
]


@pytest.mark.parametrize("mode,extra,words", BAD, ids=[b[1] or b[0] for b in BAD])
def test_bad_input_is_a_clear_error(bed, tmp_path, mode, extra, words):
    deck = FROZEN + "variable atomic atom y\n" + SED + "run 10\n"
    assert_error(lmp_sed(bed, tmp_path, deck, mode=mode, extra=extra), *words)


def test_bad_every_is_a_clear_error(bed, tmp_path):
    deck = FROZEN + SED + "run 10\n"
    assert_error(lmp_sed(bed, tmp_path, deck, every=2.5), "saltdem/sediment", "every = 2.5", "whole number")
    deck = FROZEN + SED.replace("${every}", "-3") + "run 10\n"
    assert_error(lmp_sed(bed, tmp_path, deck), "saltdem/sediment", "every = -3", "> 0")


def test_a_base_level_variable_that_leaves_the_box_is_an_error(bed, tmp_path):
    deck = FROZEN + "variable bl equal 150+step*1000\n" + SED + "run 20\n"
    r = lmp_sed(bed, tmp_path, deck, extra="base v_bl")
    assert_error(r, "saltdem/sediment", "base level = 10150", "outside the box")


def test_a_window_whose_ends_cross_is_an_error(bed, tmp_path):
    """x v_front 500: the front passes the window's other end by step 30 (450 m at 20, 650 at 30)."""
    deck = FROZEN + FRONT + SED + "run 40\n"
    r = lmp_sed(bed, tmp_path, deck, extra="base 400 x v_front 500")
    assert_error(r, "saltdem/sediment", "x v_front 500 at step 30", "650 to 500 m", "low end must be below")


def test_a_group_or_type_without_the_cover_law_is_an_error(bed, tmp_path):
    # discs of the salt law (type 2) in the fix's group
    deck = FROZEN + "set group cover type 2\ngroup salt type 2\n" + \
        SED.replace("fix sed cover", "fix sed salt") + "run 10\n"
    assert_error(lmp_sed(bed, tmp_path, deck, extra="base 150"), "saltdem/sediment", "group salt",
                 "type 2", "no cover law")
    # new discs of a type without the cover law
    deck = FROZEN + SED.replace("type 1", "type 2") + "run 10\n"
    assert_error(lmp_sed(bed, tmp_path, deck, extra="base 150"), "saltdem/sediment", "type 2",
                 "no cover law")


# ---------------------------------------------------------------------------------------------
# the scene decks' variables and the figure
# ---------------------------------------------------------------------------------------------

def run_scene(deck, wd, **var):
    cmd = [lmp_path(), "-in", str(ROOT / "examples" / deck), "-log", "log.lammps", "-echo", "none",
           "-var", "root", str(ROOT)]
    for k, v in var.items():
        cmd += ["-var", k, *str(v).split()]
    return run_cmd(cmd, cwd=wd, capture_output=True, text=True, timeout=900,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))


@pytest.fixture(scope="module")
def syntectonic(tmp_path_factory):
    """Expt 1 at the tiny preset, filling the hanging-wall low every 0.5 m of displacement."""
    wd = tmp_path_factory.mktemp("expt1_sed")
    proc = run_scene("expt1.in", wd, preset="tiny", sediment="fill", sed_every=0.5, base_level=2750)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    return wd, proc


def scene_dumps(wd, name):
    files = sorted(wd.glob(f"dump.{name}.*.txt"), key=lambda p: int(p.name.split(".")[2]))
    return files, [read_dump(f) for f in files]


def test_scene_deck_deposits_growth_strata(syntectonic):
    wd, proc = syntectonic
    assert "scene: sediment fill every 0.5 m" in proc.stdout
    assert "f_sed[1]" in proc.stdout                     # epoch in the scene's thermo
    _, frames = scene_dumps(wd, "expt1")
    last = frames[-1]
    growth = last["i_marker"] >= 1000
    assert growth.sum() > 0
    assert np.all(last["type"][growth] == 1)
    assert set(np.unique(last["i_marker"][growth])) <= {1001, 1002, 1003, 1004}
    assert np.all(frames[0]["i_marker"] < 1000)
    # below the base level when deposited (the frames come later: allow the settling)
    assert last["y"][growth].max() < 2750 + 250


def test_scene_deck_resumes_with_sedimentation(syntectonic, tmp_path):
    """The restart file of the syntectonic run, resumed with the same variables."""
    wd, _ = syntectonic
    res = sorted(wd.glob("expt1.restart.[ab]"), key=lambda p: p.stat().st_mtime)
    for f in list(wd.glob("pack_*.data")) + res:
        (tmp_path / f.name).write_bytes(f.read_bytes())
    proc = run_scene("expt1.in", tmp_path, preset="tiny", sediment="fill", sed_every=0.5, base_level=2750,
                     restart=res[0].name)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    assert "resumed from" in proc.stdout and "scene: sediment fill" in proc.stdout


def test_scene_decks_without_sedimentation_have_no_fix(tmp_path):
    proc = run_scene("expt3.in", tmp_path, preset="tiny", target=0.2, f=0.2)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    assert "saltdem/sediment" not in proc.stdout and "scene: sediment" not in proc.stdout


def test_scene_deck_erosion_alone_and_bad_mode(tmp_path):
    wd = tmp_path / "erode"
    wd.mkdir()
    proc = run_scene("expt3.in", wd, preset="tiny", target=0.2, f=0.2, sed_every=0.1, erosion_level=2000)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    assert "scene: sediment none" in proc.stdout and "erode 2000" in proc.stdout
    assert re.search(r"eroded [1-9]\d* discs", proc.stdout)
    wd = tmp_path / "bad"
    wd.mkdir()
    proc = run_scene("expt3.in", wd, preset="tiny", target=0.2, f=0.2, sediment="sprinkle")
    assert "sediment sprinkle must be none, fill or rate" in proc.stdout


def test_scene_deck_window_needs_both_ends(tmp_path):
    proc = run_scene("expt1.in", tmp_path, preset="tiny", sediment="fill", sed_xlo=0)
    assert "give both sed_xlo and sed_xhi (the window), or neither" in proc.stdout
    assert proc.returncode != 0 or "scene: sediment fill" not in proc.stdout


def test_figure_colours_growth_strata_by_epoch(syntectonic, tmp_path):
    from saltdem_post.figures import COVER_COLOURS, growth_colours, marker_colours
    from saltdem_post.materials import MaterialMap
    from matplotlib.colors import to_rgba_array

    types = np.array([1, 1, 1, 1, 1, 2, 3])
    markers = np.array([0, 1, 1001, 1002, 1003, 5, -1])
    rgba = marker_colours(types, markers, MaterialMap())
    cover = to_rgba_array(list(COVER_COLOURS))
    # layers keep their colours; each epoch has its own colour, none of them a layer colour
    assert np.allclose(rgba[0], cover[0]) and np.allclose(rgba[1], cover[1])
    epochs = rgba[2:5]
    assert len({tuple(c) for c in epochs}) == 3
    assert not any(np.allclose(c, k) for c in epochs for k in cover)
    assert np.allclose(epochs, growth_colours(np.array([1, 2, 3]), 3))
    # the command line on the syntectonic scene's frames
    wd, _ = syntectonic
    files, _ = scene_dumps(wd, "expt1")
    out = tmp_path / "fig"
    proc = subprocess.run(["/usr/bin/python3", str(ROOT / "python" / "saltdem-post"), "figure",
                           *map(str, files), "--fault-x", "3125", "-o", str(out), "--name", "sed.png", "-q"],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert (out / "sed.png").stat().st_size > 10000
