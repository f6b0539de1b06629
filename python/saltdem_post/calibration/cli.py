"""Command line: ``saltdem-calibrate [options] COMMAND [options]``.

Runs the calibration decks of ``examples/calibration/`` with the built
``lmp``, measures the emergent properties of a material and writes a report
(``report.md`` with tables, PNG plots, ``results.json``) into the output
directory (``-o``, default ``out/calibration``):

* ``biaxial``  biaxial tests of the cover at several confinements (and packs):
  peak deviatoric stress, Mohr-Coulomb fit -> bulk friction angle and
  cohesion with their standard errors;
* ``repose``   angle of repose of the cohesionless cover (dam-break heap);
* ``couette``  plane Couette flow of the salt: eta_eff against shear rate and
  against the input viscosity;
* ``search``   a grid of cover micro-parameters, each point a biaxial set; a
  plane through the grid gives the micro-parameters for target phi and C;
* ``all``      biaxial (scene radii and, for the size rule, the quick preset's
  radii), repose and couette, then the parameter files
  ``potentials/cover_NAME.params`` and ``potentials/salt_NAME.params``;
* ``report``   rebuild ``report.md`` and the plots from ``results.json``.

Every command merges its results into ``results.json`` of the output
directory and rewrites the report from all sections there, so a ``search``
followed by ``all`` in the same directory gives one report.  The decks,
``tools/pack.in``, ``potentials/`` and the default ``build/lmp`` are those of
the SaltDEM checkout (``find_repo``: $SALTDEM_ROOT, the checkout this package
sits in, or the one the current directory is in).  See docs/validation.md.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import datetime
import hashlib
import json
import math
import os
import re
import shlex
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence

import numpy as np

from ..dump import read_ave_chunk, read_ave_time
from ..output import ensure_dir, write_json
from .fit import (BiaxialCurve, Couette, MohrCoulomb, couette_fit, find_peak, mohr_coulomb_fit, newtonian_fit,
                  repose_angle)



def _is_checkout(path: Path) -> bool:
    return (path / "examples" / "calibration" / "biaxial.in").is_file() and (path / "tools" / "pack.in").is_file()


def find_repo() -> Optional[Path]:
    """The SaltDEM checkout whose decks, packing tool, potentials and build/lmp
    the calibration uses: $SALTDEM_ROOT if set, else the checkout this package
    sits in (python/saltdem_post/calibration/ of a checkout: the wrapper
    python/saltdem-calibrate), else (an installed package) the current
    directory or the nearest directory above it that is a checkout.  None if
    there is none; the commands that run LAMMPS then stop with an error."""
    env = os.environ.get("SALTDEM_ROOT")
    if env:
        return Path(env).resolve()
    here = Path(__file__).resolve().parents[3]
    if _is_checkout(here):
        return here
    cwd = Path.cwd().resolve()
    return next((d for d in (cwd, *cwd.parents) if _is_checkout(d)), None)


_FOUND = find_repo()
REPO = _FOUND if _FOUND is not None else Path(__file__).resolve().parents[3]
DECKS = REPO / "examples" / "calibration"
POTENTIALS = REPO / "potentials"
PACK_IN = REPO / "tools" / "pack.in"

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


class CalibrationError(RuntimeError):
    pass


def say(text: str) -> None:
    print(text, flush=True)


def note(ctx, text: str) -> None:
    if not ctx.quiet:
        print(f"saltdem-calibrate: {text}", file=sys.stderr, flush=True)


def fmt(v, digits=4) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return f"{v:.{digits}g}"


# ------------------------------------------------------------------- running

@dataclass
class Context:
    lmp: str
    out: Path
    jobs: int = 1
    quiet: bool = False
    rerun: bool = False


@dataclass
class Job:
    deck: Path
    workdir: Path
    variables: Dict[str, object]
    label: str
    output: str = ""
    seconds: float = 0.0
    reused: bool = False
    always: bool = False        # never reuse (e.g. a deck whose input files change)


def lmp_default() -> str:
    return os.environ.get("SALTDEM_LMP", str(REPO / "build" / "lmp"))


def run_one(ctx: Context, job: Job) -> Job:
    """Run one deck in its own directory.  A directory that holds the same
    command and the log of a finished run (LAMMPS's closing 'Total wall
    time') is reused unless ctx.rerun: an interrupted calibration resumes,
    and a set repeated with the same material and packs costs nothing.  The
    deck's SHA-1 is part of the command, so an edited deck runs again."""
    ensure_dir(str(job.workdir))
    cmd = [ctx.lmp, "-in", str(job.deck), "-echo", "none", "-screen", "none", "-log", "log.lammps",
           "-var", "root", str(REPO)]
    for k, v in job.variables.items():
        cmd += ["-var", k, str(v)]
    digest = hashlib.sha1(Path(job.deck).read_bytes()).hexdigest()
    text = f"# deck sha1 {digest}\n" + " ".join(shlex.quote(c) for c in cmd) + "\n"
    cfile, log = job.workdir / "command.sh", job.workdir / "log.lammps"
    if not (ctx.rerun or job.always) and cfile.exists() and cfile.read_text() == text and log.exists():
        out = log.read_text(errors="replace")
        m = re.search(r"^Total wall time: (\d+):(\d+):(\d+)", out, re.M)
        if m:
            job.output, job.reused = out, True
            job.seconds = 3600 * int(m.group(1)) + 60 * int(m.group(2)) + int(m.group(3))
            return job
    cfile.write_text(text)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    t0 = time.monotonic()
    proc = subprocess.run(cmd, cwd=job.workdir, capture_output=True, text=True, env=env)
    job.seconds = time.monotonic() - t0
    job.output = (log.read_text(errors="replace") if log.exists() else "") + proc.stdout + proc.stderr
    if proc.returncode != 0:
        err = next((l for l in job.output.splitlines() if "ERROR" in l), job.output[-800:])
        raise CalibrationError(f"{job.label}: lmp failed (rc {proc.returncode}) in {job.workdir}: {err}")
    return job


def run_jobs(ctx: Context, jobs: Sequence[Job]) -> List[Job]:
    """Run the jobs, ctx.jobs at a time; report each as it finishes."""
    if not jobs:
        return []
    t0, done = time.monotonic(), 0
    with concurrent.futures.ThreadPoolExecutor(max(1, ctx.jobs)) as ex:
        futs = {ex.submit(run_one, ctx, j): j for j in jobs}
        for f in concurrent.futures.as_completed(futs):
            j = f.result()
            done += 1
            el = time.monotonic() - t0
            note(ctx, f"[{done}/{len(jobs)}] {j.label} (" + ("reused, " if j.reused else "") +
                 f"{j.seconds:.0f} s; elapsed {el:.0f} s, ETA {el / done * (len(jobs) - done):.0f} s)")
    return list(jobs)


# ----------------------------------------------------------------- materials

def parse_sets(items: Optional[Sequence[str]]) -> Dict[str, str]:
    out = {}
    for it in items or ():
        if "=" not in it:
            raise ValueError(f"--set {it!r}: expected NAME=VALUE")
        k, v = it.split("=", 1)
        out[k.strip()] = v.strip()
    return out


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
    path = Path(params) if params else POTENTIALS / "cover_paper.params"
    over = dict(sets)
    over["rscale_cover"] = 1
    m = resolve_params(ctx, path, COVER_NAMES, over)
    for k in SCALED:
        m[k] *= rscale
    m["rscale_cover"] = rscale
    return m


def salt_material(ctx: Context, params: Optional[str], sets: Dict[str, str]) -> Dict[str, float]:
    path = Path(params) if params else POTENTIALS / "salt_paper.params"
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
    return s


def make_packs(ctx: Context, sample: dict, kn: float) -> Dict[int, Path]:
    d = ensure_dir(str(ctx.out / "packs"))
    packs, jobs = {}, []
    for seed in sample["seeds"]:
        name = (f"pack_{sample['W']:g}x{sample['H']:g}_r{sample['rmin']:g}-{sample['rmax']:g}{sample['dist']}"
                f"_kn{kn:g}_s{seed}.data")
        p = Path(d) / name
        packs[seed] = p
        if not p.exists():
            jobs.append(Job(PACK_IN, Path(d) / f"make_{p.stem}", dict(W=sample["W"], H=sample["H"],
                            rmin=sample["rmin"], rmax=sample["rmax"], dist=sample["dist"], seed=seed, kn=kn,
                            out=p), f"pack {name}"))
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
            jobs.append(Job(DECKS / "biaxial.in", root / f"s{s3 / MPA:g}MPa_seed{seed}", v,
                            f"biaxial {label} sigma3 {s3 / MPA:g} MPa pack {seed}"))
    run_jobs(ctx, jobs)
    tests = []
    for j in jobs:
        curve = BiaxialCurve.read(j.workdir / "biaxial_t.txt")
        pk = find_peak(curve)
        m = re.search(r"biaxial: (\d+) discs", j.output)
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
        f"{fit.cohesion_err / MPA:.3f} MPa ({len(tests)} tests, {sample['rmin']:g}-{sample['rmax']:g} m discs, "
        f"inertia x {inertia:g})")
    return out


