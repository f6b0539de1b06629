"""Command line: ``saltdem-post COMMAND DUMP... [options]``.

Every command reads the dumps frame by frame, writes PNG/CSV/JSON into the
output directory (``-o``, default ``saltdem_post_out``; ``mapview``: ``-o``
names its PNG) and prints a short summary.  ``saltdem-post COMMAND -h`` lists
the options.
"""

from __future__ import annotations

import argparse
import os
from dataclasses import asdict
import sys
import warnings
from typing import List, Optional, Sequence

import numpy as np

from . import __version__
from .dump import DumpFormatError, expand_paths, iter_frames, read_frame, scan_frames, write_dump
from .materials import DEFAULT_MARKER_COLUMN, MATERIALS, MaterialMap, markers
from .measure import salt_thickness, vertical_profile
from .output import write_csv, write_json
from .slab import map_view, map_view_figure, section_at
from .strain import strain_between
# pick_stages and previous_frame: re-exported, the figure tests use them from here
from .stages import (fault_history, out_path as _out, pick_stages, previous_frame,  # noqa: F401
                     progress_for as _progress, read_stage_frames, select_stages, selection_for as _selection,
                     stage_displacements)

DEFAULT_STAGES = (100.0, 250.0, 500.0, 750.0, 1000.0)   # m of fault displacement, as in the paper
DEFAULT_INCREMENT = 50.0                                # m: incremental strain window


# ------------------------------------------------------------------ helpers

def _say(text: str) -> None:
    print(text, flush=True)      # summaries on stdout; progress and warnings go to stderr


# ----------------------------------------------------------------- commands

def cmd_info(args) -> dict:
    paths = expand_paths(args.dumps)
    headers = scan_frames(paths, _progress(args, "scanning"))
    if not headers:
        raise DumpFormatError("no frames found")
    first = read_frame(paths, 0)
    materials = MaterialMap.parse(args.types)
    types, radius = first["type"], first.radius if ("radius" in first or "diameter" in first) else None
    counts = {m: int(materials.mask(types, m).sum()) for m in MATERIALS}
    info = {
        "files": paths, "n_frames": len(headers),
        "timesteps": [h.timestep for h in headers], "natoms": [h.natoms for h in headers],
        "columns": headers[0].columns, "box_first": headers[0].box.to_dict(),
        "box_last": headers[-1].box.to_dict(), "types": str(materials),
        "material_counts_first_frame": counts,
        "type_counts_first_frame": {int(t): int(c) for t, c in zip(*np.unique(types, return_counts=True))},
    }
    if radius is not None:
        info["radius_m"] = {"min": float(radius.min()), "median": float(np.median(radius)),
                            "max": float(radius.max())}
    if args.marker_column in first:
        mk = first[args.marker_column]
        info["markers"] = {m: [int(mk[materials.mask(types, m)].min()), int(mk[materials.mask(types, m)].max())]
                           for m in ("cover", "salt") if counts[m]}
    write_json(_out(args, "info.json"), info)
    _say(f"{len(headers)} frame(s) in {len(paths)} file(s); timesteps {headers[0].timestep}"
         f"..{headers[-1].timestep}; {headers[0].natoms} atoms; columns: {' '.join(headers[0].columns)}")
    _say("materials (first frame): " + ", ".join(f"{m} {n}" for m, n in counts.items()))
    if radius is not None:
        _say(f"disc radius {radius.min():.3g}-{radius.max():.3g} m (median {np.median(radius):.3g} m)")
    return info


def cmd_fault(args) -> List[dict]:
    paths = expand_paths(args.dumps)
    rows = fault_history(paths, MaterialMap.parse(args.types), args.fault_x, _progress(args, "fault"))
    cols = ["frame", "timestep", "dx", "dy", "slip", "throw", "heave"]
    write_csv(_out(args, "fault.csv"), {c: np.array([r[c] for r in rows]) for c in cols})
    write_json(_out(args, "fault.json"), rows)
    last = rows[-1]
    _say(f"{len(rows)} frames; final fault displacement {last['slip']:.2f} m "
         f"(throw {last['throw']:.2f} m, heave {last['heave']:.2f} m) at step {last['timestep']}")
    return rows


