"""3D slabs: sections along strike and the map view of the cover's top, on a synthetic slab
(the 2D synthetic scene extruded along z) with known answers."""

import json

import numpy as np
import pytest
from matplotlib.image import imread

from saltdem_post.cli import main
from saltdem_post.dump import Box, Frame, read_frame, write_dump
from saltdem_post.slab import default_width, map_view, section_at
from saltdem_post.synthetic import COVER, SALT, SceneSpec, reference_scene

SPEC = SceneSpec(width=1000.0, salt_thickness=120.0, cover_thickness=150.0)
A = 2.0 * SPEC.r_max          # spacing of the planes along z
NZ = 8
DEPTH = NZ * A
COLUMNS_2D = ["id", "type", "x", "y", "vx", "vy", "radius", "i_marker"]


def slab(periodic: bool = True) -> Frame:
    """NZ copies of the 2D scene at z = (k + 1/2) A (+- 0.1 A of jitter), odd ones shifted by
    A/2 in x, in a box from z = 0 to DEPTH, periodic in z or not."""
    sec = reference_scene(SPEC)
    rng = np.random.default_rng(7)
    parts = []
    for k in range(NZ):
        d = dict(sec.data)
        d["id"] = sec.ids + k * sec.natoms
        d["x"] = sec.x + (0.5 * A if k % 2 else 0.0)
        d["z"] = (k + 0.5) * A + rng.uniform(-0.1, 0.1, sec.natoms) * A
        d["vz"] = np.zeros(sec.natoms)
        d["radius"] = rng.uniform(0.8, 1.0, sec.natoms) * SPEC.r_max
        parts.append(d)
    order = ["id", "type", "x", "y", "z", "vx", "vy", "vz", "radius", "i_marker"]
    data = {c: np.concatenate([p[c] for p in parts]) for c in order}
    box = Box(np.array([0.0, sec.box.lo[1], 0.0]), np.array([SPEC.width + A, sec.box.hi[1], DEPTH]),
              boundary=("ff", "ff", "pp" if periodic else "ff"))
    return Frame(0, box, data)


def moved(frame: Frame, x=None, z=None, y=None, timestep: int = 100) -> Frame:
    data = dict(frame.data)
    for name, v in (("x", x), ("y", y), ("z", z)):
        if v is not None:
            data[name] = np.asarray(v, float)
    return Frame(timestep, frame.box, data)


def plane_ids(frame: Frame, k: int) -> np.ndarray:
    return np.sort(frame.ids[np.abs(frame["z"] - (k + 0.5) * A) < 0.2 * A])


# ------------------------------------------------------------------ sections

def test_section_is_one_plane_as_a_2d_frame():
    f = slab()
    sec = section_at(f, 3.5 * A)
    assert default_width(f) == pytest.approx(2 * np.median(f.radius))
    assert sec.columns == COLUMNS_2D
    np.testing.assert_array_equal(np.sort(sec.ids), plane_ids(f, 3))
    ref = f.subset(np.isin(f.ids, sec.ids)).sorted_by_id()
    s = sec.sorted_by_id()
    for c in ("x", "y", "radius", "type", "i_marker"):
        np.testing.assert_array_equal(s[c], ref[c])
    assert (sec.box.lo[2], sec.box.hi[2]) == pytest.approx((3.5 * A - 0.5 * default_width(f),
                                                            3.5 * A + 0.5 * default_width(f)))
    with pytest.raises(KeyError):
        sec["z"]


@pytest.mark.parametrize("z0", [0.0, 1e-6, DEPTH])
def test_section_wraps_across_a_periodic_z(z0):
    f = slab()
    sec = section_at(f, z0, width=1.5 * A)     # planes 0 and NZ-1 lie 0.5 A (+- 0.1 A) away, the next 1.5 A
    expected = np.sort(np.concatenate([plane_ids(f, 0), plane_ids(f, NZ - 1)]))
    np.testing.assert_array_equal(np.sort(sec.ids), expected)


def test_section_does_not_wrap_a_closed_z():
    f = slab(periodic=False)
    np.testing.assert_array_equal(np.sort(section_at(f, 0.0, 1.5 * A).ids), plane_ids(f, 0))
    np.testing.assert_array_equal(np.sort(section_at(f, DEPTH, 1.5 * A).ids), plane_ids(f, NZ - 1))


