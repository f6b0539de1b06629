"""The Rayleigh-Taylor benchmark of van Keken et al. (1997), isoviscous case: the analytic linear
growth rate and the analysis of bench/validation/rt_vankeken.in runs (docs/validation.md,
section 4.5; the analysis itself: python/saltdem_post/rayleigh_taylor.py).

Usage (from the repository root):
    PYTHONPATH=python /usr/bin/python3 bench/validation/rt_vankeken.py RUN.txt [RUN.txt ...] [--fit T1 T2]
prints, per run: the growth rate fitted to the interface's first Fourier mode a(t) and to vrms
over [T1, T2] (in t_b), their ratio to the analytic rate, the wall offset that would explain
the rate, the initial amplitude, and the vrms peak and its time (if the run reached it), raw and
moved to the benchmark's initial amplitude 0.02.
    PYTHONPATH=python /usr/bin/python3 bench/validation/rt_vankeken.py --poiseuille DUMP ETA GX H RHO_PHI
fits the no-slip planes and the viscosity to the dump of a Poiseuille run of the same box
(-var gravity poiseuille -var rho_light 2400 -var dump 1), and
    PYTHONPATH=python /usr/bin/python3 bench/validation/rt_vankeken.py --hydrostatic DUMP LOG K DY
prints the pressure by row of a flat interface under the full weight (-var amp 0 -var gravity
full -var wall half -var dump 1).
"""
import argparse
import sys

import numpy as np

from saltdem_post.rayleigh_taylor import (AMP, GAMMA_VK, VRMS_PEAK_VK, analyse, growth_rate, hydrostatic, poiseuille,
                                          vrms_per_amplitude)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="*")
    ap.add_argument("--fit", nargs=2, type=float, default=(5.0, 40.0), metavar=("T1", "T2"),
                    help="fit window in t_b (default 5 40)")
    ap.add_argument("--poiseuille", nargs=5, metavar=("DUMP", "ETA", "GX", "H", "RHO_PHI"),
                    help="fit the no-slip planes and the viscosity of a Poiseuille run's dump "
                         "(RHO_PHI: the fluid's mass per area, disc density x packing fraction)")
    ap.add_argument("--hydrostatic", nargs=4, metavar=("DUMP", "LOG", "K", "DY"),
                    help="pressure by row of a flat-interface run under its full weight")
    args = ap.parse_args(argv)
    if args.hydrostatic:
        dump, log, kmod, dy = args.hydrostatic
        rows = hydrostatic(dump, log, float(kmod), float(dy))
        print("| y (m) | type | P (Pa) |\n|---|---|---|")
        for y, t, p in rows:
            print(f"| {y:.1f} | {t:.2f} | {p:.4g} |")
        for t in (1, 2):
            sel = [(y, p) for y, tt, p in rows if tt == t]
            if len(sel) > 3:     # the gradient inside the layer, one row off each end
                yy, pp = np.array(sel[1:-1]).T
                print(f"type {t}: dP/dy = {np.polyfit(yy, pp, 1)[0]:.5g} Pa/m")
        return 0
    if args.poiseuille:
        dump, eta, gx, height, rho_phi = args.poiseuille
        eta, gx, height, rho_phi = map(float, (eta, gx, height, rho_phi))
        y0, y1, amp = poiseuille(dump, height)
        print(f"Poiseuille: no-slip planes at y = {y0:.2f} and H + {y1:.2f}; "
              f"viscosity {rho_phi * gx / (2 * amp) / eta:.4f} eta")
        return 0
    g = growth_rate()
    vpa = vrms_per_amplitude()
    print(f"analytic: gamma t_b = {g:.7f} (van Keken et al. 1997: {GAMMA_VK}), "
          f"vrms/U_b = {vpa:.6f} x amplitude/H ({vpa * AMP:.4e} at {AMP})")
    if not args.runs:
        return 0
    print("| n | Re_b | gamma (mode) | / analytic | gamma (vrms) | wall offset / spacing | "
          "a(0) / H | vrms(0) fit / analytic | vrms peak | / published | t peak | t peak at a(0) = 0.02 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for path in args.runs:
        r = analyse(path, *args.fit)
        d = r["delta"] * r["n"]
        line = (f"| {r['n']:.0f} | {r['Re_b']:.3g} | {r['gamma_a']:.5f} | {r['gamma_a'] / g:.3f} | "
                f"{r['gamma_v']:.5f} | {d:.2f} | {r['a_start']:.5f} | "
                f"{r['vrms0'] / (vpa * r['a0']):.3f} | ")
        if "t_peak" in r:
            line += (f"{r['vrms_peak']:.4e} | {r['vrms_peak'] / VRMS_PEAK_VK:.3f} | "
                     f"{r['t_peak']:.1f} | {r['t_peak_amp']:.1f} |")
        else:
            line += f"(not reached by t = {r['t_end']:.0f}) | | | |"
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
