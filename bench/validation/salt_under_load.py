#!/usr/bin/env python3
"""The SPH salt under load: validation flows with a hydrostatic or overburden pressure.

  slope    a salt layer (H ~ 200 m, the full preset's discs, h = 1.3 disc spacings, the
           scenes' eta 5e8 Pa s, K 1e9 Pa, S 20) flowing down a gentle slope (sin 0.0135)
           under its own weight on a no-slip base of wall discs, free top, x periodic
           (bench/validation/salt_slope.in).  Its flux per unit width against the lubrication value
           rho g sin(theta) H^3 / (3 eta) over time, at full gravity and at a tenth of it.
  couette  plane Couette flow under a weighted lid at pressure P (bench/validation/salt_couette.in):
           the lid's shear stress over the interior shear rate (layers more than 3 rmax from
           the bands), eta_eff / eta, at P 0.1, 2 and 20 MPa and lid speeds V 0.01, 0.04 and
           0.1 m/s over a gap of ~196 m (the stress against the rate at several pressures;
           at most 420 s each).

rho is the salt's mass per area in the interior of the layer (the profile), H = M / (W rho)
the thickness of a layer of that density on the base band's top, u the salt's mean velocity
(vcm), so that flux / lubrication = u / (rho g sin H^2 / (3 eta)).

  PYTHONPATH=python python3 bench/validation/salt_under_load.py [--lmp build/lmp] [--work out/salt_under_load]
        [--cases slope,couette] [--time 1500] [--extra 'PAIR STYLE KEYWORDS']
        [--couette P:V,...]

--extra: keywords for pair_style saltdem/viscous (e.g. 'noslip surface fill 8');
--couette: the lid pressures (Pa) and speeds (m/s) to run (default: all nine).

Each case is a few hundred discs (262 for the slope, 292 for Couette, 400 m wide); a slope run
of 1500 s is 214,000 steps, about 2-3 CPU minutes.  Writes WORK/results.json.
"""
import argparse
import json
import math
import pathlib
import subprocess

from saltdem_post import checkout
from saltdem_post.checkout import lmp_path

ROOT = pathlib.Path(__file__).resolve().parents[2]
RMIN, RMAX = 6.25, 15.625
ETA = 5e8
SLOPE = 0.0135
H_SALT = 25.0      # 1.3 disc spacings of the full preset's discs (examples/scene/laws.in)
DT = 0.007         # 0.95 of the stable limit at S 20, h 25


def make_pack(lmp, work, W, H, seed=7):
    """A settled pack of tools/pack.in, the full preset's discs (kept in work)."""
    out = work / f"pack_{W}x{H}_{seed}.data"
    if not out.exists():
        subprocess.run([lmp, "-in", str(ROOT / "tools" / "pack.in"), "-log", "none", "-screen",
                        "none", "-nocite", "-var", "W", str(W), "-var", "H", str(H), "-var", "rmin",
                        str(RMIN), "-var", "rmax", str(RMAX), "-var", "dist", "paper", "-var",
                        "seed", str(seed), "-var", "kn", "1e10", "-var", "out", out.name + ".tmp"],
                       cwd=work, check=True, stdout=subprocess.DEVNULL)
        (work / (out.name + ".tmp")).rename(out)
    return out


def run_deck(lmp, deck, wdir, variables):
    wdir.mkdir(parents=True, exist_ok=True)
    cmd = [lmp, "-in", str(ROOT / "bench" / "validation" / deck), "-log", "log.lammps", "-screen", "none",
           "-nocite"]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    subprocess.run(cmd, cwd=wdir, check=True, stdout=subprocess.DEVNULL)
    return (wdir / "log.lammps").read_text()


def thermo(text, first):
    """Rows of the last thermo table whose first column header is 'Step' and second 'Time'."""
    rows, cols = [], None
    for line in text.splitlines():
        s = line.split()
        if s[:2] == ["Step", "Time"]:
            cols, rows = s, []
        elif cols and len(s) == len(cols) and s[0].isdigit():
            rows.append(dict(zip(cols, map(float, s))))
        elif line.startswith("Loop time"):
            cols = None
    return rows