def cmd_strain(args) -> List[dict]:
    from .figures import strain_figure
    paths = expand_paths(args.dumps)
    materials = MaterialMap.parse(args.types)
    sel = _selection(args, ["all"] if args.incremental else ["-1"])
    ref = None if args.incremental else read_frame(paths, int(args.ref))
    summaries, prev = [], None
    for frame in iter_frames(paths, sel, _progress(args, "strain")):
        if args.incremental:
            base, prev = prev, frame
        else:
            base = ref if frame.index != ref.index else None
        if base is None:
            continue
        field = strain_between(base, frame, args.radius, args.method, args.min_neighbours)
        tag = f"{base.timestep}_{frame.timestep}"
        summary = field.summary()
        if not args.no_csv:
            summary["csv"] = write_csv(_out(args, f"strain_{tag}.csv"), field.table())
        summary["png"] = strain_figure(field, frame, _out(args, f"strain_{args.quantity}_{tag}.png"), args.quantity,
                                       materials, args.vmax)["path"]
        summaries.append(summary)
        ms = summary["max_shear"]
        _say(f"steps {base.timestep} -> {frame.timestep}: {summary['n_particles']} discs, "
             f"max shear median {ms.get('median', np.nan):.3g}, p99 {ms.get('p99', np.nan):.3g}, "
             f"max {ms.get('max', np.nan):.3g} ({summary['n_undefined']} undefined)")
    if not summaries:
        raise ValueError("no frame pair to compare: select at least two frames")
    write_json(_out(args, "strain_summary.json"), summaries)
    return summaries


def cmd_thickness(args) -> List[dict]:
    from .figures import thickness_figure
    paths = expand_paths(args.dumps)
    materials = MaterialMap.parse(args.types)
    profiles, summaries = [], []
    for frame in iter_frames(paths, _selection(args, ["-1"]), _progress(args, "thickness")):
        p = salt_thickness(frame, materials, args.bin_width, args.x_range, args.gap, args.weld_thickness)
        s = p.summary()
        s["csv"] = write_csv(_out(args, f"thickness_{frame.timestep}.csv"), p.table())
        profiles.append(p)
        summaries.append(s)
        mn = s["minimum"]
        _say(f"step {frame.timestep}: salt thickness mean {s['mean_thickness_m']:.1f} m, "
             f"minimum {mn['thickness_m']:.1f} m at x = {mn['x_m'] / 1000:.3f} km; "
             f"{len(s['welds'])} weld(s) (< {p.weld_thickness:.1f} m), welded length {s['welded_length_m']:.0f} m")
    if len(profiles) > 1:
        write_csv(_out(args, "thickness_evolution.csv"), {
            "timestep": np.array([s["timestep"] for s in summaries]),
            "min_thickness": np.array([s["minimum"]["thickness_m"] for s in summaries], float),
            "x_min": np.array([s["minimum"]["x_m"] for s in summaries], float),
            "welded_length": np.array([s["welded_length_m"] for s in summaries])})
    thickness_figure(profiles, _out(args, "thickness.png"))
    write_json(_out(args, "thickness_summary.json"), summaries)
    return summaries


