"""Fault injection: damaged restart files, a series killed mid-segment and resumed, and an
output directory that fills up or disappears mid-run.  Each case must end in a clear error or
in the result an uninterrupted run gives: never a hang, a crash or a frame silently lost.

The scene is the tiny Expt 1 (examples/expt1.in -var preset tiny at 0.05 m/s, 2 m) with a restart
file every 0.25 m, so both files of the pair (.a/.b) and their checksums
(fix saltdem/checksum) exist after the first metre."""
import os
import re
import shutil
import signal
import subprocess
import time

import numpy as np
import pytest

import mpistart
from lmprun import ROOT, lmp_path, run_cmd
from test_scenes import dumps, run_deck

VARS = dict(preset="tiny", rate=0.05, restart_disp=0.25)    # the series runner passes the rate


def copy_run(src, dst):
    shutil.copytree(src, dst)
    return dst


def restarts(wd):
    """The pair's files, newest first."""
    return sorted(wd.glob("expt1.restart.[ab]"), key=lambda p: p.stat().st_mtime, reverse=True)


def frame_steps(wd):
    return sorted(int(p.name.split(".")[2]) for p in wd.glob("dump.expt1.*.txt"))


def assert_same_end(wd, ref, xtol, vtol):
    """wd ends where run `ref` ends: positions and velocities to xtol and vtol of their largest."""
    a, b = dumps(ref, "expt1")[-1], dumps(wd, "expt1")[-1]
    for c, tol in (("x", xtol), ("y", xtol), ("vx", vtol), ("vy", vtol)):
        np.testing.assert_allclose(b[c], a[c], rtol=0, atol=tol * np.abs(a[c]).max(), err_msg=c)


def assert_resumed_correctly(wd, restart, uninterrupted, tmp_path, deck=None):
    """wd, a series run resumed from the file `restart` (a saved copy), has every frame of the
    uninterrupted run and ends exactly where a plain resume from that file ends.  (A restart
    in the middle of a run perturbs it at round-off, which the flow then amplifies: against the
    uninterrupted run only to 1e-6 in positions, 1e-4 in velocities.  docs/reliability.md,
    Restart.)"""
    assert frame_steps(wd) == frame_steps(uninterrupted)
    ref = tmp_path / "resumed_by_hand"
    ref.mkdir()
    for p in [restart, restart.with_name(restart.name + ".sha256"), *uninterrupted.glob("pack_*")]:
        shutil.copy(p, ref / p.name)
    # (resumed by the deck that wrote the file: a restart file holds its motion fix's state
    # under that deck's fix ID and style)
    run_deck(deck or "expt1.in", ref, restart=restart.name, **VARS)
    assert_same_end(wd, ref, 1e-12, 1e-12)
    assert_same_end(wd, uninterrupted, 1e-6, 1e-4)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The uninterrupted run to 2 m."""
    wd = tmp_path_factory.mktemp("reference")
    run_deck("expt1.in", wd, **VARS)
    return wd


@pytest.fixture(scope="module")
def partial(tmp_path_factory, reference):
    """The run stopped after its first frame (1 m), from the reference's pack."""
    wd = tmp_path_factory.mktemp("partial")
    for p in reference.glob("pack_*.data"):
        shutil.copy(p, wd)
    run_deck("expt1.in", wd, f=1, **VARS)
    return wd


