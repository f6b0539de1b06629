"""Buoyancy of the SPH salt: the Rayleigh-Taylor benchmark of van Keken et al. (1997) in reduced
form (bench/validation/rt_vankeken.in at its coarsest resolution, 20 rows, 20 buoyancy times; the full
numbers are in docs/validation.md, section 4.5).

Two fluid types of disc density 2160 and 2400 kg/m^3; the light layer's first Fourier mode grows
at the analytic Stokes rate (0.0109402 per t_b) within the error measured at this resolution
(0.950 of it over 5-20 t_b with the volume-weighted sums; 0.960 with the partners' own masses,
0.943-0.964 over the windows 2-20 to 5-40 t_b), and does not grow at all when the two densities
are equal."""
import os

import numpy as np
import pytest

from lmprun import ROOT, lmp_path, run_cmd
from saltdem_post import rayleigh_taylor as rt

MEASURED = 0.950     # gamma / analytic at n 20, fitted over 5-20 t_b (bench/validation/rt_vankeken.in defaults)
TOL = 0.03           # the spread of the fitted rate over reasonable windows at n 20 (0.943-0.964)


def run_rt(tmp_path, name, tend=20, **var):
    cmd = [lmp_path(), "-in", str(ROOT / "bench" / "validation" / "rt_vankeken.in"), "-log", f"log.{name}",
           "-screen", "none", "-var", "name", name, "-var", "n", "20", "-var", "tend", str(tend)]
    for k, v in var.items():
        cmd += ["-var", k, str(v)]
    proc = run_cmd(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=900,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert proc.returncode == 0, (tmp_path / f"log.{name}").read_text()[-3000:]
    return rt.read_run(tmp_path / f"{name}.txt")


def test_analytic_growth_rate():
    """the Green's-function rate of bench/validation/rt_vankeken.py is van Keken et al.'s analytic one"""
    assert rt.growth_rate() == pytest.approx(rt.GAMMA_VK, rel=1e-6)
    # a thinner layer grows more slowly, a taller box (walls further away) faster
    assert rt.growth_rate(0.15) < rt.growth_rate() < rt.growth_rate(0.25)
    assert rt.growth_rate(0.2, rt.L_BOX, 1.1) > rt.growth_rate()


def test_rayleigh_taylor_growth(tmp_path):
    head, t, vrms, ac, as_ = run_rt(tmp_path, "rt")
    amp = np.hypot(ac, as_)
    gamma, _ = rt.fit_rate(t, amp, 5.0, 20.0)
    ratio = gamma / rt.growth_rate()
    assert ratio == pytest.approx(MEASURED, abs=TOL), f"gamma/analytic {ratio:.4f}"
    # the lattice holds the benchmark's perturbation: first mode 0.0212 H (0.02)
    assert amp[0] == pytest.approx(0.02, rel=0.1)
    # inertia-free: the flow's Reynolds number Re_b x vrms/U_b stays small
    assert head["Re_b"] * max(vrms[t > 2]) < 0.01

    # the same box with equal densities (what ignoring the per-type densities would give): no
    # buoyancy, the interface stays where it is and the rate check above would fail
    head, t, vrms, ac, as_ = run_rt(tmp_path, "flat", tend=10, rho_light=2400)
    amp = np.hypot(ac, as_)
    gamma, _ = rt.fit_rate(t, amp, 3.0, 10.0)
    assert abs(gamma) < 0.05 * rt.growth_rate()
    assert abs(amp[-1] - amp[0]) < 1e-3 * amp[0]