def cmd_profile(args) -> List[dict]:
    from .figures import profile_figure
    paths = expand_paths(args.dumps)
    materials = MaterialMap.parse(args.types)
    needs_ref = args.quantity in ("ux", "uy")
    ref = read_frame(paths, int(args.ref)) if needs_ref else None
    results = []
    for frame in iter_frames(paths, _selection(args, ["-1"]), _progress(args, "profile")):
        profiles = [vertical_profile(frame, x, args.quantity, materials, args.halfwidth, ref,
                                     args.bin_height, args.viscosity) for x in args.x]
        for p in profiles:
            s = p.summary()
            s["csv"] = write_csv(_out(args, f"profile_{args.quantity}_x{p.x:g}_{frame.timestep}.csv"), p.table())
            results.append(s)
            if p.fit is None:
                _say(f"step {frame.timestep}, x = {p.x:g} m: fewer than 3 salt discs in the window")
                continue
            f = p.fit
            _say(f"step {frame.timestep}, x = {p.x:g} m: salt {f.base:.0f}-{f.top:.0f} m ({f.thickness:.0f} m), "
                 f"{args.quantity} = {f.u_base:.4g} + Couette {f.couette:.4g}·η + Poiseuille "
                 f"{f.poiseuille:.4g}·4η(1-η), R² {f.r2:.3f}, n {f.n}")
        profile_figure(profiles, _out(args, f"profile_{args.quantity}_{frame.timestep}.png"))
    write_json(_out(args, f"profile_{args.quantity}_fits.json"), results)
    return results


def cmd_figure(args) -> dict:
    from .figures import PanelRow, paper_figure
    paths = expand_paths(args.dumps)
    materials = MaterialMap.parse(args.types)
    headers = scan_frames(paths)
    if not headers:
        raise DumpFormatError("no frames found")
    disp, source = stage_displacements(args, paths, headers, materials)
    stages = select_stages(args, disp, len(headers))
    # markers are rebuilt from the first frame when the dumps have none
    frames = read_stage_frames(args, paths, stages, [] if args.marker_column in headers[0].columns else [0])
    rows, report = [], []
    for target, cur, prev in stages:
        frame = frames[cur]
        field = (strain_between(frames[prev], frame, args.radius, args.method, args.min_neighbours)
                 if prev is not None else None)
        mk = markers(frame, materials, args.marker_column, reference=frames.get(0))
        if np.isfinite(disp[cur]):
            label = f"{disp[cur]:.0f} m fault displacement (step {frame.timestep})"
        else:
            label = f"step {frame.timestep}"
        inc = ""
        if prev is not None:
            span = (f"{disp[prev]:.0f}–{disp[cur]:.0f} m" if np.isfinite(disp[[prev, cur]]).all()
                    else f"steps {frames[prev].timestep}–{frame.timestep}")
            inc = f"incremental max. shear strain, {span}"
        rows.append(PanelRow(label, frame, mk, field, inc))
        report.append({"target_m": target, "frame": cur, "timestep": frame.timestep, "displacement_m": disp[cur],
                       "previous_frame": prev, "previous_displacement_m": disp[prev] if prev is not None else None,
                       "strain": field.summary() if field is not None else None})
    xlim, ylim = ([1000.0 * v for v in lim] if lim else None for lim in (args.xlim, args.ylim))   # km -> m
    info = paper_figure(rows, _out(args, args.name), materials, args.strain_max, xlim, ylim, args.dpi, args.title,
                        growth_offset=args.growth_offset)
    result = {"figure": info, "displacement_source": source, "increment_m": args.increment, "stages": report}
    write_json(_out(args, os.path.splitext(args.name)[0] + ".json"), result)
    _say(f"{info['path']}: {len(rows)} stage(s) ({source}); strain colour scale 0-{info['strain_max']:g}; "
         f"{info['pixels'][0]}x{info['pixels'][1]} px")
    for r in report:
        inc = (f"increment from frame {r['previous_frame']}" if r["previous_frame"] is not None
               else "first frame, no increment")
        _say(f"  {r['displacement_m']:.1f} m: frame {r['frame']} (step {r['timestep']}), {inc}")
    return result


def _section_name(path: str, timestep: int, several: bool, z: float) -> str:
    stem = os.path.basename(path)
    for ext in (".gz", ".txt"):
        stem = stem[:-len(ext)] if stem.endswith(ext) else stem
    step = f"_{timestep}" if several else ""      # a file of several frames: one name per frame
    return f"{stem}{step}_z{np.format_float_positional(z, trim='-')}.txt"


