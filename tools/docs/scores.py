#!/usr/bin/env python3
"""The paper's statements about its Figs. 3-7, scored for each salt from the gallery's readings.

Docs-building code, kept out of the installed package (python/saltdem_post).  From the
repository root:

  /usr/bin/python3 tools/docs/scores.py            # writes docs/fidelity/scores.{md,csv}
  /usr/bin/python3 tools/docs/scores.py --check    # exit 1 if the committed files differ

The verdicts are the leading marks of the gallery's notes (docs/gallery/notes.md, read with
gallery_page.py's parser): in a run's ``## NAME`` section the k-th ``- `` line answers the
scene's k-th statement (paper_statements.STATEMENTS).  One run per scene and salt is scored:
the scene's own name for the stated salt, with ``_contact``, ``_eta100x`` or ``_fv`` for the
others; seed variants, the full-preset run and the study's runs are left out.
"""

from __future__ import annotations

import argparse
import csv
import io
import os
import re
import sys
from typing import Dict, List, Optional, Sequence, Tuple

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
if HERE not in sys.path:    # (paper_statements finds the package itself)
    sys.path.insert(0, HERE)

from gallery_page import _cell, leading_marks, read_notes  # noqa: E402
from paper_statements import STATEMENTS, scene_key  # noqa: E402

# (salt as the CSV names it, run-name suffix, column heading)
SALTS = (("stated", "", "stated"), ("contact", "_contact", "contact"), ("5e10", "_eta100x", "5e10"),
         ("paper", "_fv", "frictional-viscous"))
POINTS = {"\u2713": 1.0, "~": 0.5, "\u2717": 0.0}
COLUMNS = ("scene", "stage", "statement", "salt", "verdict")
NOTES = os.path.join(ROOT, "docs", "gallery", "notes.md")
OUT = os.path.join(ROOT, "docs", "fidelity")
STAGE = re.compile(r"^(\d+(?:-\d+)? m): ")


def run_salt(name: str) -> Optional[Tuple[str, str]]:
    """(scene key, salt) of a run that is scored, None for any other run (seed variants,
    ``_full``, the study's ``e1_...``)."""
    base, salt = name, "stated"
    for s, suffix, _ in SALTS:
        if suffix and name.endswith(suffix):
            base, salt = name[:-len(suffix)], s
            break
    return (base, salt) if base in STATEMENTS and scene_key(name) == base else None


def stage(where: str, text: str) -> str:
    """The statement's stage: its displacement prefix ('100 m', '750-1000 m'), else the figure."""
    m = STAGE.match(text)
    if m:
        return m.group(1)
    fig = re.search(r"Fig\. \d+[a-z]?", where)
    return fig.group(0) if fig else where


def score_rows(notes: Dict[str, List[str]]) -> List[dict]:
    """One row per statement and salt with a verdict, in the order of STATEMENTS."""
    verdicts: Dict[Tuple[str, str], List[Optional[str]]] = {}
    for name in sorted(notes):
        got = run_salt(name)
        if got:
            verdicts[got] = leading_marks(STATEMENTS[got[0]][1], notes[name])
    rows = []
    for key, (where, said) in STATEMENTS.items():
        for k, text in enumerate(said):
            for salt, _, _ in SALTS:
                mark = verdicts.get((key, salt), [None] * len(said))[k]
                if mark:
                    rows.append({"scene": key, "stage": stage(where, text), "statement": text,
                                 "salt": salt, "verdict": mark})
    return rows


def scores_csv(rows: Sequence[dict]) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=COLUMNS, lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    return buf.getvalue()


def fmt(x: float) -> str:
    return f"{x:g}"


def totals(rows: Sequence[dict]) -> Dict[str, Tuple[float, int, float, int, List[Tuple[str, int]]]]:
    """Per salt: (score, statements scored, score and count on the common statements, the
    common statements as (scene, index)).  The common statements are those every salt with a
    verdict anywhere has a verdict for."""
    cells = {(r["scene"], STATEMENTS[r["scene"]][1].index(r["statement"]), r["salt"]): r["verdict"]
             for r in rows}
    salts = [s for s, _, _ in SALTS if any(c[2] == s for c in cells)]
    common = [(key, k) for key, (_, said) in STATEMENTS.items() for k in range(len(said))
              if salts and all((key, k, s) in cells for s in salts)]
    out = {}
    for s, _, _ in SALTS:
        mine = [v for (key, k, salt), v in cells.items() if salt == s]
        same = [cells[(key, k, s)] for key, k in common if (key, k, s) in cells]
        out[s] = (sum(POINTS[v] for v in mine), len(mine), sum(POINTS[v] for v in same), len(same),
                  common)
    return out


def scene_list(common: Sequence[Tuple[str, int]]) -> str:
    """The common statements in words: whole scenes by name, else 'scene (n of m)'."""
    parts = []
    for key, (where, said) in STATEMENTS.items():
        n = sum(1 for c in common if c[0] == key)
        if n:
            parts.append(f"{key} ({where})" if n == len(said) else f"{key} ({where}; {n} of {len(said)})")
    return ", ".join(parts[:-1]) + (" and " if len(parts) > 1 else "") + parts[-1] if parts else "none"


