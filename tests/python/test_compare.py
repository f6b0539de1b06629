"""saltdem-post compare: the paper's statements per stage beside each run's outcomes, generated
from outcomes.json alone (synthetic outcomes here); a changed outcome changes the table, and
--check then fails."""
import copy
import json

from saltdem_post.cli import main
from saltdem_post.compare import comparison_markdown, comparison_rows, stage_statements


def frame(m, left, gap=0.0, faults=2, tmin=600.0):
    return {"displacement_m": m,
            "cover_motion": {"left": {"ux_m": left}, "middle": {"ux_m": 2 * left}, "right": {"ux_m": 3 * left}},
            "end_walls": {"left": {"gap": gap > 0, "collapse": False, "edge_distance_m": gap},
                          "right": {"gap": False, "collapse": False, "edge_distance_m": 5.0}},
            "faults": {"count": faults, "synthetic": faults - 1, "antithetic": 1},
            "salt": {"minimum": {"thickness_m": tmin, "x_m": 3100.0, "welded": False}},
            "salt_flow": {"regions": [{"region": "footwall", "character": "Couette"}]}}


def outcomes(gap=0.0):
    return {"frames": [frame(m, m / 10, gap=gap if m == 1000 else 0.0) for m in (100, 250, 500, 750, 1000)]}


def test_rows_follow_the_statements_and_outcomes():
    st = stage_statements("expt1")
    assert [s[1] for s in st] == [100, 250, 500, 750, 1000]
    rows = comparison_rows("expt1", {"stated": outcomes(gap=700.0), "paper": outcomes()})
    assert len(rows) == 5 and rows[-1]["paper"].startswith("a wide zone of cover deformation")
    assert "700 m gap at the left wall" in rows[-1]["runs"]["stated"]
    assert "held at both end walls" in rows[-1]["runs"]["paper"]
    assert "cover moved +100 / +200 / +300 m" in rows[-1]["runs"]["paper"]
    assert "salt thinnest 600 m at 3.10 km" in rows[-1]["runs"]["paper"]
    # Expt 2's last statement covers 750-1000 m: read at 1000 m
    rows2 = comparison_rows("expt2", {"a": outcomes()})
    assert rows2[-1]["stage"] == "750-1000 m" and "+100 /" in rows2[-1]["runs"]["a"]


def test_a_changed_outcome_fails_the_check(tmp_path):
    a, b = outcomes(), outcomes()
    pa, pb = tmp_path / "a.json", tmp_path / "b.json"
    pa.write_text(json.dumps(a))
    pb.write_text(json.dumps(b))
    assert main(["compare", str(pa), str(pb), "--labels", "stated", "paper", "-o", str(tmp_path)]) == 0
    md = tmp_path / "comparison.md"
    assert md.read_text() == comparison_markdown("expt1", {"stated": a, "paper": b})
    assert main(["compare", str(pa), str(pb), "--labels", "stated", "paper", "--check", str(md)]) == 0
    c = copy.deepcopy(b)
    c["frames"][2]["faults"]["count"] = 7
    pb.write_text(json.dumps(c))
    assert main(["compare", str(pa), str(pb), "--labels", "stated", "paper", "--check", str(md)]) == 2
    assert main(["compare", str(pa), "--labels", "x", "y"]) == 2    # labels must match
