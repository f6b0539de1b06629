"""The paper's scenes (examples/expt1-3.in) at the tiny preset, and the scene assembly."""
import json
import os
import shutil

import re

import numpy as np
import pytest
from scipy.spatial import cKDTree

from lmprun import ROOT, lmp_path, run_cmd


def run_deck(deck, wd, timeout=900, check=True, **var):
    cmd = [lmp_path(), "-in", str(ROOT / "examples" / deck), "-log", "log.lammps", "-echo", "none",
           "-var", "root", str(ROOT)]
    for k, v in var.items():
        cmd += ["-var", k, *str(v).split()]
    proc = run_cmd(cmd, cwd=wd, capture_output=True, text=True, timeout=timeout,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))
    if check:
        assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    return proc


def dumps(wd, name):
    files = sorted(wd.glob(f"dump.{name}.*.txt"), key=lambda p: int(p.name.split(".")[2]))
    return [read_dump(f) for f in files]


def read_dump(path):
    lines = path.read_text().splitlines()
    head = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))    # (after TIME)
    cols = lines[head].split()[2:]
    data = np.array([[float(v) for v in l.split()] for l in lines[head + 1:]])
    d = {c: data[:, k] for k, c in enumerate(cols)}
    order = np.argsort(d["id"])
    return {c: v[order] for c, v in d.items()}


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    out = {}
    for name in ("expt1", "expt2", "expt3"):
        wd = tmp_path_factory.mktemp(name)
        out[name] = (wd, run_deck(f"{name}.in", wd, preset="tiny"))
    return out


@pytest.mark.parametrize("name", ["expt1", "expt2", "expt3"])
def test_deck_runs_to_target(tiny, name):
    wd, proc = tiny[name]
    assert f"{name}: done, displacement 2.0 m" in proc.stdout
    frames = dumps(wd, name)
    assert len(frames) == 3    # 0, 1 and 2 m
    first = frames[0]
    assert (first["type"] == 1).sum() > 50 and (first["type"] == 2).sum() > 20
    assert np.all(first["i_marker"][first["type"] == 3] == -1)
    # progress: displacement, percent, natural time and Reynolds number in the thermo output
    assert "v_pct" in proc.stdout and "v_tnat" in proc.stdout and "f_scale[1]" in proc.stdout
    assert list(wd.glob(f"{name}.restart.*")), "no restart files"


def test_target_below_the_last_frame_ends_the_run_there(tmp_path):
    """-var target below the frame list: the frames beyond it are one frame at the target and
    the run ends there (it ran on with the drive at rest before).  Control: the frame steps
    follow the drive, 1 m and 1.5 m at 0.05 m/s."""
    proc = run_deck("expt1.in", tmp_path, preset="tiny", target=1.5, f="1 2 3")
    assert "expt1: done, displacement 1.5 m" in proc.stdout
    steps = sorted(int(p.name.split(".")[2]) for p in tmp_path.glob("dump.expt1.*.txt"))
    assert len(steps) == 3    # 0, 1 and 1.5 m
    drive = [st - steps[0] for st in steps[1:]]
    assert drive[1] == pytest.approx(1.5 * drive[0], abs=1)


def wall_motion(frames, select):
    """Displacements (first to last frame) of the wall discs chosen by select(x, y)."""
    a, b = frames[0], frames[-1]
    assert np.array_equal(a["id"], b["id"])
    m = (a["type"] == 3) & select(a["x"], a["y"])
    return np.c_[b["x"][m] - a["x"][m], b["y"][m] - a["y"][m]]


