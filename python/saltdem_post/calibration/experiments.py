"""The calibration experiments: the materials as LAMMPS resolves them, packs,
biaxial sets with their Mohr-Coulomb fit, the angle of repose, the Couette
sweep of the salt and the plane through a grid of micro-parameters."""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Dict, List, Optional, Sequence

import numpy as np

from ..dump import read_ave_chunk, read_ave_time
from ..output import ensure_dir
from .fit import BiaxialCurve, Couette, couette_fit, find_peak, mohr_coulomb_fit, newtonian_fit, repose_angle
from .runner import CalibrationError, Context, Job, note, run_jobs, run_one, say

# the cover's variables (pair saltdem/cohesive and the inertia-free integration); the ones in
# SCALED are forces or lengths that scale with the disc radius (rscale_cover)
COVER_NAMES = ("rscale_cover", "kn_cover", "kt_cover", "mu_cover", "coh_cover", "ten_cover", "rng_cover",
               "zn_cover", "zt_cover", "kr_cover", "mur_cover")
SCALED = ("coh_cover", "ten_cover", "rng_cover")
SALT_NAMES = ("eta", "rho", "rmin", "rmax", "kn_salt", "kn_wall", "K_salt", "h_salt", "S", "dt")
COHESION_KNOB = "cohesion"      # search knob: multiplies coh_cover, ten_cover and rng_cover

MPA = 1e6
PAPER_RADII = (6.25, 15.625)

# biaxial sample presets: pack size (m), disc radii (m) and their distribution (tools/pack.in
# 'dist': the full scenes draw the paper's power law, the quick scenes a uniform one), packs
# (seeds), confinements (Pa)
PRESETS = {
    "full": dict(W=400.0, H=800.0, rmin=6.25, rmax=15.625, dist="paper", seeds=(11, 12, 13, 14, 15, 16),
                 confinements=(1e6, 2e6, 5e6, 10e6)),
    "medium": dict(W=800.0, H=1600.0, rmin=12.5, rmax=31.25, dist="paper", seeds=(11, 12),
                   confinements=(1e6, 2e6, 5e6, 10e6)),
    "quick": dict(W=1600.0, H=3200.0, rmin=25.0, rmax=62.5, dist="uniform", seeds=(11, 12),
                  confinements=(1e6, 2e6, 5e6, 10e6)),
    "ci": dict(W=400.0, H=800.0, rmin=6.25, rmax=15.625, dist="paper", seeds=(11, 12),
               confinements=(1e6, 10e6)),
}
BIAXIAL_ERATE = 5e-4          # 1/s: axial strain rate (inertial number < 1e-3 at 1 MPa)
BIAXIAL_STRAIN = 0.08         # the peaks of the paper cover lie below 6 % axial strain
COUETTE_V = (0.01, 0.03, 0.1, 0.3, 1.0)         # m/s: two decades of shear rate
COUETTE_ETA = (2.5e8, 5e8, 1e9)                 # Pa s, at the reference V, S scaled with eta
COUETTE_VREF = 0.3


# ----------------------------------------------------------------- materials

def decks(ctx: Context) -> Path:
    """The calibration decks of the checkout."""
    return ctx.checkout / "examples" / "calibration"


def pack_tool(ctx: Context) -> Path:
    """tools/pack.in: the packing generator."""
    return ctx.checkout / "tools" / "pack.in"


def potentials(ctx: Context) -> Path:
    """The parameter files read by default and written by ``all``."""
    return ctx.checkout / "potentials"


def resolve_params(ctx: Context, path: Optional[Path], names: Sequence[str],
                   overrides: Dict[str, object]) -> Dict[str, float]:
    """Values of `names` after 'include path' in LAMMPS, with -var overrides
    (a params file's 'index' lines give way to them, and '$(...)' lines such
    as the radius scaling are evaluated by LAMMPS itself)."""
    d = ensure_dir(str(ctx.out / "params"))
    lines = [f"include {path}"] if path else []
    for n in names:
        lines.append(f'if "$(is_defined(variable,{n}))" then "print \'PARAM {n} ${{{n}}}\'"')
    deck = Path(d) / "resolve.in"
    deck.write_text("\n".join(lines) + "\n")
    job = run_one(ctx, Job(deck, Path(d), dict(overrides), "parameters", always=True))
    vals = {}
    for m in re.finditer(r"^PARAM (\S+) (\S+)$", job.output, re.M):
        vals[m.group(1)] = float(m.group(2))
    missing = [n for n in names if n not in vals]
    if missing:
        raise CalibrationError(f"parameters {', '.join(missing)} are defined neither in {path} nor by --set")
    return vals


