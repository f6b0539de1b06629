"""Experiment 1 deck, tiny: the scene assembles, faults, dumps markers; post-processing renders it."""
import os
import subprocess

import numpy as np
import pytest

from lmprun import ROOT, lmp_path, run_cmd

TINY = dict(preset="quick", width=1250, salt=250, cover=500, target=10, f="5 10",
            nsettle=300, rate=1, root=str(ROOT))


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    wd = tmp_path_factory.mktemp("expt1")
    cmd = [lmp_path(), "-in", str(ROOT / "examples" / "expt1.in"), "-log", "log.lammps",
           "-echo", "none"]
    for k, v in TINY.items():
        cmd += ["-var", k, *str(v).split()]
    proc = run_cmd(cmd, cwd=wd, capture_output=True, text=True, timeout=900,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))
    return wd, proc


def read_dump(path):
    lines = path.read_text().splitlines()
    head = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))    # (after TIME)
    cols = lines[head].split()[2:]
    data = np.array([[float(v) for v in l.split()] for l in lines[head + 1:]])
    return {c: data[:, k] for k, c in enumerate(cols)}


def test_scene_runs_to_target(tiny_run):
    wd, proc = tiny_run
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    assert "expt1: done, displacement 10.0 m" in proc.stdout
    dumps = sorted(wd.glob("dump.expt1.*.txt"), key=lambda p: int(p.name.split(".")[2]))
    assert len(dumps) == 3    # 0, 5 and 10 m


def test_layers_and_fault_motion(tiny_run):
    wd, proc = tiny_run
    dumps = sorted(wd.glob("dump.expt1.*.txt"), key=lambda p: int(p.name.split(".")[2]))
    first, last = read_dump(dumps[0]), read_dump(dumps[-1])
    salt, cover = first["type"] == 2, first["type"] == 1
    assert salt.sum() > 20 and cover.sum() > 60
    # salt below cover, markers carried: salt bands from x, cover layers from height
    assert first["y"][salt].max() < first["y"][cover].mean()
    assert set(np.unique(first["i_marker"][salt])) >= {0, 1}
    # the hanging-wall basement moved down-dip by the target (30 degrees)
    ids0 = dict(zip(first["id"], zip(first["x"], first["y"])))
    moved = []
    for i, t, x, y in zip(last["id"], last["type"], last["x"], last["y"]):
        if t == 3 and x > 700 and y > -60:
            x0, y0 = ids0[i]
            moved.append((x - x0, y - y0))
    d = np.array(moved)
    assert len(d) > 5
    np.testing.assert_allclose(np.median(np.hypot(d[:, 0], d[:, 1])), 10.0, rtol=1e-4)    # dumps carry 6 digits
    np.testing.assert_allclose(np.median(np.degrees(np.arctan2(-d[:, 1], d[:, 0]))), 30.0, rtol=1e-4)


def test_figure_from_real_dumps(tiny_run):
    wd, proc = tiny_run
    out = wd / "fig"
    r = subprocess.run(["/usr/bin/python3", str(ROOT / "python" / "saltdem-post"), "figure",
                        str(wd / "dump.expt1.*.txt"), "--fault-x", "625", "--at", "5", "10",
                        "--increment", "5", "-o", str(out), "--name", "tiny.png", "-q"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    png = out / "tiny.png"
    assert png.stat().st_size > 20000
    import matplotlib.image as mpimg
    img = mpimg.imread(str(png))
    assert img[..., :3].std() > 0.05    # not blank