def test_expt2_keystone_blocks(tiny):
    wd, _ = tiny["expt2"]
    frames = dumps(wd, "expt2")
    c, s = np.cos(np.radians(60)), np.sin(np.radians(60))
    left = wall_motion(frames, lambda x, y: x < 4000)
    key = wall_motion(frames, lambda x, y: (x > 5300) & (x < 7200) & (y > -150))
    right = wall_motion(frames, lambda x, y: x > 9000)
    assert len(left) > 5 and len(key) > 5 and len(right) > 5
    np.testing.assert_allclose(left, 0.0, atol=1e-6)
    np.testing.assert_allclose(key, np.tile([2 * c, -2 * s], (len(key), 1)), rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(right, np.tile([4 * c, 0.0], (len(right), 1)), rtol=1e-5, atol=1e-5)
    # symmetric graben: the keystone moves by the same amount relative to either side
    rel_left, rel_right = key[0] - left[0], key[0] - right[0]
    assert abs(np.hypot(*rel_left) - np.hypot(*rel_right)) < 1e-5


def test_expt3_end_wall_and_tilted_gravity(tiny):
    wd, proc = tiny["expt3"]
    frames = dumps(wd, "expt3")
    end = wall_motion(frames, lambda x, y: (x > 6300) & (y > 0))
    base = wall_motion(frames, lambda x, y: (x < 6300) | (y < 0))
    np.testing.assert_allclose(end, np.tile([2.0, 0.0], (len(end), 1)), atol=1e-5)
    np.testing.assert_allclose(base, 0.0, atol=1e-6)
    # the tilted gravity pulls the pack down the base (+x): mean vx of the pack > 0
    last = frames[-1]
    assert last["vx"][last["type"] != 3].mean() > 0.0


@pytest.fixture(scope="module")
def assembly(tmp_path_factory):
    """A small scene assembly at the quick preset's radii: 2.5 km x (400 m salt + 700 m cover)."""
    wd = tmp_path_factory.mktemp("assembly")
    geo = dict(width=2500, salt=400, cover=700, marker=100)
    proc = run_deck("expt1.in", wd, preset="tiny", rmin=25, rmax=62.5, dist="paper", nsettle=2000,
                    target=1, f=1, dt=0.0025, rate=1, S=4, **geo)
    return wd, proc, geo


def test_assembly_layers_and_markers(assembly):
    wd, proc, g = assembly
    first = dumps(wd, "expt1")[0]
    x, y, r, t, mk = first["x"], first["y"], first["radius"], first["type"], first["i_marker"]
    salt, cover = t == 2, t == 1
    dmean = 2 * r[salt | cover].mean()
    # the paper's radius law: mean 0.4439 (rmin + rmax), 9.71 m for 6.25-15.625 m
    assert abs(r[salt | cover].mean() / (0.44389 * 87.5) - 1) < 0.05
    # layer thicknesses within one mean disc diameter
    assert abs((y[salt] + r[salt]).max() - g["salt"]) < dmean
    assert abs((y[cover] + r[cover]).max() - (g["salt"] + g["cover"])) < dmean
    assert abs((y[salt] - r[salt]).min()) < dmean
    # markers: 100 m salt bands across the width, 100 m cover layers over its thickness
    assert np.unique(mk[salt]).size == pytest.approx(g["width"] / g["marker"], abs=1)
    assert np.unique(mk[cover]).size == pytest.approx(g["cover"] / g["marker"], abs=1)
    # settled: the overlaps of the cover's contacts (cover-cover, cover-salt) stay small against
    # the disc radii: mean under 2 % of the smaller radius, worst under 10 % of rmin (kn 2.5e9
    # N/m of the calibrated cover under the weight of 700 m of it).  Salt-salt pairs are SPH
    # particles without a hard core (kn_salt 0): their overlaps are not contacts
    p, rr, tt = np.c_[x, y][salt | cover], r[salt | cover], t[salt | cover]
    pairs = cKDTree(p).query_pairs(2 * rr.max(), output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    gap = np.hypot(*(p[i] - p[j]).T) - rr[i] - rr[j]
    withcover = (tt[i] == 1) | (tt[j] == 1)
    touching = withcover & (gap < 0)
    rel = -gap[touching] / np.minimum(rr[i], rr[j])[touching]
    assert touching.sum() > 100 and rel.mean() < 0.02, rel.mean()
    assert -gap[withcover].min() < 0.10 * 25
    assert -gap[~withcover].min() < 0.5 * 25    # salt: no disc sits on top of another
    line = [l for l in proc.stdout.splitlines() if l.startswith("pack:")][0]
    phi = float(line.split("packing fraction")[1].split(",")[0])
    z = float(line.split("coordination number")[1])
    assert 0.80 < phi < 0.90 and 3.0 < z < 4.5


def test_series_runner_fig7(tmp_path):
    """examples/run-series.sh fig7 tiny: three salt thicknesses, three figures."""
    env = dict(os.environ, OMP_NUM_THREADS="1", LMP=lmp_path())
    r = run_cmd(["bash", str(ROOT / "examples" / "run-series.sh"), "fig7", "tiny"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=600, env=env)
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
    for salt in (1000, 500, 250):
        d = ROOT / "out" / "fig7_tiny" / f"fig7_salt{salt}"
        assert f"salt {salt} m" in (d / "stdout.1.txt").read_text()
        assert (d / "figures" / f"fig7_salt{salt}.png").stat().st_size > 10000
        assert (d / "cmd.txt").read_text().strip() == \
            ("python/saltdem-section examples/sections/fig7.toml -o fig7.in && "
             f"lmp -in fig7.in -var preset tiny -var rate 0.05 -var salt {salt}")


def test_series_runner_contact_only_list(tmp_path):
    """examples/run-series.sh contact tiny with ONLY: just the named runs, with the contact salt,
    under a relative OUT (taken from the directory the script is called in)."""
    series = tmp_path / "runs" / "contact_tiny"
    env = dict(os.environ, OMP_NUM_THREADS="1", LMP=lmp_path(), ONLY="fig7_salt250_contact expt3_contact",
               OUT="runs")
    r = run_cmd(["bash", str(ROOT / "examples" / "run-series.sh"), "contact", "tiny"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=600, env=env)
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
    assert sorted(p.name for p in series.iterdir()) == ["expt3_contact", "fig7_salt250_contact"]
    for name, deck in (("fig7_salt250_contact", "fig7"), ("expt3_contact", "expt3")):
        d = series / name
        assert "-var saltlaw contact" in (d / "cmd.txt").read_text()
        assert f"examples/sections/{deck}.toml" in (d / "cmd.txt").read_text()
        assert (d / "done").exists() and (d / "outcomes" / "outcomes.json").exists()
        assert "scene: salt law contact" in (d / "stdout.1.txt").read_text()
        # the run read its own copy of the scene files (an edit to the repository's files while
        # it runs, or between its segments, does not reach it)
        for f in ("examples/scene/frames.in", "examples/expt3.in", "potentials/cover_paper.params",
                  "tools/pack.in"):
            assert (d / "scene-files" / f).read_text() == (ROOT / f).read_text()


def test_series_runner_3d(tmp_path):
    """examples/run-series.sh 3d tiny: the periodic slab and the fault dying out along strike,
    each cut into sections (two planes of the slab, five between the end walls) with their
    outcomes and figures, and the cover's map view."""
    env = dict(os.environ, OMP_NUM_THREADS="1", LMP=lmp_path(), OUT="runs")
    r = run_cmd(["bash", str(ROOT / "examples" / "run-series.sh"), "3d", "tiny"],
                cwd=tmp_path, capture_output=True, text=True, timeout=900, env=env)
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
    for name, zs in (("expt1_3d", ("500", "0")), ("fault_tip_3d", ("150", "450", "750", "1050", "1350"))):
        d = tmp_path / "runs" / "3d_tiny" / name / "post3d"
        for z in zs:
            o = json.loads((d / f"outcomes_z{z}" / "outcomes.json").read_text())
            assert o, (name, z)
            assert (d / "figures" / f"expt1_z{z}.png").stat().st_size > 10000
        assert (d / "mapview.png").stat().st_size > 10000
    cmd = (tmp_path / "runs" / "3d_tiny" / "fault_tip_3d" / "cmd.txt").read_text()
    assert "-var zends walls -var taper_from 0 -var taper_to 1000" in cmd


@pytest.mark.parametrize("name", ["expt1", "expt2"])
def test_resume_from_restart_file(tmp_path, name):
    """A run stopped after its first frame and resumed from its restart file (-var restart) ends
    in the same state as the uninterrupted run: shear history, the salt's continuity and
    reference densities, and the motion fix's displacement all come back."""
    full, part = tmp_path / "full", tmp_path / "part"
    full.mkdir(), part.mkdir()
    run_deck(f"{name}.in", full, preset="tiny")
    for p in full.glob("pack_*.data"):
        (part / p.name).write_bytes(p.read_bytes())
    run_deck(f"{name}.in", part, preset="tiny", f=1)
    newest = max(part.glob(f"{name}.restart.[ab]"), key=lambda p: p.stat().st_mtime)
    proc = run_deck(f"{name}.in", part, preset="tiny", restart=newest.name)
    assert "resumed from" in proc.stdout and f"{name}: done, displacement 2.0 m" in proc.stdout
    a, b = dumps(full, name)[-1], dumps(part, name)[-1]
    for c in ("x", "y", "vx", "vy"):
        np.testing.assert_allclose(b[c], a[c], rtol=1e-10, atol=1e-10 * np.abs(a[c]).max())
    # the model time goes on too (the figures' --rate reads it): a restart file written in the
    # middle of a run must not lose the time since that run began
    last = lambda wd: sorted(wd.glob(f"dump.{name}.*.txt"), key=lambda p: int(p.name.split(".")[2]))[-1]
    assert dump_time(last(part)) == pytest.approx(dump_time(last(full)), rel=1e-12)


def test_resume_keeps_or_sets_the_substeps(tmp_path):
    """A resumed run keeps the restart file's viscous sub-steps unless -var substeps gives them:
    the default (0) and 2 continue a 2-sub-step run alike (to the bit), 1 turns them off (a
    plain reference resumed from a sub-stepped file), and the log says which."""
    first = tmp_path / "first"
    first.mkdir()
    run_deck("expt1.in", first, preset="tiny", substeps=2, f=1)
    restart = max(first.glob("expt1.restart.[ab]"), key=lambda p: p.stat().st_mtime)
    last = {}
    for n in (0, 1, 2):
        wd = tmp_path / f"sub{n}"
        wd.mkdir()
        for p in first.glob("pack_*.data"):
            (wd / p.name).write_bytes(p.read_bytes())
        run_deck("expt1.in", wd, preset="tiny", substeps=n, restart=str(restart), f=1.5)
        said = "the viscosity in 2 sub-steps per step" in (wd / "log.lammps").read_text()
        assert said == (n != 1), f"-var substeps {n}: the log says otherwise"
        last[n] = dumps(wd, "expt1")[-1]
    for c in ("x", "y", "vx", "vy"):
        np.testing.assert_array_equal(last[0][c], last[2][c])
    assert np.abs(last[1]["vx"] - last[2]["vx"]).max() > 0, "substeps 1 did not change the run"


def test_resume_keeps_or_sets_implicit(tmp_path):
    """-var implicit yes runs the salt's viscosity implicitly (the log says so, with its
    iterations); a resumed run keeps the file's setting (auto, the default) or takes the one
    given: auto and yes continue alike (to the bit), no turns it off."""
    first = tmp_path / "first"
    first.mkdir()
    run_deck("expt1.in", first, preset="tiny", implicit="yes", f=1)
    log = (first / "log.lammps").read_text()
    assert "the viscosity in an implicit step" in log
    assert re.search(r"implicit viscous step: [0-9.]+ iterations per step", log)
    restart = max(first.glob("expt1.restart.[ab]"), key=lambda p: p.stat().st_mtime)
    last = {}
    for v in ("auto", "no", "yes"):
        wd = tmp_path / v
        wd.mkdir()
        for p in first.glob("pack_*.data"):
            (wd / p.name).write_bytes(p.read_bytes())
        run_deck("expt1.in", wd, preset="tiny", implicit=v, restart=str(restart), f=1.5)
        said = "the viscosity in an implicit step" in (wd / "log.lammps").read_text()
        assert said == (v != "no"), f"-var implicit {v}: the log says otherwise"
        last[v] = dumps(wd, "expt1")[-1]
    for c in ("x", "y", "vx", "vy"):
        np.testing.assert_array_equal(last["auto"][c], last["yes"][c])
    assert np.abs(last["no"]["vx"] - last["yes"]["vx"]).max() > 0, "implicit no changed nothing"
    # -var implicit_tol sets the solver's tolerance on the resumed style
    wd = tmp_path / "tol"
    wd.mkdir()
    for p in first.glob("pack_*.data"):
        (wd / p.name).write_bytes(p.read_bytes())
    run_deck("expt1.in", wd, preset="tiny", implicit="yes", implicit_tol="0.01",
             restart=str(restart), f=1.5)
    assert "implicit step (tolerance 0.01," in (wd / "log.lammps").read_text()
    assert np.abs(dumps(wd, "expt1")[-1]["vx"] - last["yes"]["vx"]).max() > 0


@pytest.mark.parametrize("extra,says", [({}, None),
                                        (dict(implicit_preset="yes", implicit_preset_tol="0.01"), "tolerance 0.01,"),
                                        (dict(implicit_preset="yes", implicit_preset_tol="0.01", implicit_tol="0.001"),
                                         "tolerance 0.001,"),
                                        (dict(implicit_preset="yes", implicit_preset_tol="0.01", implicit="no"), None),
                                        (dict(implicit_preset="yes", implicit_preset_tol="0.01", saltlaw="contact"),
                                         None)])
def test_implicit_auto_takes_the_presets_choice(tmp_path, extra, says):
    """implicit auto (the default) on a new run takes the preset's choice (params.in: the full
    preset sets implicit_preset yes at tolerance 0.01, the others no; here the tiny preset is
    given the full preset's choice); -var implicit_tol and -var implicit no override it, and the
    contact salt, which has no implicit step, keeps the explicit one."""
    run_deck("expt1.in", tmp_path, preset="tiny", f=1, **extra)
    log = (tmp_path / "log.lammps").read_text()
    if says is None:
        assert "the viscosity in an implicit step" not in log
    else:
        assert f"the viscosity in an implicit step ({says}" in log, log[-2000:]


@pytest.mark.parametrize("args,msg", [(("implicit", "maybe"), "implicit maybe must be yes, no or auto"),
                                      (("implicit", "yes", "saltlaw", "contact"),
                                       "implicit yes is for the SPH salt"),
                                      (("implicit_tol", "1e-3"), "implicit_tol 1e-3 needs -var implicit yes")])
def test_bad_implicit_stops(tmp_path, args, msg):
    extra = [a for k, v in zip(args[::2], args[1::2]) for a in ("-var", k, v)]
    r = run_cmd([lmp_path(), "-in", str(ROOT / "examples" / "expt1.in"), "-var", "root",
                 str(ROOT), "-var", "preset", "tiny", *extra, "-log", "none", "-echo", "none"],
                cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert r.returncode != 0 and msg in r.stdout, r.stdout[-1500:]


def test_negative_substeps_stop(tmp_path):
    r = run_cmd([lmp_path(), "-in", str(ROOT / "examples" / "expt1.in"), "-var", "root",
                        str(ROOT), "-var", "preset", "tiny", "-var", "substeps", "-1", "-log",
                        "none", "-echo", "none"], cwd=tmp_path, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode != 0 and "substeps -1 must be 0 (default), 1 or more" in r.stdout


def dump_time(path):
    lines = path.read_text().splitlines()
    return float(lines[lines.index("ITEM: TIME") + 1])


def test_missing_restart_file_stops(tmp_path):
    r = run_cmd([lmp_path(), "-in", str(ROOT / "examples" / "expt1.in"), "-var", "root",
                        str(ROOT), "-var", "preset", "tiny", "-var", "restart", "expt1_restart_x",
                        "-log", "none", "-echo", "none"], cwd=tmp_path, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode != 0 and "restart file expt1_restart_x not found" in r.stdout
    assert not list(tmp_path.glob("dump.*"))