def test_section_errors():
    f = slab()
    with pytest.raises(ValueError, match="no z column"):
        section_at(reference_scene(SPEC), 0.0)
    for z0 in (-1.0, DEPTH + 1.0):
        with pytest.raises(ValueError, match="outside the box"):
            section_at(f, z0)
    for w in (0.0, -10.0):
        with pytest.raises(ValueError, match="positive width"):
            section_at(f, 100.0, w)


# ------------------------------------------------------------------ map view

def finite(v):
    return v[np.isfinite(v)]


def check_rigid(view):
    """Zero strain wherever the top layer defines one (most cells)."""
    assert finite(view["dilatation"]).size >= 0.8 * view["dilatation"].size
    assert np.abs(finite(view["dilatation"])).max() < 1e-9
    assert np.abs(finite(view["shear"])).max() < 1e-9


def test_map_view_uniform_stretch():
    f = slab()
    cur = moved(f, x=500.0 + 1.02 * (f.x - 500.0))
    v = map_view(f, cur)
    nz, nx = v["dilatation"].shape
    assert (len(v["z"]), len(v["x"])) == (nz, nx) and nz * v["cell"][1] == pytest.approx(DEPTH)
    assert v["cell"][0] == pytest.approx(4 * np.median(f.radius[f["type"] == COVER]))
    dil, shear = finite(v["dilatation"]), finite(v["shear"])
    assert dil.size >= 0.8 * nz * nx and dil.size == shear.size
    np.testing.assert_allclose(dil, 0.02, atol=1e-6)      # det F - 1
    np.testing.assert_allclose(shear, 0.01, atol=1e-6)    # (S1 - S2) / 2 of diag(1.02, 1)
    assert v["n_top"].max() >= 6


def test_map_view_simple_shear_along_strike():
    f = slab(periodic=False)                             # a shear along z does not fit a periodic box
    v = map_view(f, moved(f, x=f.x + 0.02 * (f["z"] - 0.5 * DEPTH)))
    np.testing.assert_allclose(finite(v["dilatation"]), 0.0, atol=1e-9)
    np.testing.assert_allclose(finite(v["shear"]), 0.01, atol=1e-9)      # gamma / 2 for simple shear


def test_map_view_rigid_translation_across_the_periodic_boundary():
    f = slab()
    cur = moved(f, x=f.x + 37.0, z=np.mod(f["z"] + 0.3 * DEPTH, DEPTH))   # 30 % of the spheres wrap
    check_rigid(map_view(f, cur))


def test_map_view_rigid_rotation_about_y():
    f = slab(periodic=False)
    t, xc, zc = np.radians(10.0), 500.0, 0.5 * DEPTH
    dx, dz = f.x - xc, f["z"] - zc
    cur = moved(f, x=xc + np.cos(t) * dx + np.sin(t) * dz, z=zc - np.sin(t) * dx + np.cos(t) * dz)
    check_rigid(map_view(f, cur))


def test_map_view_graben_shows_in_the_top():
    f = slab()
    strip = (f["type"] == COVER) & (f.x > 400.0) & (f.x < 600.0)
    v = map_view(f, moved(f, y=f.y - 100.0 * strip))
    half = 0.5 * v["cell"][0]
    inside = (v["x"] - half > 400.0) & (v["x"] + half < 600.0)
    outside = (v["x"] + half < 400.0) | (v["x"] - half > 600.0)
    assert inside.sum() >= 1 and outside.sum() >= 4
    np.testing.assert_allclose(v["uplift"][:, inside], -100.0, atol=1e-9)
    np.testing.assert_allclose(finite(v["uplift"][:, outside]), 0.0, atol=1e-9)
    np.testing.assert_allclose(finite(v["dilatation"]), 0.0, atol=1e-9)   # no horizontal motion
    assert np.nanmax(v["top"] - v["top_ref"]) == pytest.approx(0.0, abs=1e-9)


