"""Limits that overflowed or passed silently (review, issue 17): a stable time step limit that is
zero or not finite, coefficients beyond the SaltDEM bounds, the wall disc count, the step of the
motion fixes, the time step message under pair hybrid, and a viscosity changed during a run.
Each test failed before its fix."""
import re

import pytest

from lmprun import assert_error, check_ok

# 10 x 10 discs of diameter 21 on a 20 m lattice (touching neighbours): type 1 salt, type 2
# cover (top rows), the lowest two rows type 3 walls, not integrated
HEAD = """units si
dimension 2
atom_style sphere
atom_modify map array
boundary p f p
comm_modify vel yes
region box block 0 200 0 200 -0.5 0.5
create_box 3 box
lattice sq 20
create_atoms 1 box
region low block INF INF INF 25 INF INF units box
region high block INF INF 150 INF INF INF units box
set region high type 2
set region low type 3
set group all diameter 21
set group all density/disc {density}
group mobile type 1 2
group salt type 1
group base type 3
neighbor 2.8 bin
"""
VISCOUS = """pair_style saltdem/viscous {ps}
pair_coeff * * {eta} 5e9 contact 0.5
"""
HYBRID = """pair_style hybrid saltdem/cohesive saltdem/viscous
pair_coeff 2 2 saltdem/cohesive {kn} 8e8 0.5 1e6 1e6 0.1
pair_coeff 2 3 saltdem/cohesive {kn} 8e8 0.5 1e6 1e6 0.1
pair_coeff 1 1 saltdem/viscous {eta} 5e9 contact 0.5
pair_coeff 1 2 saltdem/viscous {eta} 5e9 contact 0.5
pair_coeff 1 3 saltdem/viscous {eta} 5e9 contact 0.5
pair_coeff 3 3 none
"""
TAIL = """neigh_modify exclude type 3 3
velocity mobile create 1e-3 7 loop geom
fix 1 mobile saltdem/nve inertia 20 check 1
fix 2 all enforce2d
{extra}
{step}
thermo 10
thermo_style custom step dt pe ke
run {nrun}
"""


def deck(pair=VISCOUS, step="timestep 0.001", extra="", nrun=20, density=2200, ps="",
         eta="5e8", kn="2.5e9"):
    return (HEAD.format(density=density) + pair.format(ps=ps, eta=eta, kn=kn) +
            TAIL.format(extra=extra, step=step, nrun=nrun))


# ---------------------------------------------------------------------------------------------
# 2. a limit that is zero or not finite; coefficients beyond the bounds
# ---------------------------------------------------------------------------------------------

def test_zero_limit_is_an_error(lmp):
    """calibration x eta = 1e200 over a disc mass of 7e-300 kg: the viscous limit underflows to
    0, which the check read as "no limit" (the run started).  Now an error naming eta."""
    r = lmp(deck(density=1e-303, ps="calibration 1e100", eta="1e100"))
    line = assert_error(r, "saltdem/viscous", "not a finite positive number", "eta = 1e+100",
                        "calibration = 1e+100")
    assert "Step" not in r.out


def test_zero_limit_is_an_error_in_saltdem_timestep(lmp):
    r = lmp(deck(density=1e-303, ps="calibration 1e100", eta="1e100",
                 step="saltdem/timestep 0.85"))
    assert_error(r, "saltdem/timestep", "saltdem/viscous", "not a finite positive number",
                 "eta = 1e+100")


FAULT = "saltdem/wall 3 100 5 190 5 10 group hw\nfix f hw saltdem/fault dip 60 rate {rate} target 5\n"
KEYSTONE = ("saltdem/wall 3 10 15 90 15 10 group key\nsaltdem/wall 3 110 15 190 15 10 group rb\n"
            "group ks union key rb\nfix f ks saltdem/keystone dip 60 keystone key rate {rate} "
            "target 5\n")
TILTWALL = "saltdem/wall 3 100 5 190 5 10 group hw\nfix f hw saltdem/tiltwall tilt 5 rate {rate} target 5\n"
VISC_FIX = ("fix v salt saltdem/viscosity lambda {lam} model 5e8 rate 1 length 100 density 2200 "
            "inertia {inertia}\n")