def cmd_section3d(args) -> List[dict]:
    paths = expand_paths(args.dumps)
    per_file = {}
    for h in scan_frames(paths):
        per_file[h.path] = per_file.get(h.path, 0) + 1
    rows = []
    for frame in iter_frames(paths, _selection(args, ["all"]), _progress(args, "section3d")):
        for z in args.z:
            sec = section_at(frame, z, args.width)
            path = _out(args, _section_name(frame.path, frame.timestep, per_file[frame.path] > 1, z))
            write_dump(path, [sec])
            width = sec.box.hi[2] - sec.box.lo[2]
            counts = {int(t): int(c) for t, c in zip(*np.unique(sec["type"], return_counts=True))}
            rows.append({"path": path, "timestep": frame.timestep, "z_m": z, "width_m": width,
                         "natoms": sec.natoms, "types": counts})
            _say(f"{path}: step {frame.timestep}, z = {z:g} ± {width / 2:.4g} m, {sec.natoms} spheres "
                 f"(by type: {', '.join(f'{t}: {c}' for t, c in counts.items())})")
    if not rows:
        raise ValueError("no frame selected")
    return rows


def cmd_mapview(args) -> dict:
    ref, cur = read_frame(args.ref, 0), read_frame(args.cur, -1)
    view = map_view(ref, cur, args.cell, args.radius, MaterialMap.parse(args.types))
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    map_view_figure(view, args.output)
    keys = ("top", "top_ref", "uplift", "dilatation", "shear", "salt_dz", "salt_thickness", "salt_dthick")

    def span(v):
        v = v[np.isfinite(v)]
        return [float(v.min()), float(v.max())] if v.size else [None, None]
    result = {**view, "range": {k: span(view[k]) for k in keys}, "png": args.output}
    if args.json:
        write_json(args.json, result)

    def text(key, fmt):
        return "..".join("-" if v is None else format(v, fmt) for v in result["range"][key])
    undefined = int(np.isnan(view["dilatation"]).sum())
    _say(f"{args.output}: {len(view['x'])} x {len(view['z'])} cells (x, z) of {view['cell'][0]:.4g} x "
         f"{view['cell'][1]:.4g} m, steps {ref.timestep} -> {cur.timestep}; top change {text('uplift', '+.1f')} m, "
         f"dilatation {text('dilatation', '.3g')}, max shear {text('shear', '.3g')} "
         f"({undefined} cell(s) without a strain); salt along strike {text('salt_dz', '+.1f')} m, "
         f"salt thickness change {text('salt_dthick', '+.1f')} m")
    return result


def _outcome_options(args):
    from .outcomes import OutcomeOptions
    return OutcomeOptions(
        scene=args.scene, fault_x=tuple(args.fault_x or ()), downslope=args.downslope,
        marker_column=args.marker_column, radius=args.radius, method=args.method,
        min_neighbours=args.min_neighbours, band_factor=args.band_factor, band_min_strain=args.band_min_strain,
        link=args.band_link, band_halfwidth=args.band_halfwidth, min_length=args.min_band_length,
        min_discs=args.min_band_discs, min_dip=args.min_dip, max_flank_fraction=args.max_flank_fraction,
        wall_margin=args.wall_margin, tip_tolerance=args.tip_tolerance, marker_window=args.marker_window,
        bin_width=args.bin_width, weld_thickness=args.weld_thickness, gap=args.gap, flow_min=args.flow_min,
        collapse_drop=args.collapse_drop, deformed_fraction=args.deformed_fraction,
        deformed_basal=args.deformed_basal, deformed_gap=args.deformed_gap)


def _say_outcome(r: dict) -> None:
    mn, w, f = r["salt"]["minimum"], r["salt"]["welds"], r["faults"]
    disp = r["displacement_m"]
    head = f"{disp:.0f} m" if disp is not None and np.isfinite(disp) else f"step {r['timestep']}"
    thirds = r["cover_motion"]
    ux = " / ".join(f"{thirds[k]['ux_m']:+.0f}" for k in ("left", "middle", "right")) if thirds else "-"
    _say(f"  {head} (frame {r['frame']}): salt min {mn['thickness_m']:.0f} m at x = {mn['x_m'] / 1000:.2f} km, "
         f"{w['count']} weld(s); {f['count']} cover fault(s) ({f['active']} active); "
         f"cover ux thirds {ux} m; interface relief {r['interface']['relief_m'] or 0:.0f} m")


