"""The no-slip boundary at the surface of the boundary discs (pair_style saltdem/viscous
keyword noslip surface; docs/pair_saltdem_viscous.rst, docs/salt-validation.md 4.4).

A static wall particle enters the Morris viscosity at its own velocity, which holds the fluid
still at the particle's centre: on a line of wall discs the salt's no-slip plane lies near the
line's centre line, and once the salt has sheared out of the line's gaps it slips by one to two
wall-disc radii (a 190 m film 6-18 % fast).  With noslip surface each boundary disc shows the
fluid the fluid's own kernel-averaged velocity extrapolated linearly through the disc's surface
(SaltDEM::noslip_offset), and with the boundary fill (fill 8) the wall line also stands for the
part of the kernel it leaves empty.

  film      the 190 m film of bench/validation/salt_film.in (the paper's discs, h 28 m, sin 0.1, 800 m
            wide, 300 s): u_s / analytic within 3 % with noslip surface fill 8 (measured
            0.988); the centre boundary gives 1.061 here (asserted above 1.03: what the fix
            changes)
  parallel  the film with noslip surface, fill 8 and 2 viscous sub-steps on 2 MPI ranks (newton
            off and on: the boundary discs' sums of ghost partners go home by reverse
            communication, their offsets to the ghosts by forward communication) and on 2
            OpenMP threads: the serial run's mean velocity within 1e-6
  restart   the setting is in the restart file (layout 4): read back, the style says so
  3d        a block of salt sliding over a layer of wall spheres slows faster with the
            surface than with the centre (the 3D form), the same on 2 ranks
"""
import numpy as np
import pytest

from lmprun import ROOT, check_ok, run_lmp
from test_salt_film import last_block, marker

FILM_IN = (ROOT / "bench" / "validation" / "salt_film.in").read_text()
PACK_IN = (ROOT / "tools" / "pack.in").read_text()
ETA = 5e8


@pytest.fixture(scope="module")
def pack(tmp_path_factory):
    d = tmp_path_factory.mktemp("film_pack")
    check_ok(run_lmp(PACK_IN, d, W=800, H=190, rmin=6.25, rmax=15.625, seed=7, kn=5e9,
                     out="pack.data"))
    return d / "pack.data"


def surface_ratio(run, workdir, rmax=15.625):
    """u_s / analytic as bench/validation/salt_film.py measures it (the mean of the top 2 rmax against
    g sin (M/W) y_cm / eta, y_cm the profile's centre of mass above the wall discs' top)."""
    prof = last_block(workdir / "film_profile.txt")
    y, n, vx, dens = prof[:, 1], prof[:, 2], prof[:, 3], prof[:, 4]
    m = marker(run.out, "FILM")
    ycm = (dens * y).sum() / dens.sum()
    us_ana = m["g"] * m["slope"] * m["M"] / m["W"] * ycm / ETA
    ytop = run.thermo()["v_ytop"][-1]
    top = (n > 0) & (y > ytop - 2 * rmax)
    return np.average(vx[top], weights=n[top]) / us_ana


@pytest.mark.parametrize("extra, lo, hi", [("noslip surface fill 8", 0.97, 1.03),
                                           ("", 1.03, 1.2)])
def test_film_on_a_wall_line(pack, tmp_path, extra, lo, hi):
    r = run_lmp(FILM_IN, tmp_path, pack=pack, seconds=300, slope=0.1, eta=ETA, h=28, rw=6.25,
                nbin=6.25, extra=extra)
    check_ok(r)
    ratio = surface_ratio(r, tmp_path)
    assert lo < ratio < hi, f"u_s / analytic = {ratio:.4f} with '{extra or 'noslip centre'}'"


def film_run(pack, d, newton="off", **kw):
    d.mkdir(parents=True, exist_ok=True)
    deck = FILM_IN.replace("newton          off", f"newton          {newton}")
    assert f"newton          {newton}" in deck
    r = run_lmp(deck, d, pack=pack, nsteps=2000, nthermo=100, slope=0.1, eta=ETA, h=28,
                rw=6.25, nbin=6.25, extra="noslip surface fill 8 substeps 2", **kw)
    check_ok(r)
    return np.array(r.thermo()["v_vx"])