def read_chunks(path):
    """Blocks of fix ave/chunk output: list of (step, rows of [chunk, coord, count, ...])."""
    blocks, cur = [], None
    for line in pathlib.Path(path).read_text().splitlines():
        if line.startswith("#"):
            continue
        s = line.split()
        if len(s) == 3:
            cur = (int(s[0]), [])
            blocks.append(cur)
        elif cur is not None:
            cur[1].append([float(v) for v in s])
    return blocks


def marker(text, key):
    for line in text.splitlines():
        if line.startswith(key + " "):
            s = line.split()
            return {s[k]: float(s[k + 1]) for k in range(1, len(s) - 1, 2)}
    raise ValueError(f"no '{key}' line in the log")


def interior_density(block, lo, hi):
    """Mean mass per area of the bins with centres in [lo, hi]."""
    vals = [r[4] for r in block if lo <= r[1] <= hi and r[2] > 0]
    return sum(vals) / len(vals)


def slope_case(lmp, work, g, seconds, label, extra=""):
    pack = make_pack(lmp, work, 400, 232)
    nsteps = int(round(seconds / DT))
    nthermo = 5000
    text = run_deck(lmp, "salt_slope.in", work / label,
                    dict(pack=pack, dt=DT, nsteps=nsteps, nthermo=nthermo, g=g, slope=SLOPE,
                         eta=ETA, h=H_SALT, extra=extra))
    m = marker(text, "SLOPE")
    rows = thermo(text, "Step")
    blocks = read_chunks(work / label / "slope_profile.txt")
    y0 = m["y0"]
    ytop = rows[-1]["v_ytop"]
    rho = interior_density(blocks[-1][1], y0 + 40, ytop - 40)
    H = m["M"] / (m["W"] * rho)
    u_lub = rho * g * SLOPE * H * H / (3 * ETA)
    series = [(r["Time"], r["v_vx"] / u_lub) for r in rows if r["Time"] > 0]
    return dict(g=g, H=H, rho=rho, u_lub=u_lub, series=series)


def couette_case(lmp, work, P, V, seconds, label, extra="", geo=None):
    """eta_eff / eta per thermo block: the lid's stress over the interior shear rate.  geo: the
    3D or coarse variant (dim, D, radii, dist, W, H, h, dt; default the 2D full-preset case)."""
    g = dict(dim=2, D=None, radii=(RMIN, RMAX), dist="paper", W=400, H=263, h=H_SALT, dt=DT)
    g.update(geo or {})
    rmax = g["radii"][1]
    if geo is None:
        pack = make_pack(lmp, work, 400, 263)
    else:   # spheres (3D: stiffness x (rmin + rmax)) or other radii: the shared pack maker
        pack = checkout.make_pack(lmp, work / "packs", g["W"], g["H"], *g["radii"], dist=g["dist"],
                                  D=g["D"] if g["dim"] == 3 else None)
    var = dict(pack=pack, dt=g["dt"], P=P, V=V, nload=3000, nsteps=int(round(seconds / g["dt"])),
               nthermo=5000, eta=ETA, h=g["h"], extra=extra)
    if (g["radii"], g["dim"]) != ((RMIN, RMAX), 2):
        var.update(rmin=g["radii"][0], rmax=rmax)
    if g["dim"] == 3:
        var.update(dim=3, kn_wall=1e10 * sum(g["radii"]))
    text = run_deck(lmp, "salt_couette.in", work / label, var)
    m = marker(text, "COUETTE")
    rows = [r for r in thermo(text, "Step") if r["f_avt"] != 0.0]
    if not rows:
        raise SystemExit(f"{label}: no averaged stress in {seconds:g} s: the run needs more than the load "
                         f"and one thermo block ({(var['nload'] + var['nthermo']) * g['dt']:g} s); raise --time")
    blocks = read_chunks(work / label / "couette_profile.txt")
    series = []
    for (step, b), r in zip(blocks[-len(rows):], rows):
        inner = [x for x in b if m["y0"] + 3 * rmax < x[1] < r["v_ylid"] - 4 * rmax and x[2] > 0]
        n = len(inner)
        if n < 3:
            raise SystemExit(f"{label}: fewer than 3 profile bins between y0 + 3 rmax and the lid - 4 rmax "
                             f"({m['y0'] + 3 * rmax:g} to {r['v_ylid'] - 4 * rmax:g} m): raise the pack's H (--size)")
        my = sum(x[1] for x in inner) / n
        mv = sum(x[3] for x in inner) / n
        rate = (sum((x[1] - my) * (x[3] - mv) for x in inner)
                / sum((x[1] - my) ** 2 for x in inner))
        series.append((r["Time"], r["f_avt"] / rate / ETA))
    return dict(P=P, V=V, series=series)


