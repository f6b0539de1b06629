"""examples/wedge.in, loading by a prograding wedge (issue 18 item 3), at the tiny preset: the
deck runs, deposits behind the migrating front to the base level with a foreset ahead of it,
writes the epochs to its frames and resumes from its restart file."""
import math
import os
import re

import numpy as np
import pytest

from lmprun import ROOT, lmp_path, run_cmd

EPOCH = r"fix saltdem/sediment sed: epoch (\d+) at step (\d+): deposited (\d+) discs \(([-+.\deE]+) m\^2\) " \
        r"below base level ([-+.\deE]+) m in x ([-+.\deE]+) to ([-+.\deE]+) m"


def run_deck(wd, **var):
    cmd = [lmp_path(), "-in", str(ROOT / "examples" / "wedge.in"), "-log", "log.lammps", "-echo", "none",
           "-var", "root", str(ROOT)]
    for k, v in var.items():
        cmd += ["-var", k, *str(v).split()]
    return run_cmd(cmd, cwd=wd, capture_output=True, text=True, timeout=900,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))


def read_dump(path):
    lines = path.read_text().splitlines()
    head = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[head].split()[2:]
    data = np.array([[float(v) for v in l.split()] for l in lines[head + 1:]])
    d = {c: data[:, k] for k, c in enumerate(cols)}
    order = np.argsort(d["id"])
    return {c: v[order] for c, v in d.items()}


def frames(wd):
    files = sorted(wd.glob("dump.wedge.*.txt"), key=lambda p: int(p.name.split(".")[2]))
    return files, [read_dump(f) for f in files]


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    wd = tmp_path_factory.mktemp("wedge")
    proc = run_deck(wd, preset="tiny")
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    return wd, proc


def test_wedge_deck_deposits_behind_the_front(tiny):
    wd, proc = tiny
    assert "wedge: done, displacement 2.0 m" in proc.stdout
    ep = [tuple(map(float, m)) for m in re.findall(EPOCH, proc.stdout)]
    assert len(ep) >= 10
    # the window runs from the box's left end to the front, which starts at 3000 m and moves
    # 2 m/s x time (0.005 s steps): its end at each interval is the front at that step
    for e, step, n, area, base, xlo, xhi in ep:
        assert base == 1700.0 and xlo == -750.0
        assert xhi == pytest.approx(3000.0 + 2.0 * 0.005 * step, abs=1e-3)
    assert ep[0][2] > 5                       # the first interval fills the topset
    files, fr = frames(wd)
    assert len(fr) == 3                       # at 0, 1 and 2 m of front migration
    first, last = fr[0], fr[-1]
    assert np.all(first["i_marker"] < 1000)
    new = last["i_marker"] >= 1000
    assert new.sum() == sum(int(e[2]) for e in ep)
    assert np.all(last["type"][new] == 1)
    x, y, r = last["x"][new], last["y"][new], last["radius"][new]
    # behind the front: the topset below the base level (the frames come after some settling)
    behind = x + r <= 3000.0 + 2.0
    assert behind.sum() > 5
    assert np.all(y[behind] <= 1700.0 + 1.0)
    # ahead of it: a foreset, below the level falling tan(5 deg) per m from the front
    slope = math.tan(math.radians(5))
    assert np.any(x > 3100.0)
    assert np.all(y <= 1700.0 - slope * np.maximum(0.0, x - 3002.0) + 1.0)
    # nothing left of the left wall or above the base level anywhere
    assert np.all(x - r >= -100.0 - 1e-6) and y.max() <= 1701.0


def test_wedge_deck_thermo_shows_the_front(tiny):
    _, proc = tiny
    assert "v_front" in proc.stdout and "f_sed[1]" in proc.stdout
    assert "scene: sediment fill every" in proc.stdout and "window -750 to v_front" in proc.stdout


def test_wedge_deck_resumes(tiny, tmp_path):
    wd, _ = tiny
    res = sorted(wd.glob("wedge.restart.[ab]"), key=lambda p: p.stat().st_mtime)
    for f in list(wd.glob("pack_*.data")) + res:
        (tmp_path / f.name).write_bytes(f.read_bytes())
    proc = run_deck(tmp_path, preset="tiny", restart=res[0].name)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    assert "resumed from" in proc.stdout and "wedge: done, displacement 2.0 m" in proc.stdout
    # the resumed run's front continues from the file's model time (no settling, no reset)
    ep = re.findall(EPOCH, proc.stdout)
    assert ep and all(float(m[6]) == pytest.approx(3000.0 + 0.01 * int(m[1]), abs=1e-3) for m in ep)


def test_series_runner_wedge(tmp_path):
    """examples/run-series.sh wedge tiny: the run, its figure (growth strata) and outcomes."""
    import shutil
    series = ROOT / "out" / "wedge_tiny"
    shutil.rmtree(series, ignore_errors=True)
    r = run_cmd(["bash", str(ROOT / "examples" / "run-series.sh"), "wedge", "tiny"],
                       capture_output=True, text=True, timeout=900,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
    run = series / "wedge"
    assert (run / "figures" / "wedge.png").stat().st_size > 10000
    assert (run / "outcomes" / "outcomes.md").exists() and (run / "done").exists()
    assert "-var rate 0.317" in (run / "cmd.txt").read_text()
