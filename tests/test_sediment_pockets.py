"""The pocket search and the radius generator of fix saltdem/sediment alone (no LAMMPS): a
small C++ program (tests/unit/sediment_pockets_test.cpp) compiled against the package's
header-only saltdem_sediment_pockets.h and saltdem_sediment_random.h checks the generator's
stream and radius laws, the closed-form pocket of two discs, the window, the foreset, the
rate's area and maxper, and on a random bed that every new disc rests on two discs, below the
level, within the overlap tolerance, whatever order the discs were gathered in."""
from lmprun import run_unit


def test_sediment_pockets_alone(tmp_path):
    run_unit("sediment_pockets_test", tmp_path)