def cover_material(ctx: Context, params: Optional[str], sets: Dict[str, str], rscale: float) -> Dict[str, float]:
    """The cover's variables for discs rscale times the paper's: the file and
    --set values are read at rscale_cover 1 (values for 6.25-15.625 m discs)
    and the size-dependent ones (SCALED) are multiplied by rscale here."""
    path = Path(params) if params else potentials(ctx) / "cover_paper.params"
    over = dict(sets)
    over["rscale_cover"] = 1
    m = resolve_params(ctx, path, COVER_NAMES, over)
    for k in SCALED:
        m[k] *= rscale
    m["rscale_cover"] = rscale
    return m


def salt_material(ctx: Context, params: Optional[str], sets: Dict[str, str]) -> Dict[str, float]:
    path = Path(params) if params else potentials(ctx) / "salt_paper.params"
    return resolve_params(ctx, path, SALT_NAMES, sets)


def apply_knob(material: Dict[str, float], name: str, value: float) -> Dict[str, float]:
    m = dict(material)
    if name == COHESION_KNOB:
        for k in SCALED:
            m[k] = material[k] * value
    else:
        if name not in m:
            raise ValueError(f"unknown search knob {name!r}: one of {', '.join(COVER_NAMES)} or {COHESION_KNOB}")
        m[name] = value
    return m


# ------------------------------------------------------------------- biaxial

def sample_spec(preset: str, args) -> dict:
    s = dict(PRESETS[preset])
    if getattr(args, "size", None):
        s["W"], s["H"] = args.size
    if getattr(args, "radii", None):
        s["rmin"], s["rmax"] = args.radii
    if getattr(args, "dist", None):
        s["dist"] = args.dist
    if getattr(args, "seeds", None):
        s["seeds"] = tuple(args.seeds)
    if getattr(args, "confinements", None):
        s["confinements"] = tuple(c * MPA for c in args.confinements)
    s["rscale"] = s["rmin"] / PAPER_RADII[0]
    if getattr(args, "dim", 2) == 3:
        # a 3D triaxial test (biaxial.in -var dim 3): a box W x H x D of spheres
        s["dim"], s["D"] = 3, float(getattr(args, "depth", None) or s["W"])
    if getattr(args, "plane_strain", False):
        if not is_3d(s):
            raise ValueError("--plane-strain is a 3D option (--dim 3): a 2D biaxial test is plane strain already")
        s["zwalls"] = "fixed"
    return s


def is_3d(sample: dict) -> bool:
    return sample.get("dim", 2) == 3


def make_packs(ctx: Context, sample: dict, kn: float) -> Dict[int, Path]:
    d = ensure_dir(str(ctx.out / "packs"))
    packs, jobs = {}, []
    extra = {}
    size = f"{sample['W']:g}x{sample['H']:g}"
    if is_3d(sample):
        # spheres settle with the 3D stiffness: kn per metre of thickness x (rmin + rmax), as the deck scales it
        kn = kn * (sample["rmin"] + sample["rmax"])
        extra = dict(dim=3, D=sample["D"])
        size = f"3d_{size}x{sample['D']:g}"
    for seed in sample["seeds"]:
        name = (f"pack_{size}_r{sample['rmin']:g}-{sample['rmax']:g}{sample['dist']}"
                f"_kn{kn:g}_s{seed}.data")
        p = Path(d) / name
        packs[seed] = p
        if not p.exists():
            jobs.append(Job(pack_tool(ctx), Path(d) / f"make_{p.stem}", dict(W=sample["W"], H=sample["H"],
                            rmin=sample["rmin"], rmax=sample["rmax"], dist=sample["dist"], seed=seed, kn=kn,
                            out=p, **extra), f"pack {name}"))
    run_jobs(ctx, jobs)
    for p in packs.values():
        if not p.exists():
            raise CalibrationError(f"the pack {p} was not written")
    return packs