def test_every_restart_file_has_a_checksum_that_sha256sum_accepts(partial):
    files = restarts(partial)
    assert len(files) == 2
    for f in files:
        line = (partial / (f.name + ".sha256")).read_text()
        assert re.fullmatch(r"[0-9a-f]{64}  " + re.escape(f.name) + "\n", line), line
        r = subprocess.run(["sha256sum", "-c", f.name + ".sha256"], cwd=partial,
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stdout + r.stderr


def damage(path, kind):
    b = bytearray(path.read_bytes())
    n = len(b)
    if kind.startswith("truncate"):
        b = b[:n * int(kind[8:]) // 100]
    elif kind.startswith("flip"):
        b[n * int(kind[4:]) // 100] ^= 0x10
    elif kind.startswith("zero"):
        k = n * int(kind[4:]) // 100
        b[k:k + 64] = bytes(64)
    elif kind == "checksum-garbage":
        (path.parent / (path.name + ".sha256")).write_text("not a checksum\n")
        return
    elif kind == "checksum-of-the-other-file":
        other = path.name[:-1] + ("a" if path.name.endswith("b") else "b")
        shutil.copy(path.parent / (other + ".sha256"), path.parent / (path.name + ".sha256"))
        return
    path.write_bytes(bytes(b))


DAMAGES = ["truncate0", "truncate5", "truncate50", "truncate95", "flip10", "flip50", "flip99",
           "zero25", "zero50", "zero75", "checksum-garbage", "checksum-of-the-other-file"]


@pytest.mark.parametrize("kind", DAMAGES)
def test_damaged_restart_is_refused_naming_the_other_file(partial, tmp_path, kind):
    wd = copy_run(partial, tmp_path / "run")
    newest, older = restarts(wd)
    frames = frame_steps(wd)
    damage(newest, kind)
    r = run_deck("expt1.in", wd, check=False, timeout=120, restart=newest.name, **VARS)
    out = r.stdout + r.stderr
    assert r.returncode != 0, out[-2000:]
    err = next(l for l in out.splitlines() if l.startswith("ERROR"))
    assert "saltdem/read_restart" in err and newest.name in err, err
    assert f"resume from the other file of the pair, {older.name} (its checksum matches)" in out
    assert frame_steps(wd) == frames, "frames written after a refused resume"


def series(out, *extra, env_extra=None, timeout=600, popen=False, decks="1"):
    cmd = ["bash", str(ROOT / "examples" / "run-series.sh"), "expts", "tiny", "--",
           "-var", "restart_disp", str(VARS["restart_disp"]), *extra]
    # DECKS=1: from examples/expt1.in, the deck the partial runs were made with (0: from its
    # section description, the same trajectory)
    env = dict(os.environ, OMP_NUM_THREADS="1", LMP=lmp_path(), OUT=str(out), ONLY="expt1", DECKS=decks,
               **(env_extra or {}))
    if popen:
        return subprocess.Popen(cmd, cwd=out, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True, env=env, start_new_session=True)
    return run_cmd(cmd, cwd=out, capture_output=True, text=True, timeout=timeout, env=env)


def interrupted_series(partial, tmp_path):
    """OUT with the partial run laid out as an interrupted series run of expt1."""
    out = tmp_path / "out"
    run = out / "expts_tiny" / "expt1"
    run.parent.mkdir(parents=True)
    copy_run(partial, run)
    return out, run


def test_series_falls_back_to_the_older_file_and_says_so(partial, reference, tmp_path):
    out, run = interrupted_series(partial, tmp_path)
    newest, older = restarts(run)
    saved = tmp_path / "saved"
    saved.mkdir()
    shutil.copy(older, saved), shutil.copy(str(older) + ".sha256", saved)
    damage(newest, "zero50")
    r = series(out)
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
    assert (f"run-series: expt1: {newest.name} fails its checksum (damaged, or cut short while "
            f"written): resuming from the older {older.name}") in r.stdout + r.stderr
    assert (run / "done").exists()
    assert_resumed_correctly(run, saved / older.name, reference, tmp_path)


def test_series_stops_when_no_restart_file_is_sound(partial, tmp_path):
    out, run = interrupted_series(partial, tmp_path)
    for f in restarts(run):
        damage(f, "flip50")
    r = series(out)
    assert r.returncode != 0
    assert "no restart file" in r.stderr and "matches its checksum" in r.stderr, r.stderr
    assert not (run / "done").exists()


@pytest.mark.parametrize("decks", ["1", "0"])
def test_series_killed_mid_segment_resumes_to_the_uninterrupted_end(reference, tmp_path, decks):
    """SIGKILL to the whole series (runner and lmp) once a restart file and its checksum are
    there and the run has gone on past it; the same command again ends where the
    uninterrupted run ends, with all of its frames.  Both from the deck and from the section
    description (the runner's default for the paper's scenes)."""
    out = tmp_path / "out"
    out.mkdir()
    run = out / "expts_tiny" / "expt1"
    p = series(out, popen=True, decks=decks)
    try:
        t0 = time.monotonic()
        while not list(run.glob("expt1.restart.*.sha256")):
            assert p.poll() is None, p.communicate()[0][-3000:]
            assert time.monotonic() - t0 < 300, "no restart file after 300 s"
            time.sleep(0.05)
        time.sleep(0.3)
    finally:
        os.killpg(p.pid, signal.SIGKILL)
        p.wait()
    assert not (run / "done").exists(), "the run ended before it was killed: kill it earlier"
    saved = tmp_path / "saved"
    shutil.copytree(run, saved)
    r = series(out, decks=decks)
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
    used = re.search(r"-var restart (expt1\.restart\.[ab])", r.stdout).group(1)
    assert f"scene: resumed from {used}" in (run / "stdout.2.txt").read_text()
    assert (run / "stdout.1.txt").exists()    # the killed segment's output is kept
    assert "-var restart_disp 0.25" in (run / "cmd.txt").read_text()    # the runner's extra arguments
    assert_resumed_correctly(run, saved / used, reference, tmp_path,
                             deck=None if decks == "1" else run / "expt1.in")


# ---------------------------------------------------------------------------------------------
# the watchdog: a damaged file on which LAMMPS's reader loops forever
# ---------------------------------------------------------------------------------------------

SMALL = """units si
dimension 2
atom_style sphere
boundary f f p
region box block 100 300 100 300 -0.5 0.5
create_box 1 box
create_atoms 1 single 123.456789 150 0
create_atoms 1 single 234.5 250 0
set group all diameter 10
set group all density/disc 2200
write_restart r.bin
"""


def hanging_restart(wd):
    """r.bin with the first atom's record zeroed (its size and coordinates): the reader puts the
    atom outside the box and skips 0 values, for ever."""
    r = run_cmd([lmp_path(), "-echo", "none", "-log", "none"], input=SMALL, cwd=wd,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stdout + r.stderr
    b = bytearray((wd / "r.bin").read_bytes())
    k = b.find(np.float64(123.456789).tobytes())
    assert k > 8
    b[k - 8:k + 56] = bytes(64)
    (wd / "r.bin").write_bytes(bytes(b))


def read_deck(wd, line, timeout):
    return run_cmd([lmp_path(), "-echo", "none", "-log", "none"],
                          input=f"{line}\nprint 'read done'\n", cwd=wd, capture_output=True,
                          text=True, timeout=timeout)


def test_plain_read_restart_hangs_on_the_damaged_file(tmp_path):
    """Control: the damage does make LAMMPS's own read_restart loop (so the next test tests the
    watchdog, not an error LAMMPS would give anyway)."""
    hanging_restart(tmp_path)
    with pytest.raises(subprocess.TimeoutExpired):
        read_deck(tmp_path, "read_restart r.bin", timeout=10)


def test_watchdog_turns_the_hang_into_an_error(tmp_path):
    hanging_restart(tmp_path)
    t0 = time.monotonic()
    r = read_deck(tmp_path, "saltdem/read_restart r.bin timeout 2", timeout=60)
    assert time.monotonic() - t0 < 30
    assert r.returncode != 0 and "read done" not in r.stdout
    assert "ERROR: saltdem/read_restart: reading r.bin did not finish within 2 s" in r.stdout, \
        r.stdout[-2000:]
    assert "has no checksum file" in r.stdout    # warned first: nothing verified the file


def test_checksum_refuses_the_damaged_file_before_reading(tmp_path):
    (tmp_path / "r0").mkdir()
    wd = tmp_path / "r0"
    r = run_cmd([lmp_path(), "-echo", "none", "-log", "none"], input=SMALL, cwd=wd,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0
    subprocess.run("sha256sum r.bin > r.bin.sha256", shell=True, cwd=wd, check=True)
    ok = read_deck(wd, "saltdem/read_restart r.bin checksum required", timeout=60)
    assert ok.returncode == 0 and "read done" in ok.stdout, ok.stdout[-2000:]
    hanging_restart(wd)    # rewrites r.bin, damaged; the checksum is the sound file's
    t0 = time.monotonic()
    r = read_deck(wd, "saltdem/read_restart r.bin", timeout=60)
    assert time.monotonic() - t0 < 30    # refused before reading, not by the watchdog (60 s)
    assert r.returncode != 0
    assert "r.bin does not match its checksum r.bin.sha256" in r.stdout, r.stdout[-2000:]
    os.remove(wd / "r.bin.sha256")
    none = read_deck(wd, "saltdem/read_restart r.bin checksum required", timeout=60)
    assert none.returncode != 0 and "has no checksum file r.bin.sha256 (checksum required)" \
        in none.stdout


def test_damaged_scene_restart_without_checksum_never_hangs(partial, tmp_path):
    """Without a checksum nothing can tell a damaged file from a sound one, but no damage makes
    the read hang or crash: zeroed blocks and flipped bytes across the file end in an error or a
    completed read within the watchdog's time."""
    src = restarts(partial)[0]
    outcomes = []
    for kind in [f"zero{p}" for p in range(2, 100, 7)] + [f"flip{p}" for p in (1, 33, 66)]:
        wd = tmp_path / kind
        wd.mkdir()
        shutil.copy(src, wd / "r.bin")
        damage(wd / "r.bin", kind)
        try:
            r = read_deck(wd, "saltdem/read_restart r.bin timeout 5", timeout=60)
        except subprocess.TimeoutExpired:
            pytest.fail(f"{kind}: the read hung past the watchdog")
        out = r.stdout + r.stderr
        if r.returncode == 0:
            assert "read done" in out, f"{kind}: exit 0 without finishing\n{out[-1500:]}"
            outcomes.append("read")
        else:
            assert r.returncode < 128 and any(l.startswith("ERROR") for l in out.splitlines()), \
                f"{kind}: rc {r.returncode} without an ERROR line\n{out[-1500:]}"
            outcomes.append("error")
    assert "error" in outcomes


# ---------------------------------------------------------------------------------------------
# the output directory fills up or disappears mid-run
# ---------------------------------------------------------------------------------------------

def incomplete_frames(wd):
    """The frames on disk that do not hold all of their atoms."""
    bad = []
    for p in sorted(wd.glob("dump.expt1.*.txt"), key=lambda p: int(p.name.split(".")[2])):
        lines = p.read_text().splitlines()
        try:
            n = int(lines[lines.index("ITEM: NUMBER OF ATOMS") + 1])
            head = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
            ok = len(lines) - head - 1 == n and len(lines[-1].split()) == 8
        except (ValueError, IndexError, StopIteration):
            ok = False
        if not ok:
            bad.append(p.name)
    return bad


def test_disk_full_mid_run_is_an_error_and_loses_no_frame(reference, tmp_path):
    """The run's directory on a small file system that fills after the first frames."""
    """The run's directory on a small file system that fills up mid-run (at 45-65 % of what the
    whole run writes, so the full disk strikes a frame, a restart file or a checksum).  The run
    stops with an error that says what it could not write; every frame but the one being
    written then is complete, and a restart file cut short (LAMMPS does not notice) is caught
    by its checksum."""
    used = sum(p.stat().st_size for p in reference.iterdir() if p.is_file())
    errors = []
    for frac in (0.45, 0.55, 0.65):
        mnt = tmp_path / f"small{frac}"
        mnt.mkdir()
        r = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={int(frac * used) // 4096 * 4096}",
                            "tmpfs", str(mnt)], capture_output=True, text=True)
        if r.returncode != 0:
            pytest.skip(f"cannot mount a small tmpfs here ({r.stderr.strip()}); the removed "
                        "directory test covers an unwritable directory")
        try:
            for p in reference.glob("pack_*.data"):
                shutil.copy(p, mnt)
            r = run_deck("expt1.in", mnt, check=False, timeout=300, **VARS)
            out = r.stdout + r.stderr
            assert r.returncode != 0, f"{frac}: the run finished on a full disk"
            err = next((l for l in out.splitlines() if l.startswith("ERROR")), None)
            assert err is not None, out[-2000:]
            assert re.search(r"No space left|disk not full|I/O error while writing", err), err
            errors.append(err)
            bad = incomplete_frames(mnt)
            frames = sorted(mnt.glob("dump.expt1.*.txt"), key=lambda p: int(p.name.split(".")[2]))
            assert bad in ([], [frames[-1].name]), f"{frac}: incomplete frames {bad}"
            if bad:
                assert "Error writing dump" in err, err
            for f in restarts(mnt):    # a restart file either checks out or is refused
                s = mnt / (f.name + ".sha256")
                ok = s.exists() and subprocess.run(["sha256sum", "--status", "-c", s.name],
                                                   cwd=mnt).returncode == 0
                if not ok:
                    r = run_deck("expt1.in", mnt, check=False, timeout=120, restart=f.name, **VARS)
                    assert r.returncode != 0 and "saltdem/read_restart" in r.stdout
        finally:
            subprocess.run(["umount", str(mnt)])
    assert errors


def test_output_directory_removed_mid_run_is_an_error(reference, tmp_path):
    """The run's directory removed once the first restart file is there: the next frame,
    restart or checksum cannot be written, and the run stops with an error."""
    wd = tmp_path / "run"
    wd.mkdir()
    for p in reference.glob("pack_*.data"):
        shutil.copy(p, wd)
    cmd = [lmp_path(), "-in", str(ROOT / "examples" / "expt1.in"), "-echo", "none", "-log",
           "none", "-var", "root", str(ROOT)]
    for k, v in VARS.items():
        cmd += ["-var", k, str(v)]
    p = subprocess.Popen(cmd, cwd=wd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    t0 = time.monotonic()
    while not list(wd.glob("expt1.restart.*.sha256")):
        assert p.poll() is None, p.communicate()[0][-3000:]
        assert time.monotonic() - t0 < 300
        time.sleep(0.02)
    shutil.rmtree(wd)
    out, _ = p.communicate(timeout=300)
    if mpistart.start_failed(out):
        pytest.fail("INFRASTRUCTURE FAILURE, not a test result: Open MPI did not start")
    assert p.returncode != 0, "the run finished without its directory"
    err = next((l for l in out.splitlines() if l.startswith("ERROR")), None)
    assert err is not None and re.search(r"Cannot open|cannot read|writ", err), out[-2000:]