# -------------------------------------------------------------------- repose

def repose_run(ctx: Context, material: Dict[str, float], cohscale: float = 0.0, size=(800.0, 400.0),
               radii=PAPER_RADII, seed: int = 21, dist: str = "paper") -> dict:
    label = f"c{cohscale:g}"
    v = dict(material)
    v.update(L0=size[0], H0=size[1], rmin=radii[0], rmax=radii[1], dist=dist, seed=seed, cohscale=cohscale, tag="t",
             pack=Path(ensure_dir(str(ctx.out / "packs"))) /
             f"repose_{size[0]:g}x{size[1]:g}_r{radii[0]:g}-{radii[1]:g}{dist}_kn{material['kn_cover']:g}_s{seed}.data")
    job = run_jobs(ctx, [Job(DECKS / "repose.in", ctx.out / "repose" / label, v, f"repose cohscale {cohscale:g}")])[0]
    a = np.loadtxt(job.workdir / "repose_t.dump", skiprows=9)
    rep = repose_angle(a[:, 1], a[:, 2], a[:, 3])
    out = dict(cohscale=cohscale, size=list(size), radii=list(radii), dist=dist, material=material, dir=str(job.workdir.relative_to(ctx.out)),
               still_moving="still moving" in job.output, seconds=job.seconds, **rep.to_dict())
    say(f"repose (cohesion x {cohscale:g}): angle {rep.angle:.1f} +- {rep.angle_err:.1f} deg, heap {rep.height:.0f} m")
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
        run_jobs(ctx, [Job(PACK_IN, ctx.out / "packs" / f"make_{pack.stem}", dict(W=W, H=H, rmin=salt["rmin"],
                           rmax=salt["rmax"], dist=dist, seed=seed, kn=salt["kn_wall"], out=pack), "couette pack")])
    cases = [(V, salt["eta"]) for V in velocities] + [(vref, e) for e in etas if e != salt["eta"]]
    jobs = []
    for V, eta in cases:
        v = dict(salt)
        v.update(V=V, eta=eta, S=salt["S"] * eta / salt["eta"], nsteps=nsteps, W=W, H=H, dist=dist, seed=seed,
                 pack=pack, tag="t")
        jobs.append(Job(DECKS / "couette.in", ctx.out / label / f"V{V:g}_eta{eta:g}", v,
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


# ------------------------------------------------------------------ results

def load_results(ctx: Context) -> dict:
    p = ctx.out / "results.json"
    return json.loads(p.read_text()) if p.exists() else {}


def save_results(ctx: Context, results: dict) -> None:
    results["updated"] = datetime.datetime.now().isoformat(timespec="seconds")
    write_json(str(ctx.out / "results.json"), results)
    from .report import write_report
    path = write_report(ctx.out, results)
    say(f"report: {path}")


# --------------------------------------------------------------- parameters

def params_text_cover(material: Dict[str, float], result: Optional[dict], quick: Optional[dict],
                      repose: Optional[dict], name: str, command: str) -> str:
    rs = material.get("rscale_cover", 1.0)
    base = {k: (material[k] / rs if k in SCALED else material[k]) for k in COVER_NAMES if k != "rscale_cover"}
    L = [f"# SaltDEM parameters: the {name} cover - frictional-cohesive, pair style saltdem/cohesive",
         "# (elastic + reversible cohesion + Mohr-Coulomb tangential spring + rolling resistance).",
         "#",
         "#   include /path/to/potentials/cover_" + name + ".params     # before the deck's own definitions",
         "#   pair_coeff 1 1 saltdem/cohesive ${kn_cover} ${kt_cover} ${mu_cover} ${coh_cover} ${ten_cover} &",
         "#              ${rng_cover} damp ${zn_cover} ${zt_cover} rolling ${kr_cover} ${mur_cover}",
         "#",
         "# Every line is an 'index' variable: a value given on the command line or defined earlier wins.",
         "# Size rule (2D, unit thickness): stiffnesses (N/m), friction and damping ratios are independent",
         "# of the disc size; the contact cohesion and tensile strength (forces, N) and the cohesive range",
         "# (a gap, m) scale with the disc radius.  They are given for radii 6.25-15.625 m times",
         "# rscale_cover: set 'variable rscale_cover index 4' before the include for discs 4x larger",
         "# (25-62.5 m).",
         f"# Measured with: {command}"]
    if result:
        f = result["fit"]
        L.append(f"# measured: phi {f['phi']:.2f} +- {f['phi_err']:.2f} deg, C {f['cohesion'] / MPA:.3f} +- "
                 f"{f['cohesion_err'] / MPA:.3f} MPa (biaxial, radii {result['sample']['rmin']:g}-"
                 f"{result['sample']['rmax']:g} m, {len(result['tests'])} tests)")
    if quick:
        f = quick["fit"]
        L.append(f"# measured: phi {f['phi']:.2f} +- {f['phi_err']:.2f} deg, C {f['cohesion'] / MPA:.3f} +- "
                 f"{f['cohesion_err'] / MPA:.3f} MPa (biaxial, radii {quick['sample']['rmin']:g}-"
                 f"{quick['sample']['rmax']:g} m, rscale_cover {quick['material']['rscale_cover']:g})")
    if repose:
        L.append(f"# measured: angle of repose {repose['angle']:.1f} +- {repose['angle_err']:.1f} deg "
                 f"(cohesion x {repose['cohscale']:g})")
    L.append("")
    doc = {
        "rscale_cover": "disc radii / (6.25-15.625 m)",
        "kn_cover": "N/m: normal contact stiffness",
        "kt_cover": "N/m: tangential contact stiffness",
        "mu_cover": "contact friction coefficient",
        "coh_cover": "N: contact cohesion (shear strength at zero normal force), x rscale_cover",
        "ten_cover": "N: contact tensile strength, x rscale_cover",
        "rng_cover": "m: gap at which the attraction vanishes, x rscale_cover",
        "zn_cover": "normal damping ratio (fraction of critical)",
        "zt_cover": "tangential damping ratio",
        "kr_cover": "N/m: rolling stiffness",
        "mur_cover": "rolling friction coefficient",
    }
    L.append(f"variable        {'rscale_cover':<13} index 1         # {doc['rscale_cover']}")
    for k, v in base.items():
        val = f"$({v:.6g}*v_rscale_cover)" if k in SCALED else f"{v:.6g}"
        L.append(f"variable        {k:<13} index {val:<9} # {doc[k]}")
    return "\n".join(L) + "\n"


def params_text_salt(salt: Dict[str, float], couette: dict, name: str, command: str) -> str:
    L = [f"# SaltDEM parameters: the {name} salt - linear Newtonian viscous, pair style saltdem/viscous",
         "# (fluid law salt-salt), integrated by fix saltdem/nve inertia ${S}.",
         "#",
         f"#   include /path/to/potentials/salt_{name}.params",
         "#",
         f"# Measured with: {command}",
         f"# measured: eta_eff / eta = {couette['ratio_mean']:.4f} (spread {couette['ratio_spread']:.4f}) over "
         f"{couette['rate_span']:.0f}x in shear rate, plane Couette"]
    if couette.get("newtonian"):
        L.append(f"# measured: power-law index n = {couette['newtonian']['n']:.4f}, tau0 = "
                 f"{couette['newtonian']['tau0']:.4g} Pa")
    L.append("")
    for k in SALT_NAMES:
        L.append(f"variable        {k:<13} index {salt[k]:.6g}")
    return "\n".join(L) + "\n"


def write_params(path: Path, text: str, force: bool) -> Path:
    if path.exists() and not force:
        raise CalibrationError(f"{path} exists: choose another --name or add --force")
    ensure_dir(str(path.parent))
    path.write_text(text)
    return path


# ----------------------------------------------------------------- commands

def command_line(argv) -> str:
    """The command as run, without the options that name local paths (-o, --lmp)."""
    keep, skip = [], False
    for a in argv:
        if skip:
            skip = False
            continue
        if a in ("-o", "--out", "--lmp"):
            skip = True
            continue
        if a.startswith(("--out=", "--lmp=")) or (a.startswith("-o") and len(a) > 2):
            continue
        keep.append(a)
    return "python/saltdem-calibrate " + " ".join(shlex.quote(a) for a in keep)


def cmd_biaxial(ctx: Context, args) -> dict:
    sample = sample_spec(args.preset, args)
    mat = cover_material(ctx, args.params, parse_sets(args.set), sample["rscale"])
    r = biaxial_set(ctx, mat, sample, args.label or args.preset, args.erate, args.strain_max, args.inertia)
    res = load_results(ctx)
    res.setdefault("biaxial", {})[r["label"]] = r
    res["targets"] = dict(phi=args.target_phi, cohesion=args.target_cohesion * MPA)
    save_results(ctx, res)
    return r


def cmd_repose(ctx: Context, args) -> dict:
    mat = cover_material(ctx, args.params, parse_sets(args.set), 1.0)
    r = repose_run(ctx, mat, args.cohscale, tuple(args.size), dist=args.dist)
    res = load_results(ctx)
    res.setdefault("repose", {})[f"c{args.cohscale:g}"] = r
    save_results(ctx, res)
    return r


def cmd_couette(ctx: Context, args) -> dict:
    salt = salt_material(ctx, args.params, parse_sets(args.set))
    label = args.label or "couette"
    r = couette_runs(ctx, salt, args.velocities, args.etas, args.vref, args.nsteps, dist=args.dist, label=label)
    if args.target_eta:
        r["target_eta"] = args.target_eta
        r["eta_input_for_target"] = args.target_eta / r["ratio_mean"]
        say(f"couette: input eta for eta_eff = {args.target_eta:g} Pa s: {r['eta_input_for_target']:.4g} Pa s")
    res = load_results(ctx)
    if label == "couette":
        res["couette"] = r
    else:
        res.setdefault("couette_checks", {})[label] = r
    save_results(ctx, res)
    return r


def parse_grid(items: Sequence[str]) -> List[tuple]:
    grid = []
    for it in items:
        if "=" not in it:
            raise ValueError(f"--grid {it!r}: expected NAME=v1,v2,...")
        k, vals = it.split("=", 1)
        grid.append((k.strip(), [float(v) for v in vals.split(",")]))
    if not 1 <= len(grid) <= 2:
        raise ValueError("--grid: give one or two knobs")
    return grid


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


def cmd_search(ctx: Context, args) -> dict:
    sample = sample_spec(args.preset, args)
    base = cover_material(ctx, args.params, parse_sets(args.set), sample["rscale"])
    grid = parse_grid(args.grid)
    knobs = [g[0] for g in grid]
    combos = [[v] for v in grid[0][1]] if len(grid) == 1 else [[a, b] for a in grid[0][1] for b in grid[1][1]]
    points = []
    for vals in combos:
        mat = dict(base)
        for k, v in zip(knobs, vals):
            mat = apply_knob(mat, k, v)
        label = "search_" + "_".join(f"{k}{v:g}" for k, v in zip(knobs, vals))
        r = biaxial_set(ctx, mat, sample, label, args.erate, args.strain_max, args.inertia)
        points.append(dict(knobs=dict(zip(knobs, vals)), label=label, phi=r["fit"]["phi"],
                           phi_err=r["fit"]["phi_err"], cohesion=r["fit"]["cohesion"],
                           cohesion_err=r["fit"]["cohesion_err"], material=mat))
    sol = solve_plane(points, knobs, args.target_phi, args.target_cohesion * MPA)
    out = dict(knobs=knobs, base=base, sample={k: (list(v) if isinstance(v, tuple) else v) for k, v in sample.items()},
               points=points, solution=sol, targets=dict(phi=args.target_phi, cohesion=args.target_cohesion * MPA))
    if sol:
        mat = dict(base)
        for k, v in sol["knobs"].items():
            mat = apply_knob(mat, k, v)
        out["suggested"] = mat
        say("search: the planes through the grid give " +
            ", ".join(f"{k} = {v:.4g}" for k, v in sol["knobs"].items()) +
            " -> " + " ".join(f"{k}={mat[k]:.4g}" for k in COVER_NAMES if k != "rscale_cover"))
    res = load_results(ctx)
    res["search"] = out
    save_results(ctx, res)
    return out


def cmd_all(ctx: Context, args, argv) -> dict:
    sets = parse_sets(args.set)
    res = load_results(ctx)
    res["targets"] = dict(phi=args.target_phi, cohesion=args.target_cohesion * MPA)
    full = sample_spec("full", args)
    mat = cover_material(ctx, args.params, sets, 1.0)
    res.setdefault("biaxial", {})["full"] = biaxial_set(ctx, mat, full, "full", args.erate, args.strain_max)
    save_results(ctx, res)
    if args.scene_inertia and args.scene_inertia != 1.0:
        # the scenes' full preset scales the cover's inertia (S_cover): the same material must not feel it
        fs = sample_spec("full", argparse.Namespace(confinements=args.confinements, seeds=args.check_seeds))
        res["biaxial"][f"full_S{args.scene_inertia:g}"] = biaxial_set(
            ctx, mat, fs, f"full_S{args.scene_inertia:g}", None, args.strain_max, args.scene_inertia)
        save_results(ctx, res)
    quick = None
    if not args.no_quick:
        # the quick preset: radii x4, cohesion x4 by the size rule, its inertia factor
        qs = sample_spec("quick", argparse.Namespace(confinements=args.confinements, seeds=args.check_seeds))
        qmat = cover_material(ctx, args.params, sets, qs["rscale"])
        quick = res["biaxial"]["quick"] = biaxial_set(ctx, qmat, qs, "quick", None, args.strain_max,
                                                      args.quick_inertia)
        save_results(ctx, res)
    rep = None
    if not args.no_repose:
        rep = res.setdefault("repose", {})["c0"] = repose_run(ctx, mat, 0.0)
        save_results(ctx, res)
    cou = None
    if not args.no_couette:
        salt = salt_material(ctx, args.salt_params, parse_sets(args.salt_set))
        cou = res["couette"] = couette_runs(ctx, salt, COUETTE_V, COUETTE_ETA, COUETTE_VREF)
        if args.target_eta:
            cou["target_eta"] = args.target_eta
            cou["eta_input_for_target"] = args.target_eta / cou["ratio_mean"]
        save_results(ctx, res)
    cmd = command_line(argv)
    written = []
    pdir = Path(args.potentials)
    if "cover" in args.write:
        text = params_text_cover(mat, res["biaxial"]["full"], quick, rep, args.name, cmd)
        written.append(write_params(pdir / f"cover_{args.name}.params", text, args.force))
        (ctx.out / f"cover_{args.name}.params").write_text(text)
    if "salt" in args.write and cou:
        salt = dict(cou["salt"])
        if cou.get("eta_input_for_target"):
            salt["eta"] = cou["eta_input_for_target"]
        text = params_text_salt(salt, cou, args.name, cmd)
        written.append(write_params(pdir / f"salt_{args.name}.params", text, args.force))
        (ctx.out / f"salt_{args.name}.params").write_text(text)
    res["params_files"] = [str(p) for p in written]
    save_results(ctx, res)
    for p in written:
        say(f"parameters: {p}")
    return res


def cmd_report(ctx: Context, args) -> dict:
    res = load_results(ctx)
    if not res:
        raise CalibrationError(f"no results.json in {ctx.out}")
    save_results(ctx, res)
    return res


# -------------------------------------------------------------------- parser

def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="saltdem-calibrate", description=__doc__.split("\n\n")[1],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-o", "--out", default="out/calibration", help="output directory (default %(default)s)")
    p.add_argument("--lmp", default=lmp_default(), help="LAMMPS executable (default $SALTDEM_LMP or build/lmp)")
    p.add_argument("-j", "--jobs", type=int, default=1, help="LAMMPS runs at a time (default 1)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress lines on stderr")
    p.add_argument("--rerun", action="store_true",
                   help="run every test again (default: reuse a finished run of the same command in -o)")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    cover = argparse.ArgumentParser(add_help=False)
    cover.add_argument("--params", help="cover params file (default potentials/cover_paper.params)")
    cover.add_argument("--set", action="append", metavar="NAME=VALUE",
                       help="override a cover variable (repeatable), e.g. --set mu_cover=0.6")
    targets = argparse.ArgumentParser(add_help=False)
    targets.add_argument("--target-phi", type=float, default=38.0, help="degrees (default %(default)s)")
    targets.add_argument("--target-cohesion", type=float, default=2.5, help="MPa (default %(default)s)")
    bx = argparse.ArgumentParser(add_help=False)
    bx.add_argument("--confinements", type=float, nargs="+", metavar="MPA", help="confining stresses in MPa")
    bx.add_argument("--seeds", type=int, nargs="+", help="pack seeds (one sample per seed and confinement)")
    bx.add_argument("--size", type=float, nargs=2, metavar=("W", "H"), help="pack size in m")
    bx.add_argument("--radii", type=float, nargs=2, metavar=("RMIN", "RMAX"), help="disc radii in m")
    bx.add_argument("--dist", choices=("paper", "uniform"),
                    help="radius distribution of tools/pack.in (default: the preset's)")
    bx.add_argument("--erate", type=float,
                    help=f"axial strain rate 1/s (default: {BIAXIAL_ERATE:g} for the paper's discs at true inertia, "
                         "scaled to the same inertial number for other radii and --inertia)")
    bx.add_argument("--inertia", type=float, default=1.0,
                    help="inertia factor S of the cover discs (fix saltdem/nve inertia; default 1)")
    bx.add_argument("--strain-max", type=float, default=BIAXIAL_STRAIN,
                    help="axial strain at the end of a test (default %(default)s)")

    def add(name, parents, help_):
        s = sub.add_parser(name, parents=parents, help=help_, description=help_)
        return s

    s = add("biaxial", [cover, bx, targets], "biaxial tests and the Mohr-Coulomb fit of one cover material")
    s.add_argument("--preset", choices=sorted(PRESETS), default="full",
                   help="sample: full (scene radii), quick (radii x4), ci (small, two confinements)")
    s.add_argument("--label", help="name of this set in the report (default: the preset)")

    s = add("repose", [cover], "angle of repose of the cover (dam-break heap)")
    s.add_argument("--cohscale", type=float, default=0.0, help="x contact cohesion and tensile (default 0)")
    s.add_argument("--size", type=float, nargs=2, default=(800.0, 400.0), metavar=("L0", "H0"))
    s.add_argument("--dist", choices=("paper", "uniform"), default="paper", help="radius distribution")

    s = add("couette", [], "plane Couette flow of the salt: eta_eff vs shear rate and vs input eta")
    s.add_argument("--params", help="salt params file (default potentials/salt_paper.params)")
    s.add_argument("--set", action="append", metavar="NAME=VALUE", help="override a salt variable")
    s.add_argument("--velocities", type=float, nargs="+", default=list(COUETTE_V), help="m/s")
    s.add_argument("--etas", type=float, nargs="+", default=list(COUETTE_ETA),
                   help="input viscosities (Pa s) at --vref, S scaled with eta")
    s.add_argument("--vref", type=float, default=COUETTE_VREF, help="m/s (default %(default)s)")
    s.add_argument("--nsteps", type=int, default=10000, help="steps per half of the run")
    s.add_argument("--target-eta", type=float, help="Pa s: report the input eta that gives this eta_eff")
    s.add_argument("--dist", choices=("paper", "uniform"), default="paper", help="radius distribution of the pack")
    s.add_argument("--label", help="store as a check set of this name (default: the main Couette sweep)")

    s = add("search", [cover, bx, targets], "grid of cover micro-parameters -> values for the target phi and C")
    s.add_argument("--grid", action="append", required=True, metavar="NAME=V1,V2,...",
                   help=f"knob values (one or two knobs); '{COHESION_KNOB}' multiplies coh, ten and rng")
    s.add_argument("--preset", choices=sorted(PRESETS), default="full")

    s = add("all", [cover, targets], "biaxial (scene and quick radii), repose, couette -> report and params files")
    s.add_argument("--confinements", type=float, nargs="+", metavar="MPA")
    s.add_argument("--seeds", type=int, nargs="+")
    s.add_argument("--erate", type=float, help="axial strain rate of the main set (default: matched, see biaxial)")
    s.add_argument("--strain-max", type=float, default=BIAXIAL_STRAIN)
    s.add_argument("--check-seeds", type=int, nargs="+", default=[11, 12],
                   help="packs of the inertia and quick-radii check sets (default %(default)s)")
    s.add_argument("--scene-inertia", type=float, default=20.0,
                   help="the full scenes' cover inertia factor: a check set at it (default %(default)s; 1: none)")
    s.add_argument("--quick-inertia", type=float, default=4.0,
                   help="the quick scenes' cover inertia factor (default %(default)s)")
    s.add_argument("--salt-params", help="salt params file (default potentials/salt_paper.params)")
    s.add_argument("--salt-set", action="append", metavar="NAME=VALUE")
    s.add_argument("--target-eta", type=float, help="Pa s: the salt params file gets the input eta for it")
    s.add_argument("--name", default="mine", help="writes potentials/cover_NAME.params, salt_NAME.params")
    s.add_argument("--write", default="cover,salt", help="which params files: cover, salt or both (default)")
    s.add_argument("--potentials", default=str(POTENTIALS), help="directory for the params files")
    s.add_argument("--force", action="store_true", help="overwrite existing params files")
    s.add_argument("--no-quick", action="store_true", help="skip the biaxial set at the quick preset's radii")
    s.add_argument("--no-repose", action="store_true")
    s.add_argument("--no-couette", action="store_true")

    add("report", [], "rewrite report.md and the plots from results.json")
    return p


def main(argv: Optional[Sequence[str]] = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    args = _parser().parse_args(argv)
    ctx = Context(lmp=args.lmp, out=Path(args.out).resolve(), jobs=args.jobs, quiet=args.quiet, rerun=args.rerun)
    ensure_dir(str(ctx.out))
    try:
        if args.command != "report" and not _is_checkout(REPO):
            raise CalibrationError(f"no SaltDEM checkout at {REPO} (no examples/calibration/biaxial.in or "
                                   "tools/pack.in): run from the checkout or set SALTDEM_ROOT")
        if args.command != "report" and not os.path.isfile(ctx.lmp):
            raise CalibrationError(f"no LAMMPS executable at {ctx.lmp}: build it or pass --lmp / SALTDEM_LMP")
        if args.command == "all":
            args.write = [w.strip() for w in args.write.split(",")]
            cmd_all(ctx, args, argv)
        else:
            {"biaxial": cmd_biaxial, "repose": cmd_repose, "couette": cmd_couette, "search": cmd_search,
             "report": cmd_report}[args.command](ctx, args)
    except (CalibrationError, ValueError, OSError) as exc:
        print(f"saltdem-calibrate: error: {exc}", file=sys.stderr)
        return 2
    return 0
