"""The gallery page: every run of a series side by side with what the paper says of its scene.

For each run directory (``examples/run-series.sh`` layout: ``figures/NAME.png``,
``outcomes/outcomes.{md,json}``, ``wall.txt``, ``cmd.txt`` or the series' own record) the page
shows its figure (downscaled into the docs), its wall time, a one-line headline from the
outcomes at the last frame, the paper's statements about the scene (``paper.py``) beside the
run's own (a person's reading of the figure and the table, from a notes file: ``## NAME``
sections of one ``- `` line per paper statement), and the full outcomes table.
"""

from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence

from .paper import STATEMENTS, scene_key


@dataclass
class GalleryRun:
    name: str
    path: str
    title: str = ""
    figure: Optional[str] = None
    outcomes_md: str = ""
    outcomes: Optional[dict] = None
    wall_s: Optional[float] = None
    command: str = ""

    @classmethod
    def load(cls, path: str, name: Optional[str] = None) -> "GalleryRun":
        name = name or os.path.basename(os.path.normpath(path))
        run = cls(name, path)
        figs = sorted(f for f in os.listdir(os.path.join(path, "figures"))
                      if f.endswith(".png")) if os.path.isdir(os.path.join(path, "figures")) else []
        if figs:
            run.figure = os.path.join(path, "figures", f"{name}.png" if f"{name}.png" in figs else figs[0])
        md = os.path.join(path, "outcomes", "outcomes.md")
        if os.path.isfile(md):
            run.outcomes_md = open(md).read()
        js = os.path.join(path, "outcomes", "outcomes.json")
        if os.path.isfile(js):
            run.outcomes = json.load(open(js))
        for wall in ("wall.txt",):
            p = os.path.join(path, wall)
            if os.path.isfile(p):
                m = re.search(r"([0-9.]+)", open(p).read().split("wall")[-1])
                run.wall_s = float(m.group(1)) if m else None
        p = os.path.join(path, "cmd.txt")
        if os.path.isfile(p):
            run.command = open(p).read().strip()
        return run

    def headline(self) -> str:
        """Salt minimum and welds, cover faults, cover thirds and end-wall gaps at the last frame."""
        if not self.outcomes or not self.outcomes.get("frames"):
            return "no outcomes"
        f = self.outcomes["frames"][-1]
        salt, faults, motion = f.get("salt", {}), f.get("faults", {}), f.get("cover_motion", {})
        parts = [f"at {f.get('displacement_m', float('nan')):.0f} m"]
        mn = salt.get("minimum", {})
        if mn.get("thickness_m") is not None:
            parts.append(f"salt min {mn['thickness_m']:.0f} m at x {mn['x_m'] / 1000:.2f} km")
        welds = salt.get("welds", {})
        if isinstance(welds, dict) and welds.get("count"):
            parts.append(f"{welds['count']} weld(s)")
        if faults:
            parts.append(f"{faults.get('count', 0)} cover fault(s)")
        if all(k in motion for k in ("left", "middle", "right")):
            parts.append("cover ux thirds " + " / ".join(f"{motion[k]['ux_m']:+.0f}" for k in ("left", "middle", "right")) + " m")
        walls = f.get("end_walls", {})
        gaps = [side for side in ("left", "right") if walls.get(side, {}).get("gap")]
        if gaps:
            parts.append("gap at the " + " and ".join(gaps) + " wall")
        return "; ".join(parts)


def read_notes(path: Optional[str]) -> Dict[str, List[str]]:
    """``## NAME`` sections of ``- `` lines: a person's reading of each run, one line per
    paper statement (in the order of paper.STATEMENTS), then any further remarks."""
    notes: Dict[str, List[str]] = {}
    if not path or not os.path.isfile(path):
        return notes
    name = None
    for line in open(path):
        line = line.rstrip("\n")
        if line.startswith("## "):
            name = line[3:].strip()
            notes[name] = []
        elif name and line.startswith("- "):
            notes[name].append(line[2:].strip())
        elif name and line.startswith("  ") and notes[name]:
            notes[name][-1] += " " + line.strip()
    return notes


def shrink_png(src: str, dst: str, width: int = 720, colours: int = 96) -> str:
    """A docs-sized copy of a figure (about a tenth of the size)."""
    from PIL import Image
    im = Image.open(src).convert("RGB")
    if im.width > width:
        im = im.resize((width, round(im.height * width / im.width)), Image.LANCZOS)
    im.quantize(colors=colours, method=Image.Quantize.MEDIANCUT).save(dst, optimize=True)
    return dst


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def gallery_markdown(runs: Sequence[GalleryRun], notes: Dict[str, List[str]], img_dir: str,
                     page_dir: str, intro: str = "") -> str:
    out = ["# Gallery", "", intro.strip(), "" if intro else "",
           "| run | scene (paper) | wall time | at the last frame |", "|---|---|---|---|"]
    for r in runs:
        key = scene_key(r.name)
        where = STATEMENTS.get(key, ("", []))[0]
        wall = f"{r.wall_s / 60:.0f} min" if r.wall_s else "-"
        out.append(f"| [{r.name}](#{r.name.lower()}) | {key} ({where}) | {wall} | {_cell(r.headline())} |")
    out.append("")
    for r in runs:
        key = scene_key(r.name)
        where, said = STATEMENTS.get(key, ("", []))
        out += [f"## {r.name}", ""]
        if r.command:
            out += [f"Run: `{r.command}`" + (f"; wall time {r.wall_s / 60:.1f} min." if r.wall_s else ""), ""]
        if r.figure:
            os.makedirs(img_dir, exist_ok=True)
            dst = shrink_png(r.figure, os.path.join(img_dir, f"{r.name}.png"))
            out += [f"![{r.name}]({os.path.relpath(dst, page_dir)})", ""]
        mine = notes.get(r.name, [])
        if said:
            out += [f"| the paper ({where}) | this run |", "|---|---|"]
            for k, s in enumerate(said):
                out.append(f"| {_cell(s)} | {_cell(mine[k]) if k < len(mine) else 'not assessed'} |")
            out.append("")
        for extra in mine[len(said):]:
            out += [f"- {extra}"]
        if mine[len(said):]:
            out.append("")
        if r.outcomes_md:
            body = r.outcomes_md.split("\n", 1)[1] if r.outcomes_md.startswith("## ") else r.outcomes_md
            # the table names the dumps by the path they were read from: name them by the run
            body = body.replace(os.path.abspath(r.path) + os.sep, r.name + "/")
            out += ["<details><summary>Outcomes table</summary>", "", body.replace("### ", "#### ").strip(),
                    "", "</details>", ""]
    return "\n".join(out).rstrip() + "\n"
