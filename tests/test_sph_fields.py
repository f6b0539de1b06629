"""SaltDEM::SphFields, the SPH field passes of pair saltdem/viscous, alone (no LAMMPS): a small
C++ program (tests/unit/sph_fields_test.cpp) compiled against the package's
saltdem_sph_fields.cpp checks the kernel density of a square lattice against the lattice sum
and its continuum value m / a^2, the full-kernel flag, and the Bonet-Lok corrected pressure
matrix (S A = a rho I)."""
from lmprun import run_unit


def test_sph_fields_on_a_lattice(tmp_path):
    run_unit("sph_fields_test", tmp_path, ["saltdem_sph_fields.cpp"])
