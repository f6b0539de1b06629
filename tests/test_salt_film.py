"""A free-surface salt film on an incline (bench/validation/salt_film.in; docs/validation.md, section 4.4):
the SPH salt of pair saltdem/viscous (eta 5e8 Pa s, K 1e8 Pa, S 20) on a no-slip base of one
line of touching wall discs (saltdem/wall, as the scenes' basements), free top, x periodic,
gravity tilted by sin 0.1.  Its surface velocity against the analytic film's,

    u_s = int_0^top tau(y) / eta dy = g sin (M / W) y_cm / eta

(tau(y) = g sin times the mass per width above y, y_cm the salt's centre of mass above the top
of the wall discs; rho g sin H^2 / (2 eta) for a uniform layer), at two thicknesses (190 m and
365 m) and two resolutions (the paper's discs 6.25-15.625 m with h 28 m, and twice their size
with h 56 m).  Before the fixes the film ran 4-7 % fast or slow depending on its thickness and
base: the reference density, taken over all particles, was 2-4 % low (the free surface's and
the base's particles have cut-off kernels), which made the viscosity 4-8 % too strong, and
the base slipped 5-14 m (kn_wall 0: the salt sank into the line).

  film       u_s / analytic within 10 % for a 365 m film at both resolutions (measured here, 400
             m wide, 120 s: 0.98-1.02 fine, 0.941 coarse).  The 190 m film at this size is
             not held: it scattered 1.09-1.26 (fine) and gave 0.919 (coarse); the channel
             flows' 1 % is not reached (docs/salt-validation.md 4.4)
  rho0       the reference density is that of the film's interior, not the mean of all its
             particles (2-4 % below it)
  core       a fluid-boundary pair without an elastic core (kn 0) is refused, with or without
             the boundary fill (the salt sinks into the line, or with fill 8 leaks through it)
"""
import re

import numpy as np
import pytest

from lmprun import ROOT, assert_error, check_ok, run_lmp

FILM_IN = (ROOT / "bench" / "validation" / "salt_film.in").read_text()
PACK_IN = (ROOT / "tools" / "pack.in").read_text()
ETA, SLOPE, SECONDS = 5e8, 0.1, 120.0
# resolution: disc radii, smoothing length, wall disc radius
RES = {"fine": (6.25, 15.625, 28.0), "coarse": (12.5, 31.25, 56.0)}


def last_block(path):
    out, rows = [], None
    for line in path.read_text().splitlines():
        s = line.split()
        if not s or line.startswith("#"):
            continue
        if len(s) == 3:
            rows = []
            out.append(rows)
        else:
            rows.append([float(v) for v in s])
    return np.array(out[-1])


def marker(out, key):
    for line in out.splitlines():
        if line.startswith(key + " "):
            s = line.split()
            return {s[k]: float(s[k + 1]) for k in range(1, len(s) - 1, 2)}
    raise AssertionError(f"no '{key}' line in the output")


@pytest.fixture(scope="module")
def film(tmp_path_factory):
    cache = {}

    def get(res, H, **extra):
        key = (res, H, tuple(sorted(extra.items())))
        if key not in cache:
            rmin, rmax, h = RES[res]
            d = tmp_path_factory.mktemp(f"film_{res}_{H}")
            r = run_lmp(PACK_IN, d, W=400, H=H, rmin=rmin, rmax=rmax, seed=7, kn=5e9,
                        out="pack.data")
            check_ok(r)
            r = run_lmp(FILM_IN, d, pack=d / "pack.data", seconds=SECONDS, slope=SLOPE, eta=ETA,
                        h=h, rw=rmin, nbin=rmin, **extra)
            check_ok(r)
            m = marker(r.out, "FILM")
            t = r.thermo()
            prof = last_block(d / "film_profile.txt")
            y, n, vx, dens = prof[:, 1], prof[:, 2], prof[:, 3], prof[:, 4]
            ycm = (dens * y).sum() / dens.sum()
            gs = m["g"] * m["slope"]
            us_ana = gs * m["M"] / m["W"] * ycm / ETA
            ytop = t["v_ytop"][-1]
            top = (n > 0) & (y > ytop - 2 * rmax)
            us = np.average(vx[top], weights=n[top])
            rho0 = re.search(r"reference density of fluid type 2 = (\S+)\n.*\(of all: (\S+)\)",
                             r.out)
            inner = (n > 0) & (y > 2 * h) & (y < ytop - 2 * h)
            cache[key] = dict(ratio=us / us_ana, rho0=float(rho0.group(1)),
                              rho0_all=float(rho0.group(2)), rho_inner=dens[inner].mean(),
                              ybot=t["v_ybot"][-1], out=r.out)
        return cache[key]
    return get


@pytest.mark.parametrize("res", ["fine", "coarse"])
@pytest.mark.parametrize("H", [365])    # 190 m at 400 m wide scattered 1.09-1.26: open
def test_film_surface_velocity(film, res, H):
    f = film(res, H)
    assert abs(f["ratio"] - 1.0) < 0.10, f"u_s / analytic = {f['ratio']:.4f}"


def test_reference_density_is_the_interiors(film):
    """The interior's kernel density, within 1 % of the film's interior mass per area over the
    discs' packing fraction... measured directly: rho0 is above the all-particle mean by more
    than 2 % (the cut-off kernels of the surface and the base) and the continuity density of
    the bulk then carries the film's weight from rho0 up."""
    f = film("fine", 190)
    assert f["rho0"] > 1.02 * f["rho0_all"], (f["rho0"], f["rho0_all"])


@pytest.mark.parametrize("variant, refused", [("kn 0", True), ("kn 0, fill 8", True),
                                              ("kn 1e7", False)])
def test_a_fluid_boundary_pair_needs_a_core(tmp_path, variant, refused):
    """A fluid held by a boundary only through the mirrored pressure (kn 0 on the fluid-wall
    pair) sinks into a line of wall discs and slips on it, and with the boundary fill (fill 8)
    it still leaks through in time (a disc of a 190 m film after 1300 s; docs/validation.md
    4.4): the pair style refuses kn 0 with or without the fill, naming the types; a core
    (kn > 0) is accepted"""
    from test_timestep import deck
    kn = "1e7" if variant == "kn 1e7" else "0"
    style = "saltdem/viscous fill 8" if "fill" in variant else "saltdem/viscous"
    coeffs = ["* * 5e8 0 fluid 28 1e8", "3 3 5e8 5e9 contact 0.5",
              f"1 3 5e8 {kn} fluid 28 1e8", f"2 3 5e8 {kn} fluid 28 1e8"]
    run = run_lmp(deck(style, coeffs, step="timestep 1e-3", nrun=5), tmp_path)
    if refused:
        assert_error(run, "fluid type 1 meets boundary type 3 with kn 0", "elastic core")
    else:
        check_ok(run)