def cmd_outcomes(args) -> dict:
    from .outcomes import frame_outcomes, outcomes_markdown
    paths = expand_paths(args.dumps)
    materials = MaterialMap.parse(args.types)
    opts = _outcome_options(args)
    headers = scan_frames(paths)
    if not headers:
        raise DumpFormatError("no frames found")
    disp, source = stage_displacements(args, paths, headers, materials)
    stages = select_stages(args, disp, len(headers))
    frames = read_stage_frames(args, paths, stages, [0])

    def at(k):
        return float(disp[k]) if k is not None else None
    results = [frame_outcomes(frames[cur], frames[0], frames.get(prev), materials, opts, at(cur), at(prev))
               for _, cur, prev in stages]
    tips = ", ".join(f"{x:g}" for x in opts.fault_x) or "none"
    notes = [f"Dumps: `{' '.join(args.dumps)}`; scene {opts.scene}; basement fault tips (initial x, m): {tips}; "
             f"displacement {source}; incremental strain over {args.increment:g} m.",
             f"Strong strain: max shear > max({opts.band_factor:g} x the cover's median, "
             f"{opts.band_min_strain:g}); lengths in `outcomes.json` (`lengths_m`)."]
    md = outcomes_markdown(results, args.title or "Outcomes", notes)
    with open(_out(args, "outcomes.md"), "w", encoding="utf-8") as fh:
        fh.write(md)
    result = {"dumps": paths, "scene": opts.scene, "fault_x_m": list(opts.fault_x), "displacement_source": source,
              "increment_m": args.increment, "options": asdict(opts), "frames": results}
    write_json(_out(args, "outcomes.json"), result)
    _say(f"{_out(args, 'outcomes.md')}: {len(results)} stage(s) ({source}), scene {opts.scene}")
    for r in results:
        _say_outcome(r)
    return result


# ------------------------------------------------------------------- parser

