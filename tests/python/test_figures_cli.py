"""Figures and the command line, on the shipped fixture and optionally on a
real dump of the package (set SALTDEM_TEST_DUMP to its path or glob)."""

import csv
import json
import os
import subprocess
import sys

import numpy as np
import pytest
from matplotlib.colors import to_rgb
from matplotlib.image import imread

from saltdem_post.cli import main, pick_stages, previous_frame
from saltdem_post.dump import iter_frames, write_dump
from saltdem_post.figures import COVER_COLOURS, SALT_COLOURS, WALL_COLOUR
from saltdem_post.synthetic import scene_frames


def _colour_pixels(img, colour, tol=0.02):
    return int(np.all(np.abs(img[..., :3] - np.array(to_rgb(colour))) < tol, axis=-1).sum())


def check_png(path, min_ink=0.15):
    """PNG exists, is a sensible size and is not blank."""
    img = imread(path)
    h, w = img.shape[:2]
    assert 300 <= w <= 6000 and 200 <= h <= 8000
    ink = np.any(img[..., :3] < 0.97, axis=-1).mean()       # fraction of non-white pixels
    assert ink > min_ink, f"{path} looks blank ({ink:.1%} non-white)"
    colours = np.unique((img[..., :3] * 255).astype(np.uint8).reshape(-1, 3), axis=0)
    assert len(colours) > 30
    return img


def run(capsys, *argv):
    rc = main([str(a) for a in argv])
    out = capsys.readouterr()
    assert rc == 0, out.err
    return out.out


def test_fixture_is_current(fixture_path):
    """The shipped fixture matches its generator (rerun make_fixture.py if not)."""
    expected = scene_frames([0.0, 50.0, 100.0, 150.0])
    got = list(iter_frames(fixture_path))
    assert len(got) == 4 and got[0].natoms == expected[0].natoms > 300
    assert got[0].columns == ["id", "type", "x", "y", "vx", "vy", "radius", "i_marker"]
    for e, g in zip(expected, got):
        assert g.timestep == e.timestep
        for c in e.columns:
            np.testing.assert_allclose(g[c], e[c], rtol=1e-8, atol=1e-12)


