#!/usr/bin/env python3
"""The gallery pages: every run of a series side by side with what the paper says of its scene.

Docs-building code, kept out of the installed package (python/saltdem_post).  From the
repository root:

  /usr/bin/python3 tools/docs/gallery_page.py out/gallery_quick/* out/gallery_full/expt1_full \
      --notes docs/gallery/notes.md --intro docs/gallery/intro.md

For each run directory (``examples/run-series.sh`` layout: ``figures/NAME.png``,
``outcomes/outcomes.{md,json}``, ``wall.txt``, ``cmd.txt`` or the series' own record) the page
(``docs/gallery.md``) shows a summary table and one short section per run: its figure
(downscaled into the docs), its wall time, a one-line headline from the outcomes at the last
frame and how the run's reading compares with the paper's statements.  The companion page
(``docs/gallery/runs.md``) has, per run, the paper's statements about the scene
(``paper_statements.py``) beside the run's own (a person's reading of the figure and the table,
from a notes file: ``## NAME`` sections of one ``- `` line per paper statement) and the full
outcomes table.  ``--splice`` replaces only the given runs' rows and sections in both pages.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import sys
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence

from paper_statements import STATEMENTS, scene_key


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
    paper statement (in the order of paper_statements.STATEMENTS), then any further remarks."""
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


RUNS_PAGE = "gallery/runs.md"    # the companion page, relative to the gallery page
MARKS = (("\u2713", "agree"), ("~", "in part"), ("\u2717", "do not"))    # a note's leading mark


def leading_marks(said: Sequence[str], mine: Sequence[str]) -> List[Optional[str]]:
    """The verdict on each of the paper's statements: the leading mark (\u2713, ~ or \u2717) of
    the note line with the statement's index, None where that line is missing or has no mark
    (a remark); lines beyond the statements are remarks."""
    out: List[Optional[str]] = []
    for k in range(len(said)):
        line = mine[k] if k < len(mine) else ""
        out.append(next((mark for mark, _ in MARKS if line.startswith(mark)), None))
    return out


def verdict(said: Sequence[str], mine: Sequence[str]) -> str:
    """How the run's reading answers the paper's statements, counted by each note's leading
    mark (\u2713 agrees, ~ in part, \u2717 does not)."""
    if not said:
        return ""
    marks = leading_marks(said, mine)
    counts = [(marks.count(mark), word) for mark, word in MARKS]
    parts = [f"{n} {word}" for n, word in counts if n]
    missing = len(said) - min(len(mine), len(said))
    if missing:
        parts.append(f"{missing} not assessed")
    return f"Of the paper's {len(said)} statement(s): " + ", ".join(parts) + "."


def summary_row(r: "GalleryRun") -> str:
    key = scene_key(r.name)
    where = STATEMENTS.get(key, ("", []))[0]
    wall = f"{r.wall_s / 60:.0f} min" if r.wall_s else "-"
    return f"| [{r.name}](#{r.name.lower()}) | {key} ({where}) | {wall} | {_cell(r.headline())} |"


def gallery_markdown(runs: Sequence[GalleryRun], notes: Dict[str, List[str]], img_dir: str,
                     page_dir: str, intro: str = "", runs_page: str = RUNS_PAGE) -> str:
    """The gallery page: the summary table, then per run its command, figure, headline, how it
    answers the paper's statements (the side-by-side table is on ``runs_page``, relative to the
    page) and the notes' further remarks."""
    out = ["# Gallery", "", *([intro.strip(), ""] if intro.strip() else []),
           "| run | scene (paper) | wall time | at the last frame |", "|---|---|---|---|"]
    out += [summary_row(r) for r in runs]
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
        line = f"At the last frame: {r.headline()}."
        if said:
            line += f"  {verdict(said, mine)}"
        out += [line + f"  [The paper beside this run, and the outcomes]({runs_page}#{r.name.lower()}).", ""]
        for extra in mine[len(said):]:
            out += [f"- {extra}"]
        if mine[len(said):]:
            out.append("")
    return "\n".join(out).rstrip() + "\n"