@pytest.mark.parametrize("kw,word", [
    (dict(ps="calibration 1e300"), "calibration = 1e+300"),
    (dict(ps="correction 1e300"), "correction = 1e+300"),
    (dict(eta="1e300"), "eta = 1e+300"),
    (dict(eta="1e-300"), "eta = 1e-300"),
    (dict(kn="1e300", pair=HYBRID), "kn = 1e+300"),
    (dict(extra=FAULT.format(rate="1e300")), "saltdem/fault: rate = 1e+300"),
    (dict(extra=KEYSTONE.format(rate="1e300")), "saltdem/keystone: rate = 1e+300"),
    (dict(extra=TILTWALL.format(rate="1e300")), "saltdem/tiltwall: rate = 1e+300"),
    (dict(extra=VISC_FIX.format(lam="1e300", inertia=20)), "lambda = 1e+300"),
    (dict(extra=VISC_FIX.format(lam=1, inertia="1e300")), "saltdem/viscosity: inertia = 1e+300"),
    (dict(extra="fix 1 mobile saltdem/nve inertia 1e300"), "saltdem/nve: inertia = 1e+300"),
    (dict(extra="pair_coeff 2 2 saltdem/cohesive 2.5e9 8e8 0.5 1e6 1e6 0.1 rolling 1e8 1e300",
          pair=HYBRID), "rolling mu_r = 1e+300"),
    (dict(extra="saltdem/wall 3 10 5 190 5 10 density 1e300"), "density = 1e+300"),
], ids=["calibration", "correction", "eta", "eta-tiny", "kn", "fault-rate", "keystone-rate",
        "tiltwall-rate", "lambda", "viscosity-inertia", "nve-inertia", "mu_r", "wall-density"])
def test_value_beyond_the_bounds_is_refused(lmp, kw, word):
    """1e300 (or 1e-300) is refused where it is given, naming the parameter; before, each was
    accepted (products such as calibration x eta or rate x dt overflowed silently)."""
    r = lmp(deck(**kw))
    assert_error(r, "is not a usable value", word)


def test_viscosity_fix_derived_viscosity_beyond_the_bounds(lmp):
    """lambda 1e-99 over a model viscosity of 5e8: a natural viscosity of 5e-91... fine; 5e8 x
    1e99 = 5e107 natural from 'model' is beyond the bound: refused naming lambda."""
    r = lmp(deck(extra=VISC_FIX.format(lam="1e99", inertia=20)))
    assert_error(r, "saltdem/viscosity", "lambda = 1e+99", "natural")


# ---------------------------------------------------------------------------------------------
# 3. saltdem/wall: the disc count in 64 bits, refused beyond 1e7, never none silently
# ---------------------------------------------------------------------------------------------

WALL = """units si
dimension 2
atom_style sphere
boundary f f p
region box block -100 100 -100 100 -1 1
create_box 1 box
saltdem/wall {spec}
print "COUNT $(count(all))"
"""


@pytest.mark.parametrize("spec,words", [
    ("1 -90 0 90 0 1e-9", ["9e+10 wall discs", "more than the 10000000"]),   # wrapped: -2147483647
    ("1 -90 0 90 0 8e-6", ["1.125e+07 wall discs"]),                       # just beyond 1e7
    ("1 -90 0 90 0 1e-12", ["9e+13 wall discs"]),
    ("1 -90 0 90 0 500", ["radius R = 500 exceeds the box size 200"]),
])
def test_wall_count_overflow_is_an_error(lmp, spec, words):
    r = lmp(WALL.format(spec=spec))
    assert_error(r, "saltdem/wall", *words)
    assert "-2147483647" not in r.out


def test_wall_large_count_within_the_bound(lmp):
    """180,001 discs of radius 5e-4 on 180 m (well within the bound): all made."""
    r = lmp(WALL.format(spec="1 -90 0 90 0 5e-4"))
    check_ok(r)
    assert "saltdem/wall: 180001 wall discs" in r.out and "COUNT 180001" in r.out


