"""Section descriptions (python/saltdem-section): every section file of examples/sections writes a
deck that runs at the tiny preset; the paper's scenes written as sections give the decks'
trajectories bit for bit; the domino blocks follow the bookshelf kinematics; bad descriptions
stop with a message that names the problem, before anything runs."""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lmprun import check_ok, lmp_path, run_cmd

ROOT = Path(__file__).resolve().parents[1]
GEN = ROOT / "python" / "saltdem-section"
SECTIONS = sorted((ROOT / "examples" / "sections").glob("*.toml"))
sys.path.insert(0, str(ROOT / "python"))
from saltdem_post.section import SectionError, parse, deck  # noqa: E402


def write_deck(section: Path, out: Path) -> Path:
    r = subprocess.run([sys.executable, str(GEN), str(section), "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return out


def run_deck(deck_path: Path, workdir: Path, *args):
    workdir.mkdir(parents=True, exist_ok=True)
    return run_cmd([lmp_path(), "-in", str(deck_path), "-var", "root", str(ROOT), "-var", "preset", "tiny",
                    "-log", "log.lammps", *args], cwd=workdir, capture_output=True, text=True, timeout=600)


def frames(workdir: Path, name: str) -> dict:
    return {p.name: p.read_bytes() for p in sorted(workdir.glob(f"dump.{name}.*.txt"))}


def test_there_are_section_files():
    names = {p.stem for p in SECTIONS}
    assert {"expt1", "expt2", "expt3", "fig7", "wedge", "domino", "pinchout", "pillow"} <= names


@pytest.mark.parametrize("section", SECTIONS, ids=lambda p: p.stem)
def test_each_section_runs_at_tiny(tmp_path, section):
    d = write_deck(section, tmp_path / f"{section.stem}.in")
    r = run_deck(d, tmp_path / "run")
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
    name = parse(section.read_text(), str(section)).name
    assert f"{name}: done, displacement 2.0 m" in r.stdout or f"{name}: done, displacement 2.0" in r.stdout
    assert len(frames(tmp_path / "run", name)) >= 3


@pytest.mark.parametrize("expt", ["expt1", "expt2", "expt3", "wedge"])
def test_paper_scenes_as_sections_are_bit_identical(tmp_path, expt):
    d = write_deck(ROOT / "examples" / "sections" / f"{expt}.toml", tmp_path / f"s_{expt}.in")
    a = run_deck(ROOT / "examples" / f"{expt}.in", tmp_path / "deck")
    b = run_deck(d, tmp_path / "section")
    assert a.returncode == 0 and b.returncode == 0, (a.stdout + b.stdout)[-3000:]
    fa, fb = frames(tmp_path / "deck", expt), frames(tmp_path / "section", expt)
    assert len(fa) >= 3 and fa.keys() == fb.keys()
    for k in fa:
        assert fa[k] == fb[k], f"{expt}: frame {k} differs"


def test_fig7_section_takes_the_salt_thickness(tmp_path):
    d = write_deck(ROOT / "examples" / "sections" / "fig7.toml", tmp_path / "fig7.in")
    r = run_deck(d, tmp_path / "run", "-var", "salt", "500")
    assert r.returncode == 0, r.stdout[-3000:]
    assert "salt 500 m" in r.stdout


def test_domino_blocks_follow_the_bookshelf(tmp_path):
    """After the drive, each domino block's crest has moved right by e_k(theta) and stays at the
    basement top, the blocks have turned by theta, and each hanging-wall corner lies on the fault
    face of the block to its left (static for the first, turned by theta for the others)."""
    s = parse((ROOT / "examples" / "sections" / "domino.toml").read_text(), "domino.toml")
    d = tmp_path / "domino.in"
    d.write_text(deck(s).replace("include         ${root}/examples/scene/frames.in",
                                 "run 0\nthermo_style custom step f_blocks[1] "
                                 + " ".join(f"f_blocks[{k}][2] f_blocks[{k}][3] f_blocks[{k}][4]" for k in (1, 2, 3))
                                 + "\nthermo_modify format float %.15g\nthermo 1\nrun 1000\n"))
    r = run_deck(d, tmp_path / "run", "-var", "target", "1000", "-var", "rate", "1000")
    assert r.returncode == 0, r.stdout[-3000:]
    # the last thermo line, after the target
    lines = [l.split() for l in r.stdout.splitlines() if l.strip() and l.split()[0] == "1000"]
    v = [float(x) for x in lines[-1][1:]]
    assert v[0] == pytest.approx(1000.0)
    th = math.radians(20.0)
    D = math.radians(60.0)
    L = 2500.0
    e, ek = [], 0.0
    for k in range(3):
        deff = D if k == 0 else D - th
        ek += L * (math.cos(th) - 1 + math.sin(th) / math.tan(deff))
        e.append(ek)
    for k in range(3):
        heave, throw, turn = v[1 + 3 * k: 4 + 3 * k]
        assert heave == pytest.approx(e[k], rel=1e-9), k
        assert abs(throw) < 1e-6 * L
        assert turn == pytest.approx(20.0, rel=1e-12)
    # each hanging-wall corner on the face to its left
    for k in range(3):
        crest = np.array([2500.0 * (k + 2) + e[k], 0.0])
        corner = crest + L * np.array([-math.cos(th), -math.sin(th)])
        top = np.array([2500.0 * (k + 1) + (e[k - 1] if k else 0.0), 0.0])
        dip = D if k == 0 else D - th
        face = np.array([math.cos(dip), -math.sin(dip)])
        rel = corner - top
        assert abs(rel[0] * face[1] - rel[1] * face[0]) < 1e-6 * L, k   # on the line
        assert rel @ face > 0                                            # below the top


GOOD = """
name = "t"
width = 6000
[salt]
thickness = 1000
[cover]
thickness = 1500
[[fault]]
name = "a"
x = 1500
dip = 45
[[fault]]
name = "b"
x = 4500
dip = 45
toward = "left"
[[block]]
name = "l"
static = true
[[block]]
name = "k"
slip = "a"
[[block]]
name = "r"
static = true
"""


@pytest.mark.parametrize("change,words", [
    (lambda t: t.replace('x = 4500', 'x = 1000'), "give the faults left to right"),
    (lambda t: t.replace('x = 4500', 'x = 2600'), "faults a and b cross"),
    (lambda t: t.replace('x = 4500', 'x = 7000'), "x 7000 lies outside the box"),
    (lambda t: t.replace('slip = "a"', ''), "block 2 (k): no kinematics"),
    (lambda t: t.replace('slip = "a"', 'slip = "z"'), "slip names fault 'z', which is not given"),
    (lambda t: t.replace('[[block]]\nname = "r"\nstatic = true\n', ''), "cut the basement into 3 blocks; 2 are given"),
    (lambda t: t.replace('thickness = 1000', 'thickness = 1000\npillow = {x = 5800, width = 1000, height = 300}'),
     "the pillow (x 5800 +- 500 m) lies outside the box"),
    (lambda t: t.replace('thickness = 1000', 'profile = [[0, 1000], [3000, 0]]'), "profile must span the box"),
    (lambda t: t.replace('[cover]\nthickness = 1500\n', ''), "the [cover] table is missing"),
    (lambda t: t.replace('dip = 45\n[[fault]]', 'dip = 95\n[[fault]]'), "dip 95 must be in (0, 90]"),
    (lambda t: t.replace('static = true\n[[block]]\nname = "k"', 'top = 500\nstatic = true\n[[block]]\nname = "k"')
     .replace('slip = "a"', 'slip = "a"\ntop = 900'), "stands higher than its footwall"),
    (lambda t: t.replace('name = "t"', 'name = "t"\nwidht = 3'), "unknown key(s) widht"),
    (lambda t: t.replace('slip = "a"', 'slip = "a"\nto = 2000'), "to 2000 is beyond the target 1000"),
    (lambda t: t + "[walls]\nright = 'sideways'\n", "right 'sideways' must be block, static or move"),
    (lambda t: t.replace('static = true\n[[block]]\nname = "k"\nslip = "a"', 'static = true\n[[block]]\nname = "k"\ntilt = 0.01'),
     "domino blocks (tilt) must be the last blocks"),
    (lambda t: t.replace('thickness = 1500', 'thickness = 1500\n[[cover.unit]]\nname = "top"\nthickness = 1500'),
     "unit 1 (top): no material file"),
    (lambda t: t.replace('thickness = 1500', 'thickness = 1500\n[[cover.unit]]\nname = "top"\nthickness = 1000\n'
                         'material = "potentials/cover_paper.params"'), "its units add up to 1000 m, not the cover's 1500 m"),
    (lambda t: t.replace('thickness = 1500', 'thickness = 1500\n[[cover.unit]]\nname = "top"\nthickness = 1500\n'
                         'material = "potentials/nosuch.params"'), "material file potentials/nosuch.params not found"),
])
def test_bad_descriptions_name_the_problem(tmp_path, change, words):
    parse(GOOD, "good.toml")     # the base description is fine
    bad = tmp_path / "bad.toml"
    bad.write_text(change(GOOD))
    r = subprocess.run([sys.executable, str(GEN), str(bad), "-o", str(tmp_path / "bad.in")],
                       capture_output=True, text=True)
    assert r.returncode == 1, r.stdout + r.stderr
    assert words in r.stderr, r.stderr
    assert "Traceback" not in r.stderr
    assert not (tmp_path / "bad.in").exists()     # nothing half-built


def test_not_toml_is_a_clear_error(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("width = = 3\n")
    r = subprocess.run([sys.executable, str(GEN), str(bad), "--check"], capture_output=True, text=True)
    assert r.returncode == 1 and "not a valid description" in r.stderr


def test_a_preset_that_cannot_pack_the_section_stops(tmp_path):
    d = write_deck(ROOT / "examples" / "sections" / "fig7.toml", tmp_path / "fig7.in")
    r = run_deck(d, tmp_path / "run", "-var", "salt", "200")
    assert r.returncode == 1
    assert "section fig7: preset tiny cannot pack it: salt 200 m" in r.stdout
    assert not list((tmp_path / "run").glob("dump.*"))


def test_cover_units_take_their_types_and_materials(tmp_path):
    """The pillow section: the top 750 m of the cover is the weak unit (type 4, its own material
    file's coefficients; against the paper cover the weaker of each value), the rest type 1."""
    d = write_deck(ROOT / "examples" / "sections" / "pillow.toml", tmp_path / "pillow.in")
    r = run_deck(d, tmp_path / "run")
    assert r.returncode == 0, r.stdout[-3000:]
    first = sorted((tmp_path / "run").glob("dump.pillow.*.txt"), key=lambda p: int(p.name.split(".")[2]))[0]
    lines = first.read_text().splitlines()
    head = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[head].split()[2:]
    a = np.array([[float(v) for v in l.split()] for l in lines[head + 1:]])
    typ, y = a[:, cols.index("type")], a[:, cols.index("y")]
    top = 600 + 1750
    assert (typ == 4).sum() > 10 and (typ == 1).sum() > 10
    # after settling the weak unit is the upper part of the cover
    assert np.median(y[typ == 4]) > np.median(y[typ == 1])
    assert y[typ == 4].min() > top - 750 - 300      # (settling moves discs by less than a disc)
    coeffs = (tmp_path / "run" / "pillow.units.in").read_text()
    weak = [l for l in coeffs.splitlines() if l.startswith("pair_coeff 4 4 ")][0].split()
    cross = [l for l in coeffs.splitlines() if l.startswith("pair_coeff 1 4 ")][0].split()
    assert float(weak[6]) == pytest.approx(0.3)          # mu of the weak unit
    assert float(cross[6]) == pytest.approx(0.3)         # the weaker friction at the interface
    assert float(weak[7]) == pytest.approx(7e7 * 100 / 6.25)   # cohesion x rscale_cover (tiny)
    assert float(cross[7]) == pytest.approx(7e7 * 100 / 6.25)


def test_a_restart_file_of_another_deck_is_refused(tmp_path):
    """expt1.in's restart file holds the drive of its fix 'fault'; the section deck's motion fix
    is 'blocks': resuming it there would start the drive again, so the deck stops."""
    wd = tmp_path / "run"
    r = run_deck(ROOT / "examples" / "expt1.in", wd, "-var", "restart_disp", "0.5")
    assert r.returncode == 0, r.stdout[-2000:]
    newest = max(wd.glob("expt1.restart.[ab]"), key=lambda p: p.stat().st_mtime)
    d = write_deck(ROOT / "examples" / "sections" / "expt1.toml", tmp_path / "s.in")
    r = run_deck(d, wd, "-var", "restart", newest.name)
    assert r.returncode == 1
    assert "holds no drive displacement for the motion fix of this deck" in r.stdout
    assert "scene: the restart file" in r.stdout and "Unmatched" not in r.stdout


def test_the_how_to_example_is_the_staircase_section():
    """docs/sections.md's worked example is examples/sections/staircase.toml (the same section)."""
    import re
    import tomllib
    doc = (ROOT / "docs" / "sections.md").read_text()
    block = re.search(r"   ```toml\n(.*?)   ```", doc, re.S).group(1)
    text = "\n".join(l[3:] for l in block.splitlines())
    shown = tomllib.loads(text)
    real = tomllib.loads((ROOT / "examples" / "sections" / "staircase.toml").read_text())
    real.pop("title", None)
    assert shown == real
    assert deck(parse(text, "my_basin.toml")).splitlines()[20:] == \
        deck(parse((ROOT / "examples" / "sections" / "staircase.toml").read_text(),
                   "staircase.toml")).splitlines()[20:]
