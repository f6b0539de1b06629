"""Markdown tables of the outcomes of a run: one summary table (a column per
frame) and a fault table per frame."""

from __future__ import annotations

from typing import List, Optional, Sequence, Tuple

import numpy as np


def _km(x) -> str:
    return "–" if x is None else f"{x / 1000:.2f} km"


def _m(v, signed: bool = False) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "–"
    return f"{v:+.0f} m" if signed else f"{v:.0f} m"


def _stage_label(r: dict) -> str:
    d = r.get("displacement_m")
    return f"{d:.0f} m" if d is not None and np.isfinite(d) else f"step {r['timestep']}"


def _weld_text(w: dict) -> str:
    if not w["count"]:
        return "none"
    a, b = w["x_range_m"]
    return f"{w['count']}: {_m(w['total_width_m'])} in {a / 1000:.2f}–{b / 1000:.2f} km"


def _minimum_text(mn: dict) -> str:
    if mn["x_m"] is None:
        return "–"
    return f"{_m(mn['thickness_m'])} at {_km(mn['x_m'])}"


def _relative_text(mn: dict) -> str:
    if mn.get("rel_tip_m") is None:
        return "–"
    return f"{_m(mn['rel_tip_m'], True)} / {_m(mn['rel_footwall_edge_m'], True)} ({mn['side']})"


def _interface_text(i: dict) -> str:
    if i["relief_m"] is None:
        return "–"
    return f"{_m(i['relief_m'])} (low {_km(i['x_low_m'])}, high {_km(i['x_high_m'])})"


def _faults_text(f: dict) -> str:
    if not f["count"]:
        return "none"
    return (f"{f['count']} ({f['active']} active; {f['synthetic']} synthetic, "
            f"{f['antithetic']} antithetic)")


def _thirds_text(c: dict) -> str:
    if not c:
        return "–"
    return " / ".join(_m(c[k]["ux_m"], True) for k in ("left", "middle", "right"))


def _wall_text(w: Optional[dict]) -> str:
    if not w:
        return "–"
    flags = [name for name in ("gap", "collapse") if w[name]]
    return (f"edge {_m(w['edge_distance_m'])}, salt rise {_m(w['salt_rise_m'], True)}, "
            f"edge drop {_m(w['edge_drop_m'], True)}" + (f" ({', '.join(flags)})" if flags else ""))


def _body_text(body) -> str:
    if not body or body["max_thickness_m"] is None:
        return "–"
    ext = body["extent_m"]
    where = f"{_km(ext[0])}-{_km(ext[1])}" if ext else "none"
    return f"{body['max_thickness_m']:.0f} m at {_km(body['x_max_m'])} / {where}"


def _flow_text(reg: dict) -> str:
    if not reg["n_bands"]:
        return "–"
    return f"{reg['character']}, {reg['direction']} ({reg['n_dominant']} of {reg['n_bands']} bands)"


def _summary_rows(results: Sequence[dict]) -> List[Tuple[str, List[str]]]:
    rows = [
        ("frame (step)", [f"{r['frame']} ({r['timestep']})" for r in results]),
        ("min. salt thickness", [_minimum_text(r["salt"]["minimum"]) for r in results]),
        ("salt body: thickest / extent", [_body_text(r["salt"].get("body")) for r in results]),
        ("min. vs fault tip / footwall edge", [_relative_text(r["salt"]["minimum"]) for r in results]),
        ("welds (< 1 salt disc)", [_weld_text(r["salt"]["welds"]) for r in results]),
        ("salt-cover interface relief", [_interface_text(r["interface"]) for r in results]),
        ("interface offset by a cover fault",
         [", ".join(r["interface"]["offsetting_faults"]) or "no" for r in results]),
        ("cover faults", [_faults_text(r["faults"]) for r in results]),
        ("cover ux, left / middle / right third", [_thirds_text(r["cover_motion"]) for r in results]),
        ("left end wall", [_wall_text(r["end_walls"].get("left")) for r in results]),
        ("right end wall", [_wall_text(r["end_walls"].get("right")) for r in results]),
    ]
    for k, reg in enumerate(results[0]["salt_flow"]["regions"]):
        rows.append((f"salt flow, {reg['region']}",
                     [_flow_text(r["salt_flow"]["regions"][k]) for r in results]))
    if "keystone" in results[0]:
        rows.append(("deformed cover left / right of graben",
                     [(f"{_km(r['keystone']['left']['extent_m'])} / {_km(r['keystone']['right']['extent_m'])}"
                       if r["keystone"] else "–") for r in results]))
    if "tilted" in results[0]:
        rows.append(("block rotation (mean)", [("–" if r["tilted"]["mean_rotation_deg"] is None else
                                               f"{r['tilted']['mean_rotation_deg']:+.1f}°") for r in results]))
        rows.append(("fault spacing (mean)", [_km(r["tilted"]["mean_fault_spacing_m"]) for r in results]))
    return rows


def _table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> List[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return lines + ["| " + " | ".join(row) + " |" for row in rows]


def _fault_rows(faults: Sequence[dict]) -> List[List[str]]:
    rows = []
    for f in faults:
        surface = _km(f["x_surface_m"]) if f["reaches_surface"] else f"tip {_m(f['upper_tip_depth_m'])} deep"
        base = (_km(f["x_interface_m"]) if f["reaches_salt"]
                else f"tip {_m(f['lower_tip_above_salt_m'])} above salt")
        rows.append([f["id"], surface, base, f"{f['dip_deg']:.0f}°", f["dip_direction"], f["sense"] or "–",
                     _m(f["throw_m"]), "yes" if f["reaches_salt"] else "no",
                     "yes" if f["active"] else "no", _m(f["length_m"])])
    return rows


def outcomes_markdown(results: Sequence[dict], title: str = "Outcomes", notes: Sequence[str] = ()) -> str:
    """Markdown: one summary table (a column per frame) and a fault table per frame."""
    if not results:
        return f"## {title}\n\nno frames\n"
    lines = [f"## {title}", ""] + [f"{n}  " for n in notes] + ([""] if notes else [])
    header = ["outcome"] + [_stage_label(r) for r in results]
    lines += _table(header, [[name] + vals for name, vals in _summary_rows(results)])
    for r in results:
        lines += ["", f"### Cover faults at {_stage_label(r)} (frame {r['frame']})", ""]
        if not r["faults"]["list"]:
            lines.append("No localised band in the cover.")
            continue
        lines += _table(["fault", "x surface", "x interface", "dip", "dips", "sense", "throw", "reaches salt",
                         "active", "length"], _fault_rows(r["faults"]["list"]))
    return "\n".join(lines) + "\n"
