"""Dump reader: formats, frame selection, streaming, progress."""

import gzip
import io

import numpy as np
import pytest

from saltdem_post.dump import (Box, DumpFormatError, FrameSelection, expand_paths, iter_frames,
                               read_frame, scan_frames, write_dump)
from saltdem_post.progress import Progress


def _frames(make_frame, n_frames=3, n=50):
    rng = np.random.default_rng(0)
    out = []
    for k in range(n_frames):
        xy = rng.uniform(0, 1000, (n, 2))
        # columns deliberately not in the usual order
        f = make_frame(xy, radius=rng.uniform(5, 10, n), timestep=1000 * k,
                       vx=rng.normal(size=n), i_marker=rng.integers(0, 9, n))
        f.data = {c: f.data[c] for c in ("radius", "i_marker", "y", "id", "vx", "x", "type")}
        out.append(f)
    return out


@pytest.mark.parametrize("name", ["run.dump", "run.dump.gz"])
def test_roundtrip_multiframe(tmp_path, make_frame, name):
    frames = _frames(make_frame)
    path = tmp_path / name
    write_dump(path, frames)
    if name.endswith(".gz"):
        assert path.read_bytes()[:2] == b"\x1f\x8b"
    back = list(iter_frames(str(path)))
    assert [f.timestep for f in back] == [0, 1000, 2000]
    assert [f.index for f in back] == [0, 1, 2]
    for a, b in zip(frames, back):
        assert b.columns == a.columns                      # order as written, read by name
        for c in a.columns:
            np.testing.assert_allclose(b[c], a[c], rtol=1e-9)
        assert b["id"].dtype.kind == "i" and b["type"].dtype.kind == "i" and b["i_marker"].dtype.kind == "i"
        assert b["vx"].dtype.kind == "f"
        np.testing.assert_array_equal(b.box.lo, a.box.lo)


def test_one_file_per_frame_natural_order(tmp_path, make_frame):
    frames = _frames(make_frame, n_frames=3)
    for f, step in zip(frames, (0, 500, 10000)):
        f.timestep = step
        write_dump(tmp_path / f"dump.{step}.txt", [f])
    # lexical order would put dump.10000 before dump.500
    paths = expand_paths([str(tmp_path / "dump.*.txt")])
    assert [p.rsplit("/", 1)[1] for p in paths] == ["dump.0.txt", "dump.500.txt", "dump.10000.txt"]
    assert [f.timestep for f in iter_frames(str(tmp_path / "dump.*.txt"))] == [0, 500, 10000]
    with pytest.raises(FileNotFoundError):
        expand_paths([str(tmp_path / "nothing.*")])
    # the shell's expansion of the glob (lexical) comes out in the same order
    shell = sorted(str(tmp_path / f"dump.{s}.txt") for s in (0, 500, 10000))
    assert [p.rsplit("/", 1)[1] for p in shell] == ["dump.0.txt", "dump.10000.txt", "dump.500.txt"]
    assert expand_paths(shell) == paths


TRICLINIC = """ITEM: UNITS
si
ITEM: TIME
12.5
ITEM: TIMESTEP
7
ITEM: NUMBER OF ATOMS
2
ITEM: BOX BOUNDS xy xz yz pp ff pp
-10 110 10
0 50 0
-0.5 0.5 0
ITEM: ATOMS id type xs ys element
1 1 0.5 0.5 Si
2 2 0 1 C
"""


def test_triclinic_box_scaled_coordinates_and_text_column(tmp_path):
    path = tmp_path / "tri.dump"
    path.write_text(TRICLINIC)
    f = read_frame(str(path))
    assert f.timestep == 7 and f.time == 12.5 and f.natoms == 2
    # bounding box -10..110 with xy = 10 -> xlo = -10 - min(0, 10) = -10, xhi = 110 - 10 = 100
    np.testing.assert_allclose(f.box.lo[:2], [-10, 0])
    np.testing.assert_allclose(f.box.hi[:2], [100, 50])
    np.testing.assert_allclose(f.box.tilt, [10, 0, 0])
    assert f.box.periodic == (True, False, True) and f.box.triclinic
    # x = xlo + xs*lx + ys*xy, y = ylo + ys*ly
    np.testing.assert_allclose(f.x, [-10 + 55 + 5, -10 + 0 + 10])
    np.testing.assert_allclose(f.y, [25, 50])
    assert list(f["element"]) == ["Si", "C"]
    # the writer emits the same bounding-box convention
    assert [float(v) for v in f.box.header_lines()[1].split()] == [-10, 110, 10]