def at(series, t):
    """The value of the series at the time nearest t."""
    return min(series, key=lambda p: abs(p[0] - t))[1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lmp", default=lmp_path(ROOT))
    ap.add_argument("--work", default=str(ROOT / "out" / "salt_under_load"))
    ap.add_argument("--cases", default="slope,couette")
    ap.add_argument("--time", type=float, default=1500.0)
    ap.add_argument("--extra", default="", help="pair_style saltdem/viscous keywords")
    ap.add_argument("--couette", default="", help="P:V,... (default: P 1e5, 2e6, 2e7 x V 0.01, 0.04, 0.1)")
    ap.add_argument("--dim", type=int, choices=(2, 3), default=2, help="couette: 3 for a slab of spheres")
    ap.add_argument("--D", type=float, help="couette, 3D: the slab's depth along z (m; default 100)")
    ap.add_argument("--radii", type=float, nargs=2, metavar=("RMIN", "RMAX"),
                    help=f"couette: the salt's radii (m; default {RMIN:g} {RMAX:g})")
    ap.add_argument("--dist", choices=("paper", "uniform"),
                    help="couette with --dim 3 or --radii: the radius distribution (default uniform)")
    ap.add_argument("--size", type=float, nargs=2, metavar=("W", "H"),
                    help="couette: the pack, bands included (m; default 400 263)")
    ap.add_argument("--h", type=float, help=f"couette: the salt's smoothing length (m; default {H_SALT:g})")
    ap.add_argument("--dt", type=float,
                    help=f"couette: the time step (s; default {DT:g}; 3D: inside 0.073 S rho h^2 / eta)")
    args = ap.parse_args()
    # any geometry option (or --dim 3) makes a pack with the shared pack maker; none, the 2D
    # full-preset pack
    given = dict(D=args.D, radii=args.radii and tuple(args.radii), dist=args.dist,
                 W=args.size and args.size[0], H=args.size and args.size[1], h=args.h, dt=args.dt)
    given = {k: v for k, v in given.items() if v is not None}
    geo = None
    if given or args.dim == 3:
        geo = dict(dim=args.dim, D=100.0, radii=(RMIN, RMAX), dist="uniform", W=400, H=263, h=H_SALT, dt=DT)
        geo.update(given)
    lids = ([tuple(float(v) for v in c.split(":")) for c in args.couette.split(",")] if args.couette
            else [(P, V) for P in (1e5, 2e6, 2e7) for V in (0.01, 0.04, 0.1)])
    work = pathlib.Path(args.work).resolve()
    work.mkdir(parents=True, exist_ok=True)
    results = {}
    if "slope" in args.cases:
        for g, label in ((9.81, "slope_g1"), (0.981, "slope_g01")):
            r = slope_case(args.lmp, work, g, args.time, label, args.extra)
            results[label] = r
            s = r["series"]
            print(f"{label}: H {r['H']:.1f} m, rho {r['rho']:.0f} kg/m^2, flux / lubrication "
                  + ", ".join(f"{at(s, t):.3f} ({t:.0f} s)" for t in (35, 290, 700, 1050, args.time)))
    if "couette" in args.cases:
        for P, V in lids:
            label = f"couette_P{P:g}_V{V:g}"
            r = couette_case(args.lmp, work, P, V, min(args.time, 420.0), label, args.extra, geo)
            results[label] = r
            s = r["series"]
            late = [v for t, v in s if t >= 0.5 * s[-1][0]]
            print(f"{label}: eta_eff / eta {sum(late) / len(late):.3f} (second half; "
                  f"{s[0][1]:.3f} at {s[0][0]:.0f} s, {s[-1][1]:.3f} at {s[-1][0]:.0f} s)", flush=True)
    (work / "results.json").write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