def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="saltdem-post",
        description="SaltDEM post-processing: strain, salt thickness and welds, fault displacement, "
                    "flow profiles and paper-style figures from the package's LAMMPS dumps; sections "
                    "and map views of 3D slabs.",
        epilog="Give the dumps first, then options: saltdem-post figure run/dump.*.txt.gz --at 100 250. "
               "See docs/postprocessing.md.")
    p.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("dumps", nargs="+", help="dump files or globs (text, optionally .gz)")
    common.add_argument("-o", "--out", default="saltdem_post_out", help="output directory (default %(default)s)")
    common.add_argument("--types", default=None,
                        help="type->material map, e.g. 'cover=1,4;salt=2;wall=3' (default cover=1;salt=2;wall=3)")
    common.add_argument("--marker-column", default=DEFAULT_MARKER_COLUMN, help="per-atom marker column")
    common.add_argument("-q", "--quiet", action="store_true", help="no progress display")
    frames = argparse.ArgumentParser(add_help=False)
    frames.add_argument("--frames", nargs="+", metavar="F",
                        help="frame indices (negative from the end) or slices a:b[:c], or 'all'")
    frames.add_argument("--timesteps", nargs="+", type=int, metavar="T", help="select frames by timestep")
    nb = argparse.ArgumentParser(add_help=False)
    nb.add_argument("--radius", type=float, help="neighbour radius in m (default two median disc diameters)")
    nb.add_argument("--method", choices=("radius", "delaunay"), default="radius", help="neighbour definition")
    nb.add_argument("--min-neighbours", type=int, default=3)
    fx = argparse.ArgumentParser(add_help=False)
    fx.add_argument("--fault-x", type=float, nargs="+", metavar="X",
                    help="x (m) separating footwall and hanging-wall basement discs; two for a keystone "
                         "(the displacement is then the slip on the first fault)")
    stages = argparse.ArgumentParser(add_help=False)
    stages.add_argument("--at", type=float, nargs="+", default=list(DEFAULT_STAGES),
                        help="fault displacements in m (default %(default)s)")
    stages.add_argument("--frames", nargs="+", metavar="F", help="use these frames instead of --at")
    stages.add_argument("--increment", type=float, default=DEFAULT_INCREMENT,
                        help="displacement window of the incremental strain, m (default %(default)s)")
    drive = stages.add_mutually_exclusive_group()
    drive.add_argument("--disp-per-step", type=float,
                       help="fault displacement per timestep (m); default: measure it from the basement")
    drive.add_argument("--rate", type=float,
                       help="drive rate (m/s): displacement = rate x (time - time of the first frame), "
                            "from the dumps' ITEM: TIME")

    def add(name, func, parents, help_):
        s = sub.add_parser(name, parents=parents, help=help_, description=help_)
        s.set_defaults(func=func)
        return s

    add("info", cmd_info, [common], "frames, columns, box, materials and disc sizes of the dumps")
    add("fault", cmd_fault, [common, fx], "fault displacement of every frame from the basement discs")

    s = add("strain", cmd_strain, [common, frames, nb],
            "per-disc strain: finite (each selected frame vs --ref) or --incremental (consecutive frames)")
    s.add_argument("--ref", default="0", help="reference frame index for finite strain (default 0)")
    s.add_argument("--incremental", action="store_true", help="strain between consecutive selected frames")
    s.add_argument("--quantity", default="max_shear",
                   help="field mapped in the PNG: max_shear, dilatation, rotation, d2min, exx, ...")
    s.add_argument("--vmax", type=float, help="colour-scale maximum")
    s.add_argument("--no-csv", action="store_true", help="skip the per-disc CSV (large for big scenes)")

    s = add("thickness", cmd_thickness, [common, frames],
            "salt thickness profile along x, its minimum and welds (default: last frame)")
    s.add_argument("--bin-width", type=float, help="column width in m (default two median disc diameters)")
    s.add_argument("--weld-thickness", type=float, help="weld threshold in m (default one salt disc diameter)")
    s.add_argument("--gap", type=float, help="pores shorter than this (m) count as salt (default half a disc diameter)")
    s.add_argument("--x-range", type=float, nargs=2, metavar=("X0", "X1"), help="x extent in m")

    s = add("profile", cmd_profile, [common, frames],
            "vertical profile through the salt at given x with a Couette + Poiseuille fit (default: last frame)")
    s.add_argument("--x", type=float, nargs="+", required=True, help="profile positions in m")
    s.add_argument("--quantity", default="vx",
                   help="vx (velocity, default), ux/uy (displacement since --ref: marker line), or any column")
    s.add_argument("--ref", default="0", help="reference frame for ux/uy (default 0)")
    s.add_argument("--halfwidth", type=float, help="half-width of the sampling window in m")
    s.add_argument("--bin-height", type=float, help="height of the averaging bins in m")
    s.add_argument("--viscosity", type=float, help="salt viscosity (Pa s), to report dp/dx")

    s = add("figure", cmd_figure, [common, nb, fx, stages],
            "paper-style panels: markers beside incremental shear strain at chosen fault displacements")
    s.add_argument("--strain-max", type=float, help="top of the strain colour scale (default: p99, rounded)")
    s.add_argument("--xlim", type=float, nargs=2, metavar=("X0", "X1"), help="x range in km")
    s.add_argument("--ylim", type=float, nargs=2, metavar=("Y0", "Y1"), help="y range in km")
    s.add_argument("--dpi", type=int, default=150)
    s.add_argument("--name", default="paper_figure.png", help="output file name")
    s.add_argument("--title")
    s.add_argument("--growth-offset", type=int, default=1000,
                   help="growth strata: cover discs with marker OFFSET + epoch (fix saltdem/sediment, "
                        "examples/scene/sediment.in) are coloured by epoch; 0: none (default %(default)s)")

    s = add("outcomes", cmd_outcomes, [common, nb, fx, stages],
            "the paper's statements per stage: salt thinning and welds, interface relief, cover faults "
            "(dip, sense, throw), rigid-block motion, end walls, salt flow character")
    s.add_argument("--scene", choices=("fault", "keystone", "tilted"), default="fault",
                   help="Expt 1 (basement fault), Expt 2 (keystone: two --fault-x) or Expt 3 (tilted)")
    s.add_argument("--downslope", choices=("right", "left"), default="right",
                   help="tilted scene: the downslope direction, reference for synthetic/antithetic")
    g = s.add_argument_group("cover faults (lengths in m; defaults in median cover-disc diameters d)")
    g.add_argument("--band-factor", type=float, default=4.0,
                   help="strong discs: max shear above this multiple of the cover's median (default %(default)s)")
    g.add_argument("--band-min-strain", type=float, default=0.02,
                   help="... and above this strain (default %(default)s)")
    g.add_argument("--band-link", type=float, help="connect strong discs closer than this (default 2 d)")
    g.add_argument("--band-halfwidth", type=float, help="band half-width around its line (default 2 d)")
    g.add_argument("--min-band-length", type=float, help="shorter bands are not faults (default 6 d)")
    g.add_argument("--min-band-discs", type=int, default=8, help="fewer discs are not a band (default %(default)s)")
    g.add_argument("--min-dip", type=float, default=20.0,
                   help="flatter bands are not faults, degrees (default %(default)s)")
    g.add_argument("--max-flank-fraction", type=float, default=0.5,
                   help="bands whose flanks have this fraction of strong discs are distributed "
                        "deformation, not faults (default %(default)s)")
    g.add_argument("--wall-margin", type=float, help="ignore strong discs this close to an end wall (default 3 d)")
    g.add_argument("--tip-tolerance", type=float,
                   help="a band ending this close to the surface / interface reaches it (default 3 d)")
    g.add_argument("--marker-window", type=float,
                   help="width of the strips beside a fault for throw and interface step (default 5 d)")
    g = s.add_argument_group("salt, walls, scenes")
    g.add_argument("--bin-width", type=float, help="thickness columns, m (default two median disc diameters)")
    g.add_argument("--weld-thickness", type=float, help="weld threshold, m (default one salt disc diameter)")
    g.add_argument("--gap", type=float, help="pores shorter than this (m) count as salt")
    g.add_argument("--flow-min", type=float,
                   help="salt-band offsets below this are no flow, m (default one salt disc diameter)")
    g.add_argument("--collapse-drop", type=float,
                   help="cover-edge subsidence relative to the wall that counts as collapse, m (default 2 d)")
    g.add_argument("--deformed-fraction", type=float, default=0.1,
                   help="keystone: a column is deformed when this fraction of its cover is strong "
                        "(default %(default)s)")
    g.add_argument("--deformed-basal", type=float, default=3.0,
                   help="keystone: the cover within this many disc diameters of a column's base does not "
                        "count: a raft shears there in every column (default %(default)s)")
    g.add_argument("--deformed-gap", type=float, default=3.0,
                   help="keystone: the deformed zone from the graben spans gaps of undeformed cover up to this "
                        "many disc diameters (default %(default)s)")
    s.add_argument("--title", help="heading of outcomes.md")

    s = sub.add_parser("section3d", parents=[frames],
                       help="3D slabs: 2D sections at given z, written as 2D dumps for the other commands",
                       description="3D slabs: the spheres within --width/2 of each plane z = Z (periodic in z), "
                                   "written without the z columns as DIR/<stem>_z<Z>.txt, so figure, outcomes, "
                                   "strain, ... run on them (default: every frame)")
    s.set_defaults(func=cmd_section3d)
    s.add_argument("dumps", nargs="+", help="3D dump files or globs (text, optionally .gz)")
    s.add_argument("--z", type=float, nargs="+", required=True, help="section planes, m along strike")
    s.add_argument("--width", type=float, help="slice thickness, m (default one median sphere diameter)")
    s.add_argument("-o", "--out", default="saltdem_post_out", help="output directory (default %(default)s)")
    s.add_argument("-q", "--quiet", action="store_true", help="no progress display")

    s = sub.add_parser("mapview", help="3D slabs: map of the cover's top between two frames "
                                       "(elevation change, horizontal dilatation and shear on x-z cells) "
                                       "and of the salt's flow along strike",
                       description="3D slabs: map view of the cover's top surface on x-z cells between REF "
                                   "and CUR: elevation change, and the horizontal dilatation and maximum "
                                   "shear of its top layer; and of the salt below: its mean displacement "
                                   "along strike and the change of its thickness")
    s.set_defaults(func=cmd_mapview)
    s.add_argument("ref", help="earlier 3D dump (its first frame)")
    s.add_argument("cur", help="later 3D dump (its last frame)")
    s.add_argument("--cell", type=float, help="cell size, m (default two median cover diameters)")
    s.add_argument("--radius", type=float, help="strain fit: top-layer spheres this close to a cell "
                                                "centre, m (default the cell size)")
    s.add_argument("--types", default=None, help="type->material map (default cover=1;salt=2;wall=3)")
    s.add_argument("-o", "--output", default=os.path.join("saltdem_post_out", "mapview.png"),
                   help="PNG (default %(default)s)")
    s.add_argument("--json", help="also write the per-cell arrays and their ranges here")

    s = sub.add_parser("compare", help="runs side by side against the paper's statements, per stage",
                       description="runs side by side against the paper's statements, per stage, "
                                   "from their outcomes.json (saltdem-post outcomes)")
    s.set_defaults(func=cmd_compare)
    s.add_argument("outcomes", nargs="+", help="outcomes.json of each run")
    s.add_argument("--labels", nargs="+", help="a name per run (column headings)")
    s.add_argument("--scene", default="expt1", help="the paper's scene: expt1, expt2, expt3 (default %(default)s)")
    s.add_argument("--figures", nargs="+", help="the runs' figures (PNG), put side by side")
    s.add_argument("-o", "--output", default="saltdem_post_out", help="output directory")
    s.add_argument("--name", default="comparison.md")
    s.add_argument("--figure-name", default="comparison.png")
    s.add_argument("--check", metavar="FILE", help="only say whether FILE is what the outcomes give")
    return p