# ---------------------------------------------------------------------------------------------
# 4. motion fixes: a step beyond the target is refused (at init: dt may change), a step that
#    moves a block by more than 0.1 of the smallest radius warns once
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("motion", [FAULT, KEYSTONE, TILTWALL], ids=["fault", "keystone", "tiltwall"])
def test_motion_step_beyond_target_is_refused(lmp, motion):
    """rate 1e4 m/s at dt 0.001: 10 m per step, target 5 m."""
    r = lmp(deck(extra=motion.format(rate="1e4")))
    assert_error(r, "rate x dt", "10 m", "beyond the target 5 m")


def test_motion_step_checked_after_the_time_step_changes(lmp):
    """rate 1000 m/s is fine at dt 0.001 (1 m per step), not after 'timestep 0.01' (10 m)."""
    r = lmp(deck(extra="timestep 0.001\n" + FAULT.format(rate=1000) + "run 2\n",
                 step="timestep 0.01", eta="5e2"))
    assert_error(r, "saltdem/fault", "1000 x 0.01", "beyond the target")
    assert r.out.count("Loop time") == 1


def test_motion_fast_block_warns_once(lmp):
    """Keystone at 2000 m/s, dt 0.001: both blocks move 2 m per step (the right block at
    2 cos 60 = 1 x the rate), 0.2 of the smallest radius (the walls, 10 m): one warning over
    two runs.  At 400 m/s (0.4 m, 0.04 of it) none."""
    fast = KEYSTONE.format(rate=2000).replace("target 5", "target 10")
    r = lmp(deck(extra=fast, nrun=2, eta="5e2") + "run 2\n")
    check_ok(r)
    warns = re.findall(r"WARNING: Fix saltdem/keystone f: one time step moves a block by "
                       r"([0-9.e+-]+) m", r.out)
    assert len(warns) == 1 and float(warns[0]) == pytest.approx(2.0), r.out[-2000:]
    assert "smallest disc radius 10 m" in r.out and r.out.count("Loop time") == 2
    slow = KEYSTONE.format(rate=400).replace("target 5", "target 10")
    r = lmp(deck(extra=slow, nrun=2, eta="5e2"))
    check_ok(r)
    assert "WARNING" not in r.out


# ---------------------------------------------------------------------------------------------
# 8. pair hybrid: one message with the smallest limit of all SaltDEM sub-styles
# ---------------------------------------------------------------------------------------------

def test_hybrid_message_names_the_smallest_limit_of_all_substyles(lmp):
    """The cover (first sub-style) limits dt to ~1.5e-2 s, the salt (eta 5e10) to less.  At
    dt 0.1 the cover's check stopped the run naming its own limit, and the dt it advised was
    then refused by the salt.  Now the message gives the smallest limit (the salt's), every
    sub-style's limit, and its advice runs."""
    r = lmp(deck(pair=HYBRID, eta="5e10", step="timestep 0.1"))
    line = assert_error(r, "Pair style saltdem/viscous", "exceeds the stable limit", "eta = 5e+10",
                        "limits of the SaltDEM sub-styles: saltdem/cohesive")
    lim = float(re.search(r"stable limit ([0-9.eE+-]+)", line).group(1))
    subs = dict(re.findall(r" (saltdem/\w+) ([0-9.eE+-]+) s[;)]", line.split("sub-styles:")[1]))
    assert set(subs) == {"saltdem/cohesive", "saltdem/viscous"}
    assert lim == pytest.approx(float(subs["saltdem/viscous"]))
    assert lim < float(subs["saltdem/cohesive"])
    use = re.search(r"Use 'timestep ([0-9.eE+-]+)'", line).group(1)
    r = lmp(deck(pair=HYBRID, eta="5e10", step=f"timestep {use}"))
    check_ok(r)
    # each sub-style still logs its own margin
    assert len(re.findall(r"Pair style saltdem/\w+: timestep [0-9.eE+-]+ = [0-9.]+ of the stable "
                          r"limit", r.out)) == 2