def matched_erate(sample: dict, inertia: float, erate: float = BIAXIAL_ERATE) -> float:
    """The axial strain rate that gives the sample the inertial number
    I = erate d sqrt(S rho / p) of `erate` for the paper's discs at true
    inertia (S = 1): erate x (paper mean radius / mean radius) / sqrt(S)."""
    return erate * (sum(PAPER_RADII) / (sample["rmin"] + sample["rmax"])) / math.sqrt(inertia)


def biaxial_set(ctx: Context, material: Dict[str, float], sample: dict, label: str,
                erate: Optional[float] = None, strain_max: float = BIAXIAL_STRAIN, inertia: float = 1.0) -> dict:
    """Biaxial tests of one material at sample['confinements'] on each pack
    (sample['seeds']); peaks, Mohr-Coulomb fit of all peaks.  inertia: the
    cover's inertia factor S (fix saltdem/nve); erate None: matched_erate."""
    if not erate:
        erate = matched_erate(sample, inertia)
    packs = make_packs(ctx, sample, material["kn_cover"])
    root = ctx.out / "biaxial" / label
    jobs = []
    for s3 in sample["confinements"]:
        for seed in sample["seeds"]:
            v = dict(material)
            v.update(pack=packs[seed], W=sample["W"], H=sample["H"], rmin=sample["rmin"], rmax=sample["rmax"],
                     dist=sample["dist"],
                     sigma3=s3, erate=erate, strain_max=strain_max, S_cover=inertia, tag="t")
            if is_3d(sample):
                v.update(dim=3, D=sample["D"], zwalls=sample.get("zwalls", "servo"))
            jobs.append(Job(decks(ctx) / "biaxial.in", root / f"s{s3 / MPA:g}MPa_seed{seed}", v,
                            f"biaxial {label} sigma3 {s3 / MPA:g} MPa pack {seed}"))
    run_jobs(ctx, jobs)
    tests = []
    for j in jobs:
        curve = BiaxialCurve.read(j.workdir / "biaxial_t.txt")
        pk = find_peak(curve)
        m = re.search(r"biaxial: (\d+) (?:discs|spheres)", j.output)
        tests.append(dict(sigma3_target=j.variables["sigma3"], seed=j.variables.get("pack").name.split("_s")[-1]
                          .split(".")[0], dir=str(j.workdir.relative_to(ctx.out)), discs=int(m.group(1)) if m else None,
                          peak=pk.to_dict(), seconds=j.seconds,
                          curve=dict(axial=curve.axial[::2].tolist(), volumetric=curve.volumetric[::2].tolist(),
                                     sigma1=curve.sigma1[::2].tolist(), sigma3=curve.sigma3[::2].tolist())))
        if not pk.reached:
            note(ctx, f"warning: {j.label}: the peak lies at the end of the test (strain {pk.axial:.3f}); "
                      "raise --strain-max")
    fit = mohr_coulomb_fit([t["peak"]["sigma3"] for t in tests], [t["peak"]["sigma1"] for t in tests])
    try:
        res = mohr_coulomb_fit([t["peak"]["residual_sigma3"] for t in tests],
                               [t["peak"]["residual_sigma1"] for t in tests]).to_dict()
    except ValueError:
        res = None
    out = dict(label=label, material=material, sample={k: (list(v) if isinstance(v, tuple) else v)
                                                      for k, v in sample.items()},
               erate=erate, strain_max=strain_max, inertia=inertia, tests=tests, fit=fit.to_dict(), residual_fit=res,
               seconds=sum(t["seconds"] for t in tests))
    say(f"biaxial {label}: phi = {fit.phi:.2f} +- {fit.phi_err:.2f} deg, C = {fit.cohesion / MPA:.3f} +- "
        f"{fit.cohesion_err / MPA:.3f} MPa ({len(tests)} tests, {sample['rmin']:g}-{sample['rmax']:g} m "
        f"{'spheres, 3D' if is_3d(sample) else 'discs'}, "
        f"inertia x {inertia:g})")
    return out