def scores_markdown(rows: Sequence[dict]) -> str:
    tot = totals(rows)
    cells = {(r["scene"], r["statement"], r["salt"]): r["verdict"] for r in rows}
    scored = [s for s, _, _ in SALTS if tot[s][1]]
    general = any(r["scene"] == "general" for r in rows)
    common = next(iter(tot.values()))[4]
    out = ["# The paper's statements, scored", "",
           "Every statement the reference paper makes about its Figs. 3-7 (§2.3-2.5 and §3), at the "
           "stage of extension it names, scored for each salt from our reading of that salt's run "
           "of the scene (its figure and outcomes table): \u2713 agrees, 1 point; ~ in part, 0.5; "
           "\u2717 does not, 0; a blank cell where the salt has no run of that scene.  The salts: "
           "**stated**, the paper's stated Newtonian 5e8 Pa s; **contact**, discs with contact "
           "dashpots, the paper's own kind of salt; **5e10**, Newtonian 5e10 Pa s; "
           "**frictional-viscous**, the fluid salt with a frictional strength "
           "(`-var saltmodel paper`).  The Fig. 6 rows read a run at the five times slower "
           "drive against the same salt at the standard rate.  The reading behind each cell, "
           "with the numbers it quotes, is on [the gallery's run pages](../gallery/runs.md) "
           "(the run is named after the scene, with `_contact`, `_eta100x` or `_fv` added for "
           "the contact, 5e10 and frictional-viscous salts).",
           ""]
    if not general:
        out += ["The paper's general statements of §3 (no discrete faulting in the salt, a "
                "salt-cover interface never offset, Couette and Poiseuille flow) are not scored: "
                "the readings give no verdicts on them.", ""]
    out += ["| scene | stage | the paper | " + " | ".join(h for _, _, h in SALTS) + " |",
            "|---|---|---|" + "---|" * len(SALTS)]
    for key, (where, said) in STATEMENTS.items():
        if key == "general" and not general:
            continue
        for text in said:
            st = stage(where, text)
            shown = text[len(st) + 2:] if STAGE.match(text) else text
            out.append(f"| {key} ({where}) | {st} | {_cell(shown)} | "
                       + " | ".join(cells.get((key, text, s), "") for s, _, _ in SALTS) + " |")

    def total_cells(score: int, count: int) -> str:
        return " | ".join(f"{fmt(tot[s][score])} / {tot[s][count]}" if tot[s][count] else "no runs"
                          for s, _, _ in SALTS)

    out.append(f"| **total** | | score / statements scored | {total_cells(0, 1)} |")
    if len(scored) > 1:
        out.append(f"| **same statements** | | the {len(common)} statements every salt with runs "
                   f"has scored | {total_cells(2, 3)} |")
    out.append("")
    if len(scored) > 1:
        heading = {s: h for s, _, h in SALTS}
        names = ", ".join(heading[s] for s in scored[:-1]) + " and " + heading[scored[-1]]
        out += [f"The salts compare on the same statements in the last row: the {len(common)} that "
                f"{names} all have a verdict for, those of {scene_list(common)}."
                + (" A salt without runs is left out of it until its runs are read."
                   if len(scored) < len(SALTS) else ""), ""]
    return "\n".join(out).rstrip() + "\n"


def main(argv: Optional[Sequence[str]] = None) -> int:
    ap = argparse.ArgumentParser(description="docs/fidelity/scores.{md,csv}: the paper's statements "
                                             "about Figs. 3-7 scored per salt from the gallery's notes")
    ap.add_argument("--notes", default=NOTES, help="the gallery's notes (default %(default)s)")
    ap.add_argument("--out", default=OUT, help="folder of scores.md and scores.csv (default %(default)s)")
    ap.add_argument("--check", action="store_true",
                    help="write nothing; exit 1 if the files there differ from what the notes give")
    a = ap.parse_args(argv)
    if not os.path.isfile(a.notes):
        raise SystemExit(f"scores: no notes file {a.notes}")
    rows = score_rows(read_notes(a.notes))
    files = {"scores.csv": scores_csv(rows), "scores.md": scores_markdown(rows)}
    if a.check:
        bad = 0
        for name, text in files.items():
            path = os.path.join(a.out, name)
            old = open(path, encoding="utf-8").read() if os.path.isfile(path) else None
            if old != text:
                bad += 1
                if old is None:
                    print(f"scores: {path} is missing")
                    continue
                new_lines, old_lines = text.splitlines(), old.splitlines()
                k = next((i for i, (x, y) in enumerate(zip(new_lines, old_lines)) if x != y),
                         min(len(new_lines), len(old_lines)))
                print(f"scores: {path} differs from the notes at line {k + 1}:\n"
                      f"  committed: {old_lines[k] if k < len(old_lines) else '(end of file)'}\n"
                      f"  generated: {new_lines[k] if k < len(new_lines) else '(end of file)'}")
        if bad:
            print("scores: regenerate with /usr/bin/python3 tools/docs/scores.py")
        return 1 if bad else 0
    os.makedirs(a.out, exist_ok=True)
    for name, text in files.items():
        with open(os.path.join(a.out, name), "w", encoding="utf-8", newline="") as fh:
            fh.write(text)
    print(f"scores: {len(rows)} verdict(s) -> {os.path.join(a.out, 'scores.md')} and scores.csv")
    return 0


if __name__ == "__main__":
    sys.exit(main())