def test_hybrid_saltdem_timestep_agrees_with_the_check(lmp):
    r = lmp(deck(pair=HYBRID, eta="5e10", step="saltdem/timestep 1.0"))
    check_ok(r)
    m = re.search(r"saltdem/timestep: timestep ([0-9.eE+-]+) = 1 of the stable limit "
                  r"([0-9.eE+-]+) of pair style saltdem/viscous", r.out)
    assert m, r.out[-2000:]


# ---------------------------------------------------------------------------------------------
# 9. the viscosity changed during a run (fix adapt): checked again, stopped with our message
# ---------------------------------------------------------------------------------------------

ADAPT = """variable eta equal ramp(5e8,5e11)
fix ad all adapt 1 pair {sub} eta 1 1 v_eta
"""


@pytest.mark.parametrize("pair,sub,omp", [(VISCOUS, "saltdem/viscous", 0),
                                          (HYBRID, "saltdem/viscous", 0),
                                          (VISCOUS, "saltdem/viscous", 1)],
                         ids=["alone", "hybrid", "omp"])
def test_viscosity_ramp_during_a_run_is_checked(lmp, pair, sub, omp):
    """eta ramped 1000x over 400 steps at 0.85 of the starting limit: the run stops at the
    step where the limit drops below dt, with the limit named (before: it blew up, ending with
    a NaN or lost atoms)."""
    r = lmp(deck(pair=pair, step="saltdem/timestep 0.85", extra=ADAPT.format(sub=sub), nrun=400),
            omp=omp)
    if omp:
        assert "saltdem/viscous/omp" in r.out
    line = assert_error(r, "Pair style saltdem/viscous", "after eta of types", "changed during the run",
                        "exceeds the stable limit", "eta = ")
    step = int(re.search(r"at step (\d+)", line).group(1))
    assert 0 < step < 10, line     # the limit falls below 0.85 of its start within ~1 step of 400
    assert "non-finite" not in r.out and "lost" not in r.out


def test_viscosity_ramp_within_the_limit_runs(lmp):
    """Lowering eta (the limit grows) during the run passes the re-check."""
    r = lmp(deck(step="saltdem/timestep 0.85", nrun=100,
                 extra=ADAPT.format(sub="saltdem/viscous").replace("ramp(5e8,5e11)", "ramp(5e8,5e7)")))
    check_ok(r)


def test_viscosity_set_to_infinity_during_a_run(lmp):
    extra = ("variable eta equal ternary(step>=5,1e300*1e300,5e8)\n"
             "fix ad all adapt 1 pair saltdem/viscous eta * * v_eta\n")
    r = lmp(deck(step="saltdem/timestep 0.85", extra=extra, nrun=20))
    assert_error(r, "saltdem/viscous", "eta = inf", "extract")


# ---------------------------------------------------------------------------------------------
# found by the fuzzer (test_fuzz.py): saltdem/timestep before any pair_coeff crashed
# ---------------------------------------------------------------------------------------------

def test_saltdem_timestep_before_the_coefficients(lmp):
    """pair_style given, no pair_coeff yet: saltdem/timestep read the unallocated coefficient
    arrays (segmentation fault); now the error that no limit applies."""
    d = HEAD.format(density=2200) + "pair_style saltdem/viscous\nsaltdem/timestep 0.5\n"
    r = lmp(d)
    assert_error(r, "saltdem/timestep", "no stable limit applies", "coefficients are not set")


def test_saltdem_timestep_with_atom_style_atomic(lmp):
    """No per-atom radius or mass: saltdem/timestep read the missing rmass (segmentation
    fault, found by the fuzzer); now an error asking for atom_style sphere."""
    d = """units si
dimension 2
atom_style atomic
boundary f f p
region box block -100 100 -100 100 -1 1
create_box 1 box
create_atoms 1 single 0 0 0
mass 1 1
pair_style saltdem/cohesive
pair_coeff * * 1e9 1e8 0.5 0 0 0
fix f all nve
saltdem/timestep 0.5
"""
    assert_error(lmp(d), "saltdem/timestep", "saltdem/cohesive", "atom_style sphere")
