#!/usr/bin/env python3
"""A salt film on an incline (bench/validation/salt_film.in) against its analytic profile.

The film: the SPH salt of pair saltdem/viscous on a no-slip base of one line of wall discs
(as the scenes' basements), free top, x periodic, gravity tilted by sin(theta).  Analytic:

  u(y) = rho g sin (H y - y^2 / 2) / eta,    u_s = rho g sin H^2 / (2 eta),
  mean u = rho g sin H^2 / (3 eta)

with y from the top of the wall discs, rho the salt's mass per area in the interior of the film
(the profile's bins more than 2h from the base and the top) and H = M / (W rho).  Reported:

  us     the film's surface velocity (the profile's mean over its top 2h, extrapolated to the
         top with the fitted parabola) over the analytic u_s
  mean   the salt's mean velocity over the analytic mean
  eta    -rho g sin / (2 c) from the curvature c of a parabola fitted to the interior
  slip   where that parabola reaches u = 0, below the wall discs' top (m; > 0: the salt slips)

  PYTHONPATH=python python3 bench/validation/salt_film.py [--lmp build/lmp] [--work out/salt_film] [--json FILE]
        [--case NAME:H:key=value,...] [--seconds 60] [--W 400] [--dim 3 --D 100]

  --dim 3: the film as a slab of spheres D deep along z (x and z periodic; a pack of
  tools/pack.in -var dim 3, settled with the 2D stiffness times rmin + rmax), on a layer of wall
  spheres; M / W is then M / (W D), the mass per area, and rho a mass per volume.  The salt-wall
  core kn_wall defaults to 5e9 x (rmin + rmax), the 3D scenes' rule.

  (case keys: the deck's variables, and rmin, rmax, seed of the pack)
"""
import argparse
import json
import pathlib
import subprocess

import numpy as np

from saltdem_post.checkout import lmp_path, make_pack

ROOT = pathlib.Path(__file__).resolve().parents[2]


def read_blocks(path):
    blocks, cur = [], None
    for line in pathlib.Path(path).read_text().splitlines():
        if line.startswith("#"):
            continue
        s = line.split()
        if len(s) == 3:
            cur = []
            blocks.append(cur)
        elif cur is not None:
            cur.append([float(v) for v in s])
    return [np.array(b) for b in blocks]


def marker(text, key):
    for line in text.splitlines():
        if line.startswith(key + " "):
            s = line.split()
            return {s[k]: float(s[k + 1]) for k in range(1, len(s) - 1, 2)}
    raise ValueError(f"no '{key}' line in the log")


def thermo_last(text):
    cols, last = None, None
    for line in text.splitlines():
        s = line.split()
        if s[:2] == ["Step", "Time"]:
            cols = s
        elif cols and len(s) == len(cols) and s[0].isdigit():
            last = dict(zip(cols, map(float, s)))
    return last


def analyse(text, profile, h, rmax=15.625):
    """The film's measures from a log and its profile file (the last block: the time average
    over the second half of the run)."""
    m = marker(text, "FILM")
    prof = read_blocks(profile)[-1]
    last = thermo_last(text)
    ytop = last["v_ytop"] - m["y0"]
    y, n, vx, dens = prof[:, 1] - m["y0"], prof[:, 2], prof[:, 3], prof[:, 4]
    full = n > 0
    gs = m["g"] * m["slope"]
    eta = m["eta"]
    mw = m["M"] / (m["W"] * m.get("D", 1.0))   # mass per width (2D), per area (3D)
    ycm = np.sum(dens * y) / np.sum(dens)      # the salt's centre of mass above the base
    tau_b = gs * mw                            # the base's shear stress
    us_ana = tau_b * ycm / eta                 # = int_0^top tau(y) / eta dy
    top = full & (y > ytop - 2 * rmax)
    us = np.average(vx[top], weights=n[top])
    # the film as a layer of uniform density (the interior's, bins more than 2h from the base
    # and the top) and thickness H = M / (W rho) on the base: rho g sin H^2 / (2 eta)
    inner = full & (y > 2 * h) & (y < ytop - 2 * h)
    rho = dens[inner].mean()
    H = mw / rho
    us_uni = rho * gs * H * H / (2 * eta)
    # the interior's curvature
    c, b, a = np.polyfit(y[inner], vx[inner], 2, w=np.sqrt(n[inner]))
    return dict(H=H, ycm=ycm, rho=rho, ytop=ytop, us=us, us_ana=us_ana, ratio=us / us_ana,
                ratio_uniform=us / us_uni, slip=(us - us_ana) * eta / tau_b,
                eta=-rho * gs / (2 * c) / eta, mean=last["v_vx"] / (2.0 / 3.0 * us_uni))


def run_case(lmp, work, name, pack, seconds, rmax=15.625, **var):
    wdir = work / name
    wdir.mkdir(parents=True, exist_ok=True)
    h = var.get("h", 28)
    cmd = [lmp, "-in", str(ROOT / "bench" / "validation" / "salt_film.in"), "-log", "log.lammps", "-screen",
           "none", "-nocite", "-var", "pack", str(pack)]
    if str(var.get("dim", 2)) == "3":
        # the deck turns seconds into steps of the step saltdem/timestep sets
        var.setdefault("seconds", seconds)
    else:
        # the step is set by saltdem/timestep; nsteps from an estimate of it
        dt = var.pop("dt_est", 0.008)
        var.setdefault("nsteps", int(round(seconds / dt)))
    for k, v in var.items():
        cmd += ["-var", k, str(v)]
    subprocess.run(cmd, cwd=wdir, check=True, stdout=subprocess.DEVNULL)
    text = (wdir / "log.lammps").read_text()
    return analyse(text, wdir / "film_profile.txt", h, rmax)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lmp", default=lmp_path(ROOT))
    ap.add_argument("--work", default=str(ROOT / "out" / "salt_film"))
    ap.add_argument("--seconds", type=float, default=60.0)
    ap.add_argument("--W", type=float, default=400.0)
    ap.add_argument("--dim", type=int, choices=(2, 3), default=2)
    ap.add_argument("--D", type=float, default=100.0, help="3D: the slab's depth along z (m)")
    ap.add_argument("--case", action="append", default=[],
                    help="NAME:H:key=value,... (e.g. f365:365:K=1e8,kn_wall=5e9)")
    ap.add_argument("--json")
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    lmp = str(pathlib.Path(args.lmp).resolve())
    cases = args.case or ["f190:190:", "f365:365:"]
    results = {}
    for spec in cases:
        name, H, kv = spec.split(":", 2)
        var = dict(item.split("=") for item in kv.split(",") if item)
        rmin = float(var.pop("rmin", 6.25))
        rmax = float(var.pop("rmax", 15.625))
        seed = int(var.pop("seed", 7))
        D = args.D if args.dim == 3 else None
        pack = make_pack(lmp, work / "packs", args.W, float(H), rmin, rmax, seed=seed, D=D)
        if "h" in var:
            var["h"] = float(var["h"])
        if args.dim == 3:
            var["dim"] = 3
            var.setdefault("kn_wall", 5e9 * (rmin + rmax))
        r = run_case(lmp, work, name, pack, args.seconds, rmax, **var)
        results[name] = r
        print(f"{name}: y_cm {r['ycm']:.1f} m, H {r['H']:.1f} m: u_s/ana {r['ratio']:.4f}, slip "
              f"length {r['slip']:.2f} m (uniform layer: u_s/ana {r['ratio_uniform']:.4f}, mean/ana "
              f"{r['mean']:.4f}); curvature eta/eta {r['eta']:.3f}", flush=True)
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
