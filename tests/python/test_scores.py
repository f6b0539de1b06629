"""The scores of the paper's statements per salt (tools/docs/scores.py, not installed): the
committed docs/fidelity/scores.csv is well formed, the totals of scores.md are those of the
CSV, the committed files are what the gallery's notes give, and a changed verdict in the
notes changes the totals."""

import csv
import os
import re
import shutil
import subprocess
import sys

import pytest

from paper_statements import STATEMENTS
from scores import POINTS, SALTS, main, run_salt

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
FIDELITY = os.path.join(REPO, "docs", "fidelity")
NOTES = os.path.join(REPO, "docs", "gallery", "notes.md")


def read_csv(folder=FIDELITY):
    with open(os.path.join(folder, "scores.csv"), encoding="utf-8", newline="") as fh:
        return list(csv.reader(fh))


def csv_totals(rows):
    """Per salt (score, count) over all its verdicts and over the statements every salt with
    verdicts has scored."""
    salts = {r[3] for r in rows}
    by = {}
    for scene, _, text, salt, v in rows:
        by.setdefault((scene, text), {})[salt] = POINTS[v]
    common = [k for k, v in by.items() if set(v) == salts]
    out = {}
    for s in salts:
        mine = [v[s] for v in by.values() if s in v]
        same = [by[k][s] for k in common]
        out[s] = ((sum(mine), len(mine)), (sum(same), len(same)))
    return out


def md_totals(folder=FIDELITY):
    """The two totals rows of scores.md: {salt column: 'score / count'} each."""
    text = open(os.path.join(folder, "scores.md"), encoding="utf-8").read()
    got = {}
    for label in ("total", "same statements"):
        m = re.search(rf"^\| \*\*{label}\*\* \|.*$", text, re.M)
        assert m, f"no {label} row in scores.md"
        got[label] = [c.strip() for c in m.group(0).strip("|").split("|")][3:]
    return got


def parse(cell):
    m = re.fullmatch(r"([0-9.]+) / (\d+)", cell)
    return (float(m.group(1)), int(m.group(2))) if m else None


def test_committed_csv_is_well_formed():
    rows = read_csv()
    assert rows[0] == ["scene", "stage", "statement", "salt", "verdict"]
    body = rows[1:]
    assert len(body) > 20
    salts = {s for s, _, _ in SALTS}
    order = list(STATEMENTS)
    keys = []
    for scene, stage, text, salt, v in body:
        assert scene in STATEMENTS and text in STATEMENTS[scene][1], (scene, text)
        assert salt in salts and v in ("\u2713", "~", "\u2717")
        assert stage and (text.startswith(stage + ": ") or stage in STATEMENTS[scene][0])
        keys.append((order.index(scene), STATEMENTS[scene][1].index(text),
                     [s for s, _, _ in SALTS].index(salt)))
    assert keys == sorted(keys) and len(set(keys)) == len(keys)


def test_markdown_totals_are_those_of_the_csv():
    tot, md = csv_totals(read_csv()[1:]), md_totals()
    for label, which in (("total", 0), ("same statements", 1)):
        for (salt, _, heading), cell in zip(SALTS, md[label]):
            if salt in tot:
                score, n = tot[salt][which]
                assert parse(cell) == (pytest.approx(score), n), (label, heading, cell)
            else:
                assert cell == "no runs", (label, heading, cell)


def test_committed_files_pass_the_check():
    r = subprocess.run([sys.executable, os.path.join(REPO, "tools", "docs", "scores.py"), "--check"],
                       capture_output=True, text=True, cwd=REPO)
    assert r.returncode == 0, r.stdout + r.stderr


@pytest.mark.parametrize("name, got", [
    ("expt1", ("expt1", "stated")), ("expt1_contact", ("expt1", "contact")),
    ("expt3_slow_eta100x", ("expt3_slow", "5e10")), ("expt1_slow_fv", ("expt1_slow", "paper")),
    ("fig7_salt250_fv", ("fig7_salt250", "paper")), ("expt2_slow", ("expt2_slow", "stated")),
    ("expt1_seed2", None), ("expt1_full", None), ("e1_base", None), ("expt1_contact_seed2", None)])
def test_run_names_map_to_a_scene_and_salt(name, got):
    assert run_salt(name) == got


def test_a_changed_verdict_changes_the_totals(tmp_path, capsys):
    out = tmp_path / "out"
    # the notes without the frictional-viscous runs, whose column then has none
    text = re.sub(r"(?ms)^## \w+_fv\n.*?(?=^## |\Z)", "", open(NOTES, encoding="utf-8").read())
    base = tmp_path / "base.md"
    base.write_text(text, encoding="utf-8")
    assert main(["--notes", str(base), "--out", str(out)]) == 0
    before = md_totals(str(out))
    # the contact salt's reading of Expt 1 at 100 m: its leading mark turned to another
    section = text.index("## expt1_contact\n")
    first = text.index("\n- ", section) + 3
    was = text[first]
    now = "\u2717" if was != "\u2717" else "\u2713"
    notes = tmp_path / "notes.md"
    notes.write_text(text[:first] + now + text[first + 1:], encoding="utf-8")
    assert main(["--notes", str(notes), "--out", str(out), "--check"]) == 1
    assert "differs" in capsys.readouterr().out
    # a new salt's run appears in its column, with no change to the tool
    with open(notes, "a", encoding="utf-8") as fh:
        fh.write("\n## expt1_fv\n- \u2713 one\n- ~ two\n- \u2717 three\n- a remark, not a verdict\n")
    assert main(["--notes", str(notes), "--out", str(out)]) == 0
    after = md_totals(str(out))
    col = [s for s, _, _ in SALTS].index("contact")
    b, a = parse(before["total"][col]), parse(after["total"][col])
    assert a == (b[0] + POINTS[now] - POINTS[was], b[1]) and a != b
    assert parse(after["total"][-1]) == (1.5, 3)
    assert before["total"][-1] == "no runs"
    assert all(r[3] != "paper" or r[0] == "expt1" for r in read_csv(str(out))[1:])
    assert csv_totals(read_csv(str(out))[1:])["paper"][0] == (1.5, 3)


def test_general_statements_appear_only_with_verdicts(tmp_path):
    md = open(os.path.join(FIDELITY, "scores.md"), encoding="utf-8").read()
    has_general = any(r[0] == "general" for r in read_csv()[1:])
    assert ("| general (" in md) == has_general
    notes = tmp_path / "notes.md"
    shutil.copy(NOTES, notes)
    with open(notes, "a", encoding="utf-8") as fh:
        fh.write("\n## general_contact\n- \u2713 a\n- ~ b\n- \u2717 c\n")
    main(["--notes", str(notes), "--out", str(tmp_path)])
    assert "| general (§3) |" in open(tmp_path / "scores.md", encoding="utf-8").read()
