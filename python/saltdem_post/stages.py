"""The stages of a run the commands report on: the drive displacement of every frame (given,
from the model time, or measured from the basement discs), the frames nearest the paper's
displacements and the frames an incremental strain window needs; and the small helpers the
commands share for options, output paths and progress."""

from __future__ import annotations

import os
import warnings
from typing import List, Optional, Sequence

import numpy as np

from .dump import iter_frames
from .materials import MaterialMap
from .measure import fault_displacement
from .output import ensure_dir, write_csv
from .progress import Progress
from .selection import FrameSelection


def progress_for(args, label: str) -> Optional[Progress]:
    return None if args.quiet else Progress(label)


def selection_for(args, default: Sequence[str]) -> FrameSelection:
    if args.frames or args.timesteps:
        return FrameSelection(args.frames, args.timesteps)
    return FrameSelection(list(default))


def out_path(args, name: str) -> str:
    return os.path.join(ensure_dir(args.out), name)


def tips_of(fault_x) -> List[float]:
    if fault_x is None:
        return []
    return sorted(float(x) for x in (fault_x if isinstance(fault_x, (list, tuple)) else [fault_x]))


def fault_history(paths: Sequence[str], materials: MaterialMap, fault_x=None,
                  progress: Optional[Progress] = None) -> List[dict]:
    """Fault displacement of every frame relative to the first one.

    ``fault_x``: None, one x or several (a keystone's two tips: then the
    displacement on the first fault, see ``outcomes.block_slip``)."""
    from .outcomes import block_slip
    tips = tips_of(fault_x)
    rows, ref = [], None
    for frame in iter_frames(paths, progress=progress):
        wall = frame.subset(materials.mask(frame["type"], "wall"))
        if ref is None:
            ref = wall
        if not wall.natoms:
            fd = None
        elif len(tips) > 1:
            fd = block_slip(ref, wall, materials, tips)
        else:
            fd = fault_displacement(ref, wall, materials, tips[0] if tips else None)
        row = {"frame": frame.index, "timestep": frame.timestep, "time": frame.time}
        row.update(fd.to_dict() if fd else {"dx": np.nan, "dy": np.nan, "slip": np.nan,
                                             "throw": np.nan, "heave": np.nan})
        rows.append(row)
    return rows


def previous_frame(disp: Sequence[float], cur: int, increment: float) -> Optional[int]:
    """The frame before ``cur`` whose displacement is nearest to ``increment``
    metres less; among equals the latest (so a run without fault motion
    falls back to the preceding frame)."""
    if cur <= 0:
        return None
    back = np.abs(np.asarray(disp[:cur], float) - (disp[cur] - increment))[::-1]
    if not np.isfinite(back).any():
        return cur - 1
    return cur - 1 - int(np.nanargmin(back))


def pick_stages(disp: Sequence[float], targets: Sequence[float], increment: float):
    """For each target displacement: (target, frame nearest to it, frame
    ``increment`` metres earlier or None)."""
    disp = np.asarray(disp, float)
    if not np.isfinite(disp).any():
        raise ValueError("no fault displacement could be measured (no wall/basement discs?); "
                         "give --disp-per-step or check --types")
    stages = []
    for target in targets:
        cur = int(np.nanargmin(np.abs(disp - target)))
        stages.append((float(target), cur, previous_frame(disp, cur, increment)))
    return stages


def stage_displacements(args, paths: Sequence[str], headers, materials: MaterialMap):
    """Drive displacement of every frame and how it was obtained: from
    ``--disp-per-step`` (x timestep), ``--rate`` (x time since the first
    frame, from the dumps' ITEM: TIME) or measured from the basement discs
    (``--fault-x``); the measured history is also written to fault.csv."""
    if args.disp_per_step is not None:
        disp = np.array([(h.timestep - headers[0].timestep) * args.disp_per_step for h in headers])
        return disp, f"{args.disp_per_step:g} m per timestep"
    if args.rate is not None:
        missing = [h.index for h in headers if h.time is None]
        if missing:
            raise ValueError(f"--rate needs the model time in every frame (ITEM: TIME, LAMMPS dump_modify "
                             f"time yes); frame {missing[0]} has none")
        disp = np.array([(h.time - headers[0].time) * args.rate for h in headers])
        return disp, f"{args.rate:g} m/s x model time"
    history = fault_history(paths, materials, args.fault_x, progress_for(args, "fault displacement"))
    write_csv(out_path(args, "fault.csv"), {c: np.array([r[c] for r in history])
                                        for c in ("frame", "timestep", "dx", "dy", "slip")})
    return np.array([r["slip"] for r in history]), "measured from the basement discs"


def select_stages(args, disp: np.ndarray, n_frames: int):
    """(target, frame, previous frame) per stage: ``--frames`` as given, or
    the frame nearest each ``--at`` displacement (warning when the run does
    not get there; targets beyond the run that map to the same frame are
    dropped)."""
    if args.frames:
        return [(float(disp[c]), c, previous_frame(disp, c, args.increment))
                for c in FrameSelection(args.frames).resolve(n_frames)]
    stages = pick_stages(disp, args.at, args.increment)
    reached = float(np.nanmax(disp))
    for target, cur, _ in stages:
        if abs(disp[cur] - target) > 0.5 * args.increment:
            warnings.warn(f"no frame near {target:g} m of fault displacement (run reaches {reached:.1f} m); "
                          f"using frame {cur} at {disp[cur]:.1f} m")
    unique = {}
    for stage in stages:
        unique.setdefault(stage[1], stage)
    return list(unique.values())


def read_stage_frames(args, paths: Sequence[str], stages, extra: Sequence[int] = ()) -> dict:
    """The frames the stages need (current and previous), by index."""
    needed = {c for _, c, _ in stages} | {p for _, _, p in stages if p is not None} | set(extra)
    return {f.index: f for f in iter_frames(paths, FrameSelection(sorted(needed)),
                                            progress_for(args, "reading stages"))}