# -------------------------------------------------------------------- repose

def repose_run(ctx: Context, material: Dict[str, float], cohscale: float = 0.0, size=(800.0, 400.0),
               radii=PAPER_RADII, seed: int = 21, dist: str = "paper", dim: int = 2,
               depth: Optional[float] = None) -> dict:
    """The dam-break heap of repose.in and its angle.  dim 3: a slab of
    spheres `depth` m deep along z, periodic in z (repose.in -var dim 3 -var D
    depth, contact laws x (rmin + rmax)); the heap is uniform along z, so its
    angle is fitted from the spheres' x, y as in 2D."""
    three = dim == 3
    if dim not in (2, 3):
        raise ValueError(f"repose: dim = {dim} must be 2 or 3")
    if three and (depth is None or depth < 4 * radii[1]):
        raise ValueError(f"repose: a 3D heap needs a depth D (m) of at least 4 rmax = {4 * radii[1]:g} m: "
                         "give --depth")
    label = f"c{cohscale:g}" + ("_3d" if three else "")
    shape = f"{size[0]:g}x{size[1]:g}" + (f"x{depth:g}" if three else "")
    v = dict(material)
    v.update(L0=size[0], H0=size[1], rmin=radii[0], rmax=radii[1], dist=dist, seed=seed, cohscale=cohscale, tag="t",
             pack=Path(ensure_dir(str(ctx.out / "packs"))) /
             f"repose{'3d' if three else ''}_{shape}_r{radii[0]:g}-{radii[1]:g}{dist}_kn{material['kn_cover']:g}"
             f"_s{seed}.data")
    if three:
        v.update(dim=3, D=depth)
    what = f"repose {'3D ' if three else ''}cohscale {cohscale:g}"
    job = run_jobs(ctx, [Job(decks(ctx) / "repose.in", ctx.out / "repose" / label, v, what)])[0]
    # columns id x y radius (3D: then z)
    a = np.loadtxt(job.workdir / "repose_t.dump", skiprows=9)
    rep = repose_angle(a[:, 1], a[:, 2], a[:, 3])
    m = re.search(r"repose: released (\d+) (?:discs|spheres)", job.output)
    out = dict(cohscale=cohscale, size=list(size), radii=list(radii), dist=dist, material=material, dir=str(job.workdir.relative_to(ctx.out)),
               still_moving="still moving" in job.output, seconds=job.seconds, **rep.to_dict())
    if three:
        out.update(dim=3, depth=depth, spheres=int(m.group(1)) if m else None)
        say(f"repose 3D (cohesion x {cohscale:g}, {out['spheres']} spheres {radii[0]:g}-{radii[1]:g} m, block "
            f"{size[0]:g} x {size[1]:g} x {depth:g} m): angle {rep.angle:.1f} +- {rep.angle_err:.1f} deg, "
            f"heap {rep.height:.0f} m, {'STILL MOVING' if out['still_moving'] else 'at rest'}")
    else:
        say(f"repose (cohesion x {cohscale:g}): angle {rep.angle:.1f} +- {rep.angle_err:.1f} deg, "
            f"heap {rep.height:.0f} m")
    return out


# ------------------------------------------------------------------- couette

def pack_discs(path: Path) -> int:
    """The atom count of a LAMMPS data file."""
    with open(path, encoding="utf-8") as fh:
        for line in fh:
            if line.strip().endswith("atoms"):
                return int(line.split()[0])
    return 0