def test_map_view_salt_flow_along_strike_and_thickness():
    """The salt moves 20 m along +z and, in a strip, its upper half rises 30 m: the map shows
    20 m along strike wherever there is salt and +30 m of thickness in the strip only; the
    cover is untouched."""
    f = slab(periodic=False)
    salt = f["type"] == SALT
    ymid = np.median(f.y[salt])
    strip = salt & (f.x > 400.0) & (f.x < 600.0) & (f.y > ymid)
    v = map_view(f, moved(f, z=f["z"] + 20.0 * salt, y=f.y + 30.0 * strip))
    has = np.isfinite(v["salt_thickness_ref"])
    assert has.sum() >= 0.8 * has.size
    np.testing.assert_allclose(v["salt_dz"][has], 20.0, atol=1e-9)
    half = 0.5 * v["cell"][0]
    inside = (v["x"] - half > 400.0) & (v["x"] + half < 600.0)
    outside = (v["x"] + half < 400.0) | (v["x"] - half > 600.0)
    assert inside.sum() >= 1
    np.testing.assert_allclose(finite(v["salt_dthick"][:, inside]), 30.0, atol=1e-9)
    np.testing.assert_allclose(finite(v["salt_dthick"][:, outside]), 0.0, atol=1e-9)
    np.testing.assert_allclose(finite(v["uplift"]), 0.0, atol=1e-9)
    check_rigid(v)


# ----------------------------------------------------------------------- CLI

def run(capsys, *argv):
    rc = main([str(a) for a in argv])
    out = capsys.readouterr()
    assert rc == 0, out.err
    return out.out


def test_cli_section3d_and_mapview(capsys, tmp_path):
    ref = slab()
    cur = moved(ref, x=500.0 + 1.02 * (ref.x - 500.0))
    write_dump(tmp_path / "dump.slab.0.txt", [ref])
    write_dump(tmp_path / "dump.slab.100.txt", [cur])
    out = run(capsys, "section3d", tmp_path / "dump.slab.*.txt", "--z", 3.5 * A, 0, "-o", tmp_path / "sec", "-q")
    assert len(out.strip().splitlines()) == 4
    for step, frame in ((0, ref), (100, cur)):
        for z in (3.5 * A, 0.0):
            path = tmp_path / "sec" / f"dump.slab.{step}_z{z:g}.txt"
            back = read_frame(str(path))
            assert back.columns == COLUMNS_2D and back.timestep == step
            np.testing.assert_array_equal(np.sort(back.ids), np.sort(section_at(frame, z).ids))
            np.testing.assert_allclose(back.sorted_by_id().x, section_at(frame, z).sorted_by_id().x, rtol=1e-9)

    # a 2D tool on the sections: the 2 % stretch along x, as the equivalent simple shear
    run(capsys, "strain", tmp_path / "sec" / "dump.slab.*_z175.txt", "--no-csv", "-q", "-o", tmp_path / "strain")
    summary = json.loads((tmp_path / "strain" / "strain_summary.json").read_text())[0]
    assert summary["dilatation"]["median"] == pytest.approx(0.02, abs=1e-6)
    assert summary["max_shear"]["median"] == pytest.approx(0.02 / np.sqrt(1.02), abs=1e-6)

    # several frames in one file: one name per frame
    write_dump(tmp_path / "dump.both.txt", [ref, cur])
    run(capsys, "section3d", tmp_path / "dump.both.txt", "--z", 3.5 * A, "-o", tmp_path / "both", "-q")
    assert sorted(p.name for p in (tmp_path / "both").iterdir()) == ["dump.both_0_z175.txt",
                                                                     "dump.both_100_z175.txt"]

    png, js = tmp_path / "map" / "m.png", tmp_path / "m.json"
    out = run(capsys, "mapview", tmp_path / "dump.slab.0.txt", tmp_path / "dump.slab.100.txt", "-o", png,
              "--json", js)
    assert str(png) in out
    img = imread(str(png))
    assert img.shape[0] > 200 and img.shape[1] > 400 and np.any(img[..., :3] < 0.9)
    info = json.loads(js.read_text())
    assert info["range"]["dilatation"] == pytest.approx([0.02, 0.02], abs=1e-6)
    assert info["range"]["shear"] == pytest.approx([0.01, 0.01], abs=1e-6)
    assert np.shape(info["uplift"]) == (len(info["z"]), len(info["x"]))


def test_cli_section3d_refuses_a_2d_dump(capsys, tmp_path):
    write_dump(tmp_path / "flat.txt", [reference_scene(SPEC)])
    assert main(["section3d", str(tmp_path / "flat.txt"), "--z", "0", "-o", str(tmp_path)]) == 2
    assert "no z column" in capsys.readouterr().err