def runs_markdown(runs: Sequence[GalleryRun], notes: Dict[str, List[str]], gallery: str = "../gallery.md") -> str:
    """The companion page: per run the paper's statements beside the run's reading, and the
    full outcomes table (``gallery``: the gallery page, relative to this one)."""
    out = ["# Gallery: each run beside the paper, and its outcomes", "",
           f"The long tables of the [gallery]({gallery}), generated with it "
           "(`tools/docs/gallery_page.py`): for each run the paper's statements about its scene "
           "beside our reading of the run (\u2713 agrees, \u2717 does not, ~ in part; from the "
           "figure and the outcomes table, numbers quoted from it), then the full "
           "`saltdem-post outcomes` table.", ""]
    for r in runs:
        key = scene_key(r.name)
        where, said = STATEMENTS.get(key, ("", []))
        out += [f"## {r.name}", "", f"Figure and summary: [gallery]({gallery}#{r.name.lower()}).", ""]
        mine = notes.get(r.name, [])
        if said:
            out += [f"| the paper ({where}) | this run |", "|---|---|"]
            for k, s in enumerate(said):
                out.append(f"| {_cell(s)} | {_cell(mine[k]) if k < len(mine) else 'not assessed'} |")
            out.append("")
        if r.outcomes_md:
            body = r.outcomes_md.split("\n", 1)[1] if r.outcomes_md.startswith("## ") else r.outcomes_md
            # the table names the dumps by the path they were read from: name them by the run
            body = body.replace(os.path.abspath(r.path) + os.sep, r.name + "/")
            out += ["<details><summary>Outcomes table</summary>", "", body.replace("### ", "#### ").strip(),
                    "", "</details>", ""]
    return "\n".join(out).rstrip() + "\n"


SECTION = r"^## {name}\n.*?(?=^#{{1,2}} |\Z)"


def splice(page: str, new: str, name: str, row: bool) -> str:
    """``page`` with the run's section (and its summary row, if ``row``) replaced by the one
    in ``new``; an error if the page has no such section or row."""
    parts = [re.compile(SECTION.format(name=re.escape(name)), re.M | re.S)]
    if row:
        parts.append(re.compile(rf"^\| \[{re.escape(name)}\]\(#{re.escape(name.lower())}\) \|.*$", re.M))
    for pat in parts:
        old, got = pat.search(page), pat.search(new)
        if not old or not got:
            raise SystemExit(f"gallery_page: no {name} {'row' if pat is not parts[0] else 'section'} to replace")
        was = old.group(0)    # the blank lines that closed the old section close the new one
        page = page[:old.start()] + got.group(0).rstrip("\n") + was[len(was.rstrip("\n")):] + page[old.end():]
    return page


def main(argv: Optional[Sequence[str]] = None) -> int:
    ap = argparse.ArgumentParser(description="docs/gallery.md and docs/gallery/runs.md from run directories "
                                             "(examples/run-series.sh): figure, wall time, outcomes, the "
                                             "paper's statements beside a person's notes")
    ap.add_argument("runs", nargs="+", help="run directories (NAME/ with figures/, outcomes/, wall.txt)")
    ap.add_argument("-o", "--out", default="docs/gallery.md", help="the page (default %(default)s)")
    ap.add_argument("--runs-page", help=f"the companion page (default: {RUNS_PAGE} beside the page)")
    ap.add_argument("--img", default=None, help="figure copies (default: img/gallery beside the page)")
    ap.add_argument("--notes", help="notes file: '## NAME' sections, one '- ' line per paper statement")
    ap.add_argument("--intro", help="a markdown file put at the top of the page")
    ap.add_argument("--append", help="a markdown file put at the end of the page")
    ap.add_argument("--splice", action="store_true",
                    help="replace only these runs' rows and sections in the existing pages")
    a = ap.parse_args(argv)
    runs = [GalleryRun.load(p) for p in a.runs]
    page_dir = os.path.dirname(os.path.abspath(a.out))
    runs_path = a.runs_page or os.path.join(page_dir, RUNS_PAGE)
    img = a.img or os.path.join(page_dir, "img", "gallery")
    notes = read_notes(a.notes)
    rel_runs = os.path.relpath(runs_path, page_dir)
    rel_page = os.path.relpath(os.path.abspath(a.out), os.path.dirname(os.path.abspath(runs_path)))
    intro = open(a.intro).read() if a.intro else ""
    text = gallery_markdown(runs, notes, img, page_dir, intro, rel_runs)
    companion = runs_markdown(runs, notes, rel_page)
    if a.splice:
        page, other = open(a.out).read(), open(runs_path).read()
        for r in runs:
            page = splice(page, text, r.name, row=True)
            other = splice(other, companion, r.name, row=False)
        text, companion = page, other
    elif a.append:
        text += "\n" + open(a.append).read().lstrip("\n")
    os.makedirs(os.path.dirname(os.path.abspath(runs_path)), exist_ok=True)
    with open(a.out, "w") as fh:
        fh.write(text)
    with open(runs_path, "w") as fh:
        fh.write(companion)
    print(f"gallery: {len(runs)} run(s) -> {a.out} and {runs_path} (figures in {img})"
          + (" (spliced)" if a.splice else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
