"""Command line: ``saltdem-calibrate [options] COMMAND [options]``.

Runs the calibration decks of ``examples/calibration/`` with the built
``lmp``, measures the emergent properties of a material and writes a report
(``report.md`` with tables, PNG plots, ``results.json``) into the output
directory (``-o``, default ``out/calibration``):

* ``biaxial``  biaxial tests of the cover at several confinements (and packs):
  peak deviatoric stress, Mohr-Coulomb fit -> bulk friction angle and
  cohesion with their standard errors;
* ``repose``   angle of repose of the cohesionless cover (dam-break heap;
  ``--dim 3 --depth D``: a slab of spheres D deep, periodic along z);
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
the SaltDEM checkout (``checkout.find_repo``: $SALTDEM_ROOT, the checkout this package
sits in, or the one the current directory is in).  See docs/validation.md.
"""

from __future__ import annotations

import argparse
import os
import shlex
import sys
from pathlib import Path
from typing import Dict, List, Optional, Sequence

from ..checkout import is_checkout, lmp_path, repo
from ..output import ensure_dir
from .experiments import (BIAXIAL_ERATE, BIAXIAL_STRAIN, COHESION_KNOB, COUETTE_ETA, COUETTE_V, COUETTE_VREF,
                          COVER_NAMES, MPA, PAPER_RADII, PRESETS, apply_knob, biaxial_set, couette_runs,
                          cover_material, potentials, repose_run, salt_material, sample_spec, solve_plane)
from .runner import CalibrationError, Context, say
from .writers import load_results, params_text_cover, params_text_salt, save_results, write_params


# --------------------------------------------------------- option values

def parse_sets(items: Optional[Sequence[str]]) -> Dict[str, str]:
    out = {}
    for it in items or ():
        if "=" not in it:
            raise ValueError(f"--set {it!r}: expected NAME=VALUE")
        k, v = it.split("=", 1)
        out[k.strip()] = v.strip()
    return out


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
    if args.depth is not None and args.dim != 3:
        raise ValueError("repose: --depth is the depth of a 3D slab: give it with --dim 3")
    radii = tuple(args.radii)
    # the size rule (cohesion, tensile strength and range x rmin / 6.25 m), as biaxial --radii does
    mat = cover_material(ctx, args.params, parse_sets(args.set), radii[0] / PAPER_RADII[0])
    r = repose_run(ctx, mat, args.cohscale, tuple(args.size), radii=radii, dist=args.dist, dim=args.dim,
                   depth=args.depth)
    res = load_results(ctx)
    res.setdefault("repose", {})[f"c{args.cohscale:g}" + ("_3d" if args.dim == 3 else "")] = r
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
    pdir = Path(args.potentials) if args.potentials else potentials(ctx)
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
    p.add_argument("--lmp", help="LAMMPS executable (default $SALTDEM_LMP or build/lmp)")
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
    bx.add_argument("--dim", type=int, choices=(2, 3), default=2,
                    help="2: biaxial tests of discs (default); 3: triaxial tests of spheres (biaxial.in -var dim 3, "
                         "contact laws x (rmin + rmax) as in the 3D scenes)")
    bx.add_argument("--depth", type=float, metavar="D",
                    help="3D: sample depth along z in m (default: the width W)")
    bx.add_argument("--plane-strain", action="store_true",
                    help="3D: hold the z walls while shearing (plane strain along z, as a slab periodic along "
                         "strike) instead of keeping sigma3 on them")

    def add(name, parents, help_):
        s = sub.add_parser(name, parents=parents, help=help_, description=help_)
        return s

    s = add("biaxial", [cover, bx, targets], "biaxial tests and the Mohr-Coulomb fit of one cover material")
    s.add_argument("--preset", choices=sorted(PRESETS), default="full",
                   help="sample: full (scene radii), medium (radii x2), quick (radii x4), ci (small, two confinements)")
    s.add_argument("--label", help="name of this set in the report (default: the preset)")

    s = add("repose", [cover], "angle of repose of the cover (dam-break heap)")
    s.add_argument("--cohscale", type=float, default=0.0, help="x contact cohesion and tensile (default 0)")
    s.add_argument("--size", type=float, nargs=2, default=(800.0, 400.0), metavar=("L0", "H0"))
    s.add_argument("--dist", choices=("paper", "uniform"), default="paper", help="radius distribution")
    s.add_argument("--radii", type=float, nargs=2, default=PAPER_RADII, metavar=("RMIN", "RMAX"),
                   help="disc radii in m (default %(default)s; the quick scenes': 25 62.5 with --dist uniform)")
    s.add_argument("--dim", type=int, choices=(2, 3), default=2,
                   help="2: a heap of discs (default); 3: a slab of spheres --depth deep, periodic in z "
                        "(repose.in -var dim 3, contact laws x (rmin + rmax) as in the 3D scenes)")
    s.add_argument("--depth", type=float, metavar="D",
                   help="3D: depth of the slab along z in m (at least 4 rmax)")

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
    s.add_argument("--potentials", help="directory for the params files")
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
        if args.command != "report":
            ctx.root = repo()
            if not is_checkout(ctx.root):
                raise CalibrationError(f"no SaltDEM checkout at {ctx.root} (no examples/calibration/biaxial.in or "
                                       "tools/pack.in): run from the checkout or set SALTDEM_ROOT")
            ctx.lmp = ctx.lmp or lmp_path(ctx.root)
            if not os.path.isfile(ctx.lmp):
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
