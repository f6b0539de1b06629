"""The gallery's builder (tools/docs/gallery_page.py, not installed): run names map to the paper's
scenes, a person's notes sit beside the paper's statements, a run directory of
examples/run-series.sh becomes a section of the page and of its companion page, and a run's
sections can be spliced into pages that exist."""

import json

import numpy as np
import pytest

from gallery_page import GalleryRun, gallery_markdown, main, read_notes, runs_markdown
from paper_statements import STATEMENTS, scene_key


@pytest.mark.parametrize("name, key", [
    ("expt1", "expt1"), ("expt1_contact", "expt1"), ("expt1_seed3", "expt1"),
    ("expt1_slow", "expt1_slow"), ("expt1_slow_contact", "expt1_slow"),
    ("expt2_contact", "expt2"), ("expt2_slow_contact", "expt2_slow"),
    ("expt3_slow_contact", "expt3_slow"), ("fig7_salt250_contact", "fig7_salt250"),
    ("fig7_salt1000", "fig7_salt1000"), ("e1_base", "expt1"), ("endwall_smooth", "general"),
    ("expt10", "general"), ("fig7", "general")])
def test_scene_key(name, key):
    assert scene_key(name) == key


def make_run(tmp_path, name, ux=(+10.0, +20.0, +30.0)):
    """A run directory as examples/run-series.sh leaves it, with a tiny figure."""
    from PIL import Image
    d = tmp_path / name
    (d / "figures").mkdir(parents=True)
    (d / "outcomes").mkdir()
    Image.fromarray(np.full((40, 1200, 3), 200, np.uint8)).save(d / "figures" / f"{name}.png")
    frame = {"displacement_m": 1000.0, "salt": {"minimum": {"thickness_m": 412.0, "x_m": 3300.0},
                                                "welds": {"count": 1}},
             "faults": {"count": 3},
             "cover_motion": {k: {"ux_m": v} for k, v in zip(("left", "middle", "right"), ux)},
             "end_walls": {"left": {"gap": True}, "right": {"gap": False}}}
    (d / "outcomes" / "outcomes.json").write_text(json.dumps({"frames": [frame]}))
    (d / "outcomes" / "outcomes.md").write_text(f"## outcomes\n\nDumps: `{d.resolve()}/dump.expt1.*.txt`\n\n"
                                                "### 1000 m\n\n| a | b |\n|---|---|\n| 1 | 2 |\n")
    (d / "wall.txt").write_text("754\n")
    (d / "cmd.txt").write_text(f"ONLY={name} examples/run-series.sh gallery quick\n")
    return d


def test_run_directory_becomes_a_section(tmp_path):
    d = make_run(tmp_path, "expt1_contact")
    run = GalleryRun.load(str(d))
    assert run.wall_s == 754.0 and run.command.startswith("ONLY=expt1_contact")
    head = run.headline()
    for part in ("at 1000 m", "salt min 412 m at x 3.30 km", "1 weld(s)", "3 cover fault(s)",
                 "+10 / +20 / +30 m", "gap at the left wall"):
        assert part in head

    notes = tmp_path / "notes.md"
    said = STATEMENTS["expt1"][1]
    notes.write_text("## expt1_contact\n- first | reading\n- second\n  continued\n"
                     + "".join(f"- s{k}\n" for k in range(2, len(said))) + "- a remark beyond the paper\n")
    mine = read_notes(str(notes))["expt1_contact"]
    assert mine[1] == "second continued" and len(mine) == len(said) + 1

    page = tmp_path / "docs"
    text = gallery_markdown([run], read_notes(str(notes)), str(page / "img"), str(page))
    long = runs_markdown([run], read_notes(str(notes)))
    assert "| [expt1_contact](#expt1_contact) | expt1 (§2.3, Fig. 3) | 13 min |" in text
    assert "first \\| reading" in long                       # a '|' in a note does not split the row
    assert f"| {said[0]} | first \\| reading |" in long
    assert "- a remark beyond the paper" in text
    assert f"Of the paper's {len(said)} statement(s): " in text     # counted by leading marks: none here
    assert "(gallery/runs.md#expt1_contact)" in text and "(../gallery.md#expt1_contact)" in long
    assert "#### 1000 m" in long and "![expt1_contact](img/expt1_contact.png)" in text
    assert "Dumps: `expt1_contact/dump.expt1.*.txt`" in long
    assert str(tmp_path) not in text and str(tmp_path) not in long
    assert (page / "img" / "expt1_contact.png").stat().st_size > 0


def test_unassessed_statements_say_so_and_cli_writes_the_page(tmp_path):
    runs = [make_run(tmp_path, "fig7_salt250"), make_run(tmp_path, "expt3_slow_contact")]
    out = tmp_path / "gallery.md"
    main([*map(str, runs), "-o", str(out)])
    text, long = out.read_text(), (tmp_path / "gallery" / "runs.md").read_text()
    assert long.count("not assessed") == len(STATEMENTS["fig7_salt250"][1]) + len(STATEMENTS["expt3_slow"][1])
    assert f"{len(STATEMENTS['fig7_salt250'][1])} not assessed." in text
    assert "fig7_salt250 (§3, Fig. 7c)" in text and "expt3_slow (§3, Fig. 6c)" in text


def test_leading_marks_are_counted_and_a_run_is_spliced(tmp_path):
    """A run's row and sections replace the old ones in both pages; the other runs and what the
    page has beyond the gallery stay as they were."""
    runs = [make_run(tmp_path, "expt1"), make_run(tmp_path, "fig7_salt250")]
    notes = tmp_path / "notes.md"
    notes.write_text("## fig7_salt250\n- \u2713 localised\n- \u2717 no weld\n")
    beyond = tmp_path / "beyond.md"
    beyond.write_text("\n# Beyond the paper\n\n## wedge\n\nby hand\n")
    out = tmp_path / "gallery.md"
    main([*map(str, runs), "-o", str(out), "--notes", str(notes), "--append", str(beyond)])
    text = out.read_text()
    assert "Of the paper's 2 statement(s): 1 agree, 1 do not." in text
    assert text.rstrip().endswith("## wedge\n\nby hand") and "\n\n\n" not in text

    (runs[1] / "wall.txt").write_text("1800\n")
    notes.write_text("## fig7_salt250\n- ~ localised in part\n- \u2713 a weld\n- spliced remark\n")
    main([str(runs[1]), "-o", str(out), "--notes", str(notes), "--splice"])
    new, long = out.read_text(), (tmp_path / "gallery" / "runs.md").read_text()
    assert "| [fig7_salt250](#fig7_salt250) | fig7_salt250 (§3, Fig. 7c) | 30 min |" in new
    assert "Of the paper's 2 statement(s): 1 agree, 1 in part." in new and "- spliced remark" in new
    assert "| ~ localised in part |" in long and "no weld" not in long
    assert new.count("## fig7_salt250") == 1 and long.count("## fig7_salt250") == 1
    keep = text.split("## expt1\n", 1)[1].split("## fig7_salt250")[0]
    assert keep in new and "## expt1\n" in long                   # the other run is untouched
    assert new.rstrip().endswith("## wedge\n\nby hand")
    with pytest.raises(SystemExit, match="no expt2 section"):
        main([str(make_run(tmp_path, "expt2")), "-o", str(out), "--splice"])