@pytest.mark.parametrize("mode", ["np2", "np2_newton", "omp2"])
def test_parallel_runs_give_the_serial_flow(pack, tmp_path, mode):
    a = film_run(pack, tmp_path / "serial")
    kw = {"np": 2} if mode.startswith("np2") else {"omp": 2}
    b = film_run(pack, tmp_path / mode, newton="on" if mode == "np2_newton" else "off", **kw)
    assert abs(a[-1]) > 1e-3    # the film flows
    np.testing.assert_allclose(b, a, rtol=1e-6, atol=1e-9 * abs(a).max())


def test_restart_keeps_noslip(pack, tmp_path):
    deck = FILM_IN + "write_restart r.restart\n"
    check_ok(run_lmp(deck, tmp_path, pack=pack, nsteps=20, slope=0.1, eta=ETA, h=28, rw=6.25,
                     extra="noslip surface"))
    r = run_lmp("read_restart r.restart\ncomm_modify vel yes\npair_coeff * * none\n"
                "pair_coeff 2 2 saltdem/viscous 5e8 0 fluid 28 1e8\n"
                "pair_coeff 2 3 saltdem/viscous 5e8 5e9 fluid 28 1e8\n"
                "neigh_modify exclude type 3 3\nfix integ salt saltdem/nve inertia 20\n"
                "timestep 0.005\nrun 2\n", tmp_path)
    check_ok(r)
    assert "no-slip at the surfaces of the boundary discs" in r.out
    (tmp_path / "plain").mkdir()
    r = run_lmp(FILM_IN, tmp_path / "plain", pack=pack, nsteps=20, slope=0.1, eta=ETA, h=28,
                rw=6.25)
    check_ok(r)
    assert "no-slip at the surfaces" not in r.out


DECK_3D = """units si
dimension 3
atom_style sphere
boundary p p f
comm_modify vel yes
newton ${newton}
region box block 0 200 0 200 -20 200 units box
create_box 2 box
lattice sc 20
region salt block INF INF INF INF 0 180 units box
region wall block INF INF INF INF -20 -1 units box
create_atoms 1 region salt
create_atoms 2 region wall
set group all diameter 20
set group all density 2200
group salt type 1
velocity salt set 2 0 0 units box
pair_style saltdem/viscous noslip ${noslip}
pair_coeff 1 1 5e8 0 fluid 26 1e9
pair_coeff 1 2 5e8 1e10 fluid 26 1e9
pair_coeff 2 2 5e8 1e10 contact 0
neigh_modify exclude type 2 2
fix integ salt saltdem/nve inertia 20
timestep 0.003
variable vx equal vcm(salt,x)
thermo_style custom step v_vx
thermo_modify format float %.12g
thermo 50
run 267
"""


def test_3d_block_on_a_wall_layer(tmp_path):
    """3D: a block of salt sliding over a layer of static wall spheres slows down, faster with
    the no-slip plane at the spheres' surfaces than at their centres (measured: 2 m/s -> 0.56
    against 0.65 in 0.8 s; dt 0.003 s, below the spheres' viscous limit), and 2 MPI ranks
    (newton off and on) give the serial run"""
    def vx(noslip, ranks=1, newton="off"):
        d = tmp_path / f"{noslip}_{ranks}_{newton}"
        d.mkdir()
        r = run_lmp(DECK_3D, d, np=ranks, noslip=noslip, newton=newton)
        check_ok(r)
        return np.array(r.thermo()["v_vx"])
    centre, surface = vx("centre"), vx("surface")
    assert 0.3 < surface[-1] < centre[-1] < 1.0, (surface[-1], centre[-1])
    assert centre[-1] - surface[-1] > 0.05
    for newton in ("off", "on"):
        np.testing.assert_allclose(vx("surface", ranks=2, newton=newton), surface, rtol=1e-8)


@pytest.mark.parametrize("value", ["sideways", "1"])
def test_noslip_needs_centre_or_surface(tmp_path, value):
    from lmprun import assert_error
    r = run_lmp(DECK_3D.replace("noslip ${noslip}", f"noslip {value}"), tmp_path, newton="off")
    assert_error(r, f"noslip '{value}' is not a boundary", "surface", "centre")
