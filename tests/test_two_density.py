"""Two salt fluids of different density at rest under their full weight keep a hydrostatic
pressure profile (issue 18: the SPH sums weigh a partner as the particle's own material,
PairSaltdemViscous::pair_weights; docs/validation.md, section 4.5).

bench/validation/rt_vankeken.in with a flat interface (amp 0) and the full weight on each fluid: 4 rows of
light fluid (2160 kg/m^3) under 16 of heavy (2400 kg/m^3).  The heavy fluid's pressure gradient
is its weight per area, and the light layer continues the heavy fluid's pressure at the
interface with its own, smaller, gradient.  Before the volume-weighted sums a light particle
counted a heavy neighbour's mass as if it were light: the light layer stood 3.5-4.4e6 Pa (15-17 %)
above the hydrostatic pressure; now within 1 %."""
import os

import numpy as np

from lmprun import ROOT, lmp_path, run_cmd
from saltdem_post import rayleigh_taylor as rt

G = 9.81
H = 1000.0
N = 20
K = 1e9


def test_two_density_column_is_hydrostatic(tmp_path):
    cmd = [lmp_path(), "-in", str(ROOT / "bench" / "validation" / "rt_vankeken.in"), "-log", "log.hs",
           "-screen", "none", "-var", "name", "hs", "-var", "n", str(N), "-var", "amp", "0",
           "-var", "gravity", "full", "-var", "wall", "half", "-var", "S", "1",
           "-var", "tend", "15", "-var", "dump", "1", "-var", "K", str(K)]
    proc = run_cmd(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=600,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert proc.returncode == 0, (tmp_path / "log.hs").read_text()[-3000:]
    head, t, vrms, _, _ = rt.read_run(tmp_path / "hs.txt")
    assert vrms[-1] < 1e-8, "the flat column has not come to rest"

    rows = rt.hydrostatic(tmp_path / "hs.dump", tmp_path / "log.hs", K, H / N)
    y = np.array([r[0] for r in rows])
    typ = np.array([r[1] for r in rows])
    p = np.array([r[2] for r in rows])
    assert set(np.round(typ, 6)) == {1.0, 2.0}, "every row holds one fluid"
    light, heavy = typ == 1.0, typ == 2.0
    y_int = 0.5 * (y[light].max() + y[heavy].min())

    # the heavy fluid away from the lid: the gradient of its weight per area
    w_heavy = head["phi"] * head["rho_heavy"] * G
    w_light = head["phi"] * head["rho_light"] * G
    fit = heavy & (y < H - 3 * H / N)
    slope, icpt = np.polyfit(y[fit], p[fit], 1)
    assert abs(-slope / w_heavy - 1.0) < 0.01, f"heavy dP/dy {slope:.6g} against {-w_heavy:.6g}"

    # the light layer continues the heavy fluid's pressure at the interface with its own weight
    p_int = slope * y_int + icpt
    expected = p_int + w_light * (y_int - y[light])
    err = np.abs(p[light] / expected - 1.0)
    assert err.max() < 0.01, f"light rows off hydrostatic by {err.max():.3%} " \
        f"(P {p[light]} against {expected})"


def test_fluid_disc_without_radius_is_refused(tmp_path):
    """the sums weigh a partner by its size: a fluid disc of radius 0 is an error naming it"""
    from lmprun import run_lmp
    from test_timestep import LAWS, deck
    style, coeffs = LAWS["fluid only"]
    text = deck(style, coeffs, step="timestep 1e-3").replace(
        "set group all density/disc 2200",
        "set group all density/disc 2200\nset atom 17 diameter 0.0")
    run = run_lmp(text, tmp_path)
    assert run.rc != 0
    err = run.error() or ""
    assert "radius 0" in err and "atom 17" in err and "diameter" in err, run.out[-2000:]
