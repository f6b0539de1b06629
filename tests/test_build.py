"""The build: lmp carries USER-SALTDEM and its styles, decks using them run, bad arguments fail."""

from lmprun import lmp_path, run_cmd

STYLES = ["saltdem/cohesive", "saltdem/cohesive/omp", "saltdem/viscous", "saltdem/viscous/omp",
          "saltdem/nve", "saltdem/viscosity", "saltdem/fault"]

DECK = """
units si
dimension 2
atom_style sphere
boundary p p p
comm_modify vel yes
region box block 0 200 0 200 -1 1
create_box 1 box
lattice sq 20
create_atoms 1 box
set type 1 diameter 20.2
set type 1 density/disc 2200
velocity all create 1.0 4928 dist gaussian
pair_style saltdem/cohesive
pair_coeff * * 1e9 5e8 0.5 1e6 1e6 0.05
neighbor 1.0 bin
fix 1 all saltdem/nve
timestep 0.001
thermo_style custom step atoms ke pe
run 200
"""


def test_help_lists_package_and_styles():
    out = run_cmd([lmp_path(), "-h"], capture_output=True, text=True).stdout
    pkgs = out.split("Installed packages:")[1].split("List of individual style options")[0]
    assert "USER-SALTDEM" in pkgs.split()
    for pkg in ("GRANULAR", "OPENMP"):
        assert pkg in pkgs.split()
    assert "KSPACE" not in pkgs.split()
    words = out.split()
    for style in STYLES:
        assert style in words, f"{style} missing from lmp -h"


def test_deck_with_our_style_runs(lmp):
    r = lmp(DECK)
    assert r.rc == 0, r.out[-2000:]
    t = r.thermo()
    assert t["Atoms"][-1] == 100
    assert t["Step"][-1] == 200
    # the lattice overlaps: the pack is compressed, so contacts carry elastic energy
    assert t["PotEng"][0] != 0.0


def test_unknown_argument_is_a_clear_error(lmp):
    r = lmp(DECK.replace("pair_style saltdem/cohesive", "pair_style saltdem/cohesive bogus 3"))
    assert r.rc != 0
    err = r.error()
    assert err is not None and "saltdem/cohesive" in err and "bogus" in err, r.out[-1500:]