def couette_runs(ctx: Context, salt: Dict[str, float], velocities: Sequence[float], etas: Sequence[float],
                 vref: float, nsteps: int = 10000, W: float = 1000.0, H: float = 500.0, seed: int = 7,
                 dist: str = "paper", label: str = "couette") -> dict:
    pack = Path(ensure_dir(str(ctx.out / "packs"))) / \
        f"couette_{W:g}x{H:g}_r{salt['rmin']:g}-{salt['rmax']:g}{dist}_s{seed}.data"
    if not pack.exists():
        run_jobs(ctx, [Job(pack_tool(ctx), ctx.out / "packs" / f"make_{pack.stem}", dict(W=W, H=H, rmin=salt["rmin"],
                           rmax=salt["rmax"], dist=dist, seed=seed, kn=salt["kn_wall"], out=pack), "couette pack")])
    cases = [(V, salt["eta"]) for V in velocities] + [(vref, e) for e in etas if e != salt["eta"]]
    jobs = []
    for V, eta in cases:
        v = dict(salt)
        v.update(V=V, eta=eta, S=salt["S"] * eta / salt["eta"], nsteps=nsteps, W=W, H=H, dist=dist, seed=seed,
                 pack=pack, tag="t")
        jobs.append(Job(decks(ctx) / "couette.in", ctx.out / label / f"V{V:g}_eta{eta:g}", v,
                        f"couette V {V:g} m/s eta {eta:g} Pa s"))
    run_jobs(ctx, jobs)
    rmax = salt["rmax"]
    lo, hi = 2 * rmax + 3 * rmax, H - 2 * rmax - 3 * rmax        # interior: 3 rmax off the wall bands
    runs = []
    for j in jobs:
        st = read_ave_time(j.workdir / "couette_t_stress.txt")
        prof = read_ave_chunk(j.workdir / "couette_t_profile.txt")[-1]
        y, vx = prof[:, 1], prof[:, 3]
        rate, r2, eta_eff = couette_fit(y, vx, st[-1, 1], lo, hi)
        eta_in, V, S = j.variables["eta"], j.variables["V"], j.variables["S"]
        L = H - 4 * rmax
        c = Couette(V=V, tau=float(st[-1, 1]), rate=rate, eta_eff=eta_eff, r2=r2,
                    reynolds=S * salt["rho"] * V * L / eta_in, tau_first=float(st[0, 1]))
        runs.append(dict(eta_in=eta_in, S=S, dir=str(j.workdir.relative_to(ctx.out)), seconds=j.seconds,
                         profile=dict(y=y.tolist(), vx=vx.tolist()), **c.to_dict()))
    sweep = [r for r in runs if r["eta_in"] == salt["eta"]]
    nf = newtonian_fit([r["rate"] for r in sweep], [r["tau"] for r in sweep]) if len(sweep) >= 2 else None
    ratios = [r["eta_eff"] / r["eta_in"] for r in sweep]
    out = dict(salt=salt, nsteps=nsteps, vref=vref, dist=dist, pack_discs=pack_discs(pack), runs=runs, newtonian=nf, interior=[lo, hi],
               eta_eff_mean=float(np.mean([r["eta_eff"] for r in sweep])),
               ratio_mean=float(np.mean(ratios)), ratio_spread=float(np.ptp(ratios)) if ratios else None,
               rate_span=(max(r["rate"] for r in sweep) / min(r["rate"] for r in sweep)) if sweep else None)
    say(f"couette: eta_eff/eta = {out['ratio_mean']:.4f} (spread {out['ratio_spread']:.4f}) over "
        f"{out['rate_span']:.0f}x in shear rate" + (f"; power-law index n = {nf['n']:.4f}" if nf else ""))
    return out


# ------------------------------------------------------------------- search

def solve_plane(points: List[dict], knobs: List[str], target_phi: float, target_c: float) -> Optional[dict]:
    """phi and C as planes in the knobs over the grid; the knob values that
    give both targets (two knobs) or phi (one knob)."""
    X = np.array([[p["knobs"][k] for k in knobs] for p in points])
    A = np.column_stack([X, np.ones(len(X))])
    if len(points) < A.shape[1]:
        return None
    cphi, *_ = np.linalg.lstsq(A, np.array([p["phi"] for p in points]), rcond=None)
    cc, *_ = np.linalg.lstsq(A, np.array([p["cohesion"] for p in points]), rcond=None)
    if len(knobs) == 2:
        M = np.array([[cphi[0], cphi[1]], [cc[0], cc[1]]])
        rhs = np.array([target_phi - cphi[2], target_c - cc[2]])
        try:
            sol = np.linalg.solve(M, rhs)
        except np.linalg.LinAlgError:
            return None
    else:
        sol = np.array([(target_phi - cphi[1]) / cphi[0]])
    return dict(knobs={k: float(v) for k, v in zip(knobs, sol)}, phi_plane=cphi.tolist(), c_plane=cc.tolist())