def cmd_compare(args) -> dict:
    """Runs side by side against the paper: comparison.md (printed too) and, with --figures,
    one image of their figures."""
    import json
    from .compare import comparison_markdown, side_by_side
    labels = args.labels or [f"run {k + 1}" for k in range(len(args.outcomes))]
    if len(labels) != len(args.outcomes):
        raise ValueError(f"{len(labels)} --labels for {len(args.outcomes)} outcomes files")
    runs = {lab: json.load(open(p)) for lab, p in zip(labels, args.outcomes)}
    text = comparison_markdown(args.scene, runs)
    if args.check:
        old = open(args.check).read()
        if old != text:
            raise ValueError(f"{args.check} is not what the outcomes give now: run saltdem-post compare again")
        _say(f"{args.check}: up to date")
        return {"markdown": text}
    os.makedirs(args.output, exist_ok=True)
    md = os.path.join(args.output, args.name)
    with open(md, "w") as f:
        f.write(text)
    _say(text)
    _say(f"written: {md}")
    if args.figures:
        if len(args.figures) != len(labels):
            raise ValueError(f"{len(args.figures)} --figures for {len(labels)} runs")
        png = os.path.join(args.output, args.figure_name)
        side_by_side(args.figures, labels, png)
        _say(f"written: {png}")
    return {"markdown": text}


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = _parser().parse_args(argv)
    with warnings.catch_warnings():
        warnings.simplefilter("always", UserWarning)
        warnings.showwarning = lambda msg, *a, **k: print(f"saltdem-post: warning: {msg}", file=sys.stderr)
        try:
            args.func(args)
        except (OSError, DumpFormatError, ValueError, KeyError, IndexError, NotImplementedError) as exc:
            print(f"saltdem-post: error: {exc}", file=sys.stderr)
            return 2
    return 0