def test_paper_figure_from_fixture(capsys, tmp_path, fixture_path):
    out = run(capsys, "figure", fixture_path, "--at", 50, 100, 150, "-o", tmp_path, "-q")
    assert "3 stage(s)" in out
    info = json.loads((tmp_path / "paper_figure.json").read_text())
    stages = info["stages"]
    assert [s["frame"] for s in stages] == [1, 2, 3]
    assert [s["previous_frame"] for s in stages] == [0, 1, 2]
    np.testing.assert_allclose([s["displacement_m"] for s in stages], [50, 100, 150], atol=1e-6)
    # incremental strain over 50 m: nothing near 0 m shear everywhere, but not huge either
    p99 = [s["strain"]["max_shear"]["p99"] for s in stages]
    assert all(0.05 < v < 1.0 for v in p99)
    img = check_png(tmp_path / "paper_figure.png")
    h, w = img.shape[:2]
    assert [w, h] == info["figure"]["pixels"]
    assert w == (2 * 6.0 + 1.0) * 150                       # two 6-inch panel columns at 150 dpi
    left, right = img[:, : w // 2], img[:, w // 2:]
    # marker colours on the geometry side only, strain colours on the other
    for c in (COVER_COLOURS[0], COVER_COLOURS[1], SALT_COLOURS[0], SALT_COLOURS[1], WALL_COLOUR):
        assert _colour_pixels(left, c) > 500, c
    assert _colour_pixels(right, COVER_COLOURS[1]) < 50
    assert _colour_pixels(right, WALL_COLOUR) > 500             # basement drawn grey beside strain


def test_figure_without_marker_column_per_frame_files(capsys, tmp_path, fixture_path):
    """Markers rebuilt from the first frame; one file per frame; cropped axes."""
    for f in iter_frames(fixture_path):
        del f.data["i_marker"]
        write_dump(tmp_path / f"dump.{f.timestep}.txt", [f])
    out = run(capsys, "figure", tmp_path / "dump.*.txt", "--at", 100, "--xlim", 0.5, 1.5,
              "--disp-per-step", 0.01, "-o", tmp_path / "out", "-q")
    assert "0.01 m per timestep" in out
    info = json.loads((tmp_path / "out" / "paper_figure.json").read_text())
    assert [(s["frame"], s["previous_frame"]) for s in info["stages"]] == [(2, 1)]
    img = check_png(tmp_path / "out" / "paper_figure.png")
    left = img[:, : img.shape[1] // 2]
    for c in (COVER_COLOURS[0], COVER_COLOURS[1], SALT_COLOURS[0], SALT_COLOURS[1]):
        assert _colour_pixels(left, c) > 500, c


def test_figure_picks_frames_by_displacement():
    disp = [0.0, 25.0, 50.0, 75.0, 100.0, 250.0, 300.0]
    stages = pick_stages(disp, [100, 250, 1000], 50.0)
    assert stages == [(100.0, 4, 2), (250.0, 5, 4), (1000.0, 6, 5)]
    assert previous_frame([0.0, 0.0, 0.0], 2, 50.0) == 1     # no motion: the frame before
    assert previous_frame([0.0, 10.0], 0, 50.0) is None
    with pytest.raises(ValueError):
        pick_stages([np.nan, np.nan], [100], 50.0)


def test_cli_commands_on_fixture(capsys, tmp_path, fixture_path):
    out = run(capsys, "info", fixture_path, "-o", tmp_path, "-q")
    info = json.loads((tmp_path / "info.json").read_text())
    assert info["n_frames"] == 4 and info["timesteps"] == [0, 5000, 10000, 15000]
    assert sum(info["material_counts_first_frame"].values()) == info["natoms"][0]
    assert "4 frame(s)" in out

    run(capsys, "fault", fixture_path, "-o", tmp_path, "-q")
    rows = list(csv.DictReader(open(tmp_path / "fault.csv")))
    np.testing.assert_allclose([float(r["slip"]) for r in rows], [0, 50, 100, 150], atol=1e-6)
    np.testing.assert_allclose(float(rows[-1]["throw"]), 150 * np.sin(np.radians(60)), atol=1e-6)

    out = run(capsys, "strain", fixture_path, "--incremental", "-o", tmp_path, "-q")
    summ = json.loads((tmp_path / "strain_summary.json").read_text())
    assert [(s["ref_timestep"], s["cur_timestep"]) for s in summ] == [(0, 5000), (5000, 10000), (10000, 15000)]
    table = np.genfromtxt(tmp_path / "strain_5000_10000.csv", delimiter=",", names=True)
    assert len(table) == info["natoms"][0]
    assert np.all(np.diff(table["id"]) > 0)
    check_png(tmp_path / "strain_max_shear_5000_10000.png")

    out = run(capsys, "thickness", fixture_path, "--frames", "all", "-o", tmp_path, "-q")
    summ = json.loads((tmp_path / "thickness_summary.json").read_text())
    assert len(summ) == 4 and all(s["welds"] == [] for s in summ)
    assert summ[0]["mean_thickness_m"] == pytest.approx(220.0, abs=5.0)
    assert (tmp_path / "thickness_evolution.csv").exists() and "minimum" in out
    check_png(tmp_path / "thickness.png", min_ink=0.03)

    out = run(capsys, "profile", fixture_path, "--x", 300, 1700, "-o", tmp_path, "-q")
    fits = json.loads((tmp_path / "profile_vx_fits.json").read_text())
    assert len(fits) == 2 and all(f["fit"]["r2"] > 0.99 for f in fits)
    assert "Couette" in out and (tmp_path / "profile_vx_x300_15000.csv").exists()
    check_png(tmp_path / "profile_vx_15000.png", min_ink=0.03)


def test_cli_reports_errors(capsys, tmp_path):
    assert main(["info", str(tmp_path / "missing.dump"), "-o", str(tmp_path)]) == 2
    assert "error" in capsys.readouterr().err


@pytest.mark.parametrize("how", ["script", "module"])
def test_entry_points(tmp_path, fixture_path, repo_root, how):
    if how == "script":
        cmd = [sys.executable, os.path.join(repo_root, "python", "saltdem-post")]
        env = dict(os.environ)
    else:
        cmd = [sys.executable, "-m", "saltdem_post"]
        env = dict(os.environ, PYTHONPATH=os.path.join(repo_root, "python"))
    res = subprocess.run(cmd + ["info", fixture_path, "-o", str(tmp_path)], capture_output=True,
                         text=True, env=env, cwd=tmp_path, timeout=120)
    assert res.returncode == 0, res.stderr
    assert "553 atoms" in res.stdout and (tmp_path / "info.json").exists()


@pytest.mark.skipif(not os.environ.get("SALTDEM_TEST_DUMP"),
                    reason="set SALTDEM_TEST_DUMP to a dump (or glob) written by the package's decks")
def test_real_dump(capsys, tmp_path):
    dump = os.environ["SALTDEM_TEST_DUMP"]
    run(capsys, "info", dump, "-o", tmp_path, "-q")
    info = json.loads((tmp_path / "info.json").read_text())
    assert info["n_frames"] >= 1 and {"id", "type", "radius"} <= set(info["columns"])
    frames = ["0", "-1"] if info["n_frames"] > 1 else ["0"]
    run(capsys, "figure", dump, "--frames", *frames, "-o", tmp_path, "-q")
    check_png(tmp_path / "paper_figure.png")
    run(capsys, "thickness", dump, "-o", tmp_path, "-q")
    summ = json.loads((tmp_path / "thickness_summary.json").read_text())
    assert summ[0]["mean_thickness_m"] is not None and summ[0]["mean_thickness_m"] > 0