def test_frame_selection(tmp_path, make_frame):
    frames = _frames(make_frame, n_frames=5, n=10)
    path = str(tmp_path / "run.dump.gz")
    write_dump(path, frames)
    steps = lambda sel: [f.timestep for f in iter_frames(path, sel)]  # noqa: E731
    assert steps(FrameSelection(["-1"])) == [4000]
    assert steps(FrameSelection(["0", "-2"])) == [0, 3000]
    assert steps(FrameSelection(["::2"])) == [0, 2000, 4000]
    assert steps(FrameSelection(["1:3"])) == [1000, 2000]
    assert steps(FrameSelection(timesteps=[3000])) == [3000]
    assert steps(FrameSelection(["all"])) == [0, 1000, 2000, 3000, 4000]
    assert read_frame(path, -1).timestep == 4000
    with pytest.raises(IndexError):
        read_frame(path, 9)
    headers = scan_frames([path])
    assert [h.timestep for h in headers] == [0, 1000, 2000, 3000, 4000]
    assert all(h.natoms == 10 for h in headers)


def test_selection_stops_early_without_reading_rest(tmp_path, make_frame):
    frames = _frames(make_frame, n_frames=2, n=5)
    path = tmp_path / "run.dump"
    write_dump(path, frames)
    with open(path, "a") as fh:
        fh.write("garbage that would fail to parse\n")
    assert [f.timestep for f in iter_frames(str(path), FrameSelection(["0"]))] == [0]
    with pytest.raises(DumpFormatError):
        list(iter_frames(str(path)))


def test_truncated_last_frame_is_dropped_with_warning(tmp_path, make_frame):
    frames = _frames(make_frame, n_frames=2, n=20)
    buf = io.StringIO()
    write_dump(buf, frames)
    text = buf.getvalue()
    path = tmp_path / "running.dump.gz"
    with gzip.open(path, "wt") as fh:
        fh.write(text[: len(text) - 200])           # a run still writing its second frame
    with pytest.warns(UserWarning, match="truncated"):
        got = list(iter_frames(str(path)))
    assert [f.timestep for f in got] == [0]


def test_progress_reports_frames_and_eta(tmp_path, make_frame):
    path = str(tmp_path / "run.dump")
    write_dump(path, _frames(make_frame, n_frames=3, n=10))
    stream = io.StringIO()
    prog = Progress("test", stream=stream, interval=0.0)
    list(iter_frames(path, FrameSelection(["1"]), progress=prog))
    out = stream.getvalue()
    assert "test: 1 frames (0 parsed)" in out and "ETA" in out
    assert "2 frames (1 parsed)" in out                 # stopped after the selected frame
    prog = Progress("all", stream=stream, interval=0.0)
    list(iter_frames(path, progress=prog))
    assert "all: 3 frames (3 parsed) 100%" in stream.getvalue()


def test_box_write_read_triclinic_roundtrip(tmp_path, make_frame):
    f = make_frame([[0.0, 0.0], [10.0, 5.0]])
    f.box = Box(np.array([0.0, 0.0, -0.5]), np.array([100.0, 40.0, 0.5]), np.array([-7.0, 0.0, 0.0]),
                ("pp", "ff", "pp"))
    write_dump(tmp_path / "t.dump", [f])
    g = read_frame(str(tmp_path / "t.dump"))
    np.testing.assert_allclose(g.box.lo, f.box.lo)
    np.testing.assert_allclose(g.box.hi, f.box.hi)
    np.testing.assert_allclose(g.box.tilt, f.box.tilt)
    assert g.box.boundary == ("pp", "ff", "pp")


def test_progress_on_a_terminal_redraws_one_line():
    class Tty(io.StringIO):
        def isatty(self):
            return True
    stream = Tty()
    prog = Progress("job", stream=stream, interval=0.0)
    prog.start(1000)
    prog.update(500, label="step 10")
    prog.finish()
    out = stream.getvalue()
    assert out.startswith("\rjob: 1 frames (1 parsed)  50% ETA") and "[step 10]" in out
    assert out.endswith("\n") and out.count("\n") == 1
