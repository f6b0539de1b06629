"""The README's main job (quick Expt 1 at the paper's rate and salt) to 250 m of its 1000 m, with physics checks
on the frames and its figure (about 4 minutes on one core, including the one-time packing)."""
import os
import subprocess

import numpy as np
import pytest

from lmprun import ROOT, lmp_path, run_cmd
from test_scenes import dumps


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    wd = tmp_path_factory.mktemp("quick")
    cmd = [lmp_path(), "-in", str(ROOT / "examples" / "expt1.in"), "-var", "preset", "quick",
           "-var", "target", "250", "-var", "f", "50", "100", "200", "250", "-var", "root", str(ROOT), "-log", "log.lammps", "-echo", "none"]
    proc = run_cmd(cmd, cwd=wd, capture_output=True, text=True, timeout=1800,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    return wd, proc


def test_reaches_target_without_losses(quick):
    wd, proc = quick
    assert "expt1: done, displacement 250.0 m" in proc.stdout
    assert "WARNING" not in proc.stdout    # no Reynolds-number warning, no image-flag resets
    frames = dumps(wd, "expt1")
    assert len(frames) == 5    # 0, 50, 100, 200, 250 m
    n0 = [(f["type"] == t).sum() for f in frames[:1] for t in (1, 2, 3)]
    for f in frames[1:]:
        assert [(f["type"] == t).sum() for t in (1, 2, 3)] == n0    # no disc lost
        assert np.isfinite(f["x"]).all() and np.isfinite(f["vx"]).all()


def test_salt_flows_and_hanging_wall_subsides(quick):
    """Across 250 m of displacement on a 30 degree fault (throw 125 m) the salt and cover above
    the hanging wall subside more than above the footwall: the salt accommodates the fault."""
    wd, _ = quick
    frames = dumps(wd, "expt1")

    def top(f, t, x0, x1):
        m = (f["type"] == t) & (f["x"] > x0) & (f["x"] < x1)
        return np.percentile(f["y"][m] + f["radius"][m], 98)

    first, last = frames[0], frames[-1]
    throw = 250 * np.sin(np.radians(30))
    # the salt top over the hanging wall sinks clearly more than over the footwall (measured
    # 58-64 m more at 250 m); at the paper's rate and salt the cover moves as one raft
    # (docs/scenes.md) whose top sinks by about the throw on both sides: which side sinks more
    # is within the run-to-run spread (hanging wall -15 m to +4 m against the footwall in runs
    # of this scene), so for the cover only its subsidence is checked
    for t in (2, 1):    # salt top, cover top
        fw = top(last, t, 500, 2500) - top(first, t, 500, 2500)
        hw = top(last, t, 3800, 5800) - top(first, t, 3800, 5800)
        if t == 2:
            assert hw < fw - 0.15 * throw, (t, fw, hw)
        else:
            assert hw < -0.5 * throw and fw < -0.5 * throw, (t, fw, hw)
        assert hw > -1.5 * throw, (t, fw, hw)    # bounded by the basement's own drop + heave
    # the salt bands deform: the marker band boundaries are no longer vertical above the fault
    s0, s1 = first["type"] == 2, last["type"] == 2
    moved = np.hypot(last["x"][s1] - first["x"][s0], last["y"][s1] - first["y"][s0])
    assert np.percentile(moved, 90) > 0.2 * throw


def test_figure(quick):
    wd, proc = quick
    out = wd / "fig"
    r = subprocess.run(["/usr/bin/python3", str(ROOT / "python" / "saltdem-post"), "figure",
                        str(wd / "dump.expt1.*.txt"), "--fault-x", "3125", "--at", "100", "250", "-o", str(out), "--name", "q.png", "-q"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    assert (out / "q.png").stat().st_size > 100000
