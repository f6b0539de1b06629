"""Reading SaltDEM's LAMMPS output files: the package's one I/O module.

* ``dump custom`` text files: a streaming reader and a small writer.  Frames
  are read one at a time, so a run of any length only ever holds the frames
  the caller keeps.  Files may be gzip-compressed (detected from the magic
  bytes, not the name), hold several frames, or be one file per frame
  (``dump.*.txt``, sorted by the numbers in their names).  Columns are looked
  up by name, in whatever order the deck wrote them.
* ``fix ave/chunk`` and ``fix ave/time`` files (the calibration and channel
  decks' profiles and time series): ``read_ave_chunk``, ``read_ave_time``,
  gzip-compressed or not.
"""

from __future__ import annotations

import glob
import gzip
import io
import os
import re
import warnings
from dataclasses import dataclass, field
from itertools import islice
from typing import Dict, Iterable, Iterator, List, Optional, Sequence

import numpy as np

from .selection import FrameSelection

__all__ = [
    "Box", "Frame", "FrameHeader", "DumpFormatError", "expand_paths",
    "iter_frames", "scan_frames", "read_frame", "write_dump", "FrameSelection",
    "match_ids", "read_ave_chunk", "read_ave_time",
]


class DumpFormatError(ValueError):
    """The file is not a LAMMPS text dump (or ave/chunk, ave/time file) we understand."""


# Columns LAMMPS writes as integers; custom integer properties are ``i_*``.
_INT_COLUMNS = {"id", "type", "mol", "proc", "procp1", "ix", "iy", "iz"}


def _is_int_column(name: str) -> bool:
    return name in _INT_COLUMNS or name.startswith(("i_", "i2_"))


@dataclass
class Box:
    """Simulation box: orthogonal bounds plus tilt factors (xy, xz, yz)."""

    lo: np.ndarray
    hi: np.ndarray
    tilt: np.ndarray = field(default_factory=lambda: np.zeros(3))
    boundary: tuple = ("pp", "pp", "pp")

    @property
    def length(self) -> np.ndarray:
        return self.hi - self.lo

    @property
    def periodic(self) -> tuple:
        return tuple(b == "pp" for b in self.boundary)

    @property
    def triclinic(self) -> bool:
        return bool(np.any(self.tilt != 0.0))

    def header_lines(self) -> List[str]:
        """The ``ITEM: BOX BOUNDS`` block as LAMMPS would write it."""
        flags = " ".join(self.boundary)

        def row(*values):                   # repr: shortest exact round-trip
            return " ".join(repr(float(v)) for v in values)
        if not self.triclinic:
            return [f"ITEM: BOX BOUNDS {flags}"] + [row(lo, hi) for lo, hi in zip(self.lo, self.hi)]
        xy, xz, yz = self.tilt
        # LAMMPS writes the bounding box of the tilted cell, not lo/hi.
        return [f"ITEM: BOX BOUNDS xy xz yz {flags}",
                row(self.lo[0] + min(0.0, xy, xz, xy + xz), self.hi[0] + max(0.0, xy, xz, xy + xz), xy),
                row(self.lo[1] + min(0.0, yz), self.hi[1] + max(0.0, yz), xz),
                row(self.lo[2], self.hi[2], yz)]

    def to_dict(self) -> dict:
        return {"lo": self.lo.tolist(), "hi": self.hi.tolist(),
                "tilt": self.tilt.tolist(), "boundary": list(self.boundary)}


@dataclass
class FrameHeader:
    timestep: int
    natoms: int
    box: Box
    columns: List[str]
    path: str
    index: int = 0          # position in the whole sequence of files
    time: Optional[float] = None


@dataclass
class Frame:
    """One dump frame: header plus a dict of per-atom column arrays."""

    timestep: int
    box: Box
    data: Dict[str, np.ndarray]
    path: str = ""
    index: int = 0
    time: Optional[float] = None

    @property
    def natoms(self) -> int:
        return len(next(iter(self.data.values()))) if self.data else 0

    @property
    def columns(self) -> List[str]:
        return list(self.data)

    def __contains__(self, name: str) -> bool:
        return name in self.data

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self.data[name]
        except KeyError:
            raise KeyError(f"column {name!r} not in dump (has: {' '.join(self.data)})") from None

    def _coord(self, axis: int) -> np.ndarray:
        c = "xyz"[axis]
        for name in (c, c + "u"):
            if name in self.data:
                return self.data[name].astype(float)
        for name in (c + "s", c + "su"):
            if name in self.data:
                return self._unscale(axis)
        raise KeyError(f"no {c} coordinate column (x, xu, xs or xsu) in dump")

    def _unscale(self, axis: int) -> np.ndarray:
        def s(a):
            c = "xyz"[a]
            col = self.data.get(c + "s", self.data.get(c + "su"))
            return np.zeros(self.natoms) if col is None else col
        L, xy, xz, yz = self.box.length, *self.box.tilt
        if axis == 0:
            return self.box.lo[0] + s(0) * L[0] + s(1) * xy + s(2) * xz
        if axis == 1:
            return self.box.lo[1] + s(1) * L[1] + s(2) * yz
        return self.box.lo[2] + s(2) * L[2]

    @property
    def x(self) -> np.ndarray:
        return self._coord(0)

    @property
    def y(self) -> np.ndarray:
        return self._coord(1)

    @property
    def xy(self) -> np.ndarray:
        return np.column_stack([self.x, self.y])

    @property
    def radius(self) -> np.ndarray:
        if "radius" in self.data:
            return self.data["radius"].astype(float)
        if "diameter" in self.data:
            return 0.5 * self.data["diameter"].astype(float)
        raise KeyError("dump has neither a 'radius' nor a 'diameter' column")

    @property
    def ids(self) -> np.ndarray:
        return self["id"]

    def subset(self, mask: np.ndarray) -> "Frame":
        return Frame(self.timestep, self.box, {k: v[mask] for k, v in self.data.items()},
                     self.path, self.index, self.time)

    def sorted_by_id(self) -> "Frame":
        return self.subset(np.argsort(self.ids, kind="stable"))


def match_ids(ids_a: np.ndarray, ids_b: np.ndarray):
    """Indices ``(ia, ib)`` with ``ids_a[ia] == ids_b[ib]``, for atoms in both."""
    _, ia, ib = np.intersect1d(ids_a, ids_b, assume_unique=True, return_indices=True)
    return ia, ib


# --------------------------------------------------------------------- paths

def _natural_key(path: str):
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", path)]


def expand_paths(patterns: Iterable[str]) -> List[str]:
    """Expand globs (``dump.*.txt``) and sort by the numbers in the names, so that
    ``dump.1000.txt`` follows ``dump.200.txt``: the frames of a run in the order of their
    steps, whether the program or the shell expanded the glob (the shell sorts
    ``dump.100280.txt`` before ``dump.6000.txt``).
    """
    out: List[str] = []
    for pat in patterns:
        if os.path.exists(pat):
            out.append(pat)
            continue
        matches = glob.glob(pat)
        if not matches:
            raise FileNotFoundError(f"no dump file matches {pat!r}")
        out.extend(matches)
    return sorted(dict.fromkeys(out), key=_natural_key)


class _Source:
    """An open dump file; ``raw_pos`` is the on-disk (compressed) position,
    which is what the progress display measures."""

    def __init__(self, path: str):
        self.path = path
        self.raw = open(path, "rb")
        magic = self.raw.read(2)
        self.raw.seek(0)
        self.fh = (io.BufferedReader(gzip.GzipFile(fileobj=self.raw), 1 << 20)
                   if magic == b"\x1f\x8b" else self.raw)

    @property
    def raw_pos(self) -> int:
        return self.raw.tell()

    def close(self):
        self.fh.close()
        self.raw.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


# -------------------------------------------------------------------- header

_BOUNDARY = re.compile(rb"^[pfsm]{2}$")


def _parse_box(item: bytes, fh, path: str) -> Box:
    tokens = item.split()[2:]                      # after "BOX BOUNDS"
    if b"abc" in tokens:
        raise DumpFormatError(f"{path}: general triclinic boxes ('abc origin') are not supported")
    triclinic = b"xy" in tokens
    flags = tuple(t.decode() for t in tokens if _BOUNDARY.match(t)) or ("pp", "pp", "pp")
    rows = []
    for _ in range(3):
        vals = fh.readline().split()
        if len(vals) < (3 if triclinic else 2):
            raise DumpFormatError(f"{path}: malformed BOX BOUNDS line")
        rows.append([float(v) for v in vals])
    rows = np.array([r[:3] if triclinic else r[:2] + [0.0] for r in rows])
    lo, hi, tilt = rows[:, 0].copy(), rows[:, 1].copy(), np.zeros(3)
    if triclinic:
        xy, xz, yz = tilt[:] = rows[:, 2]
        lo[0] -= min(0.0, xy, xz, xy + xz)
        hi[0] -= max(0.0, xy, xz, xy + xz)
        lo[1] -= min(0.0, yz)
        hi[1] -= max(0.0, yz)
    return Box(lo, hi, tilt, flags)


def _read_header(fh, path: str) -> Optional[FrameHeader]:
    """Read ITEM blocks up to and including ``ITEM: ATOMS``; None at EOF."""
    timestep = natoms = box = time = None
    started = False
    while True:
        line = fh.readline()
        if not line:
            if started:
                warnings.warn(f"{path}: file ends inside a frame header; ignoring the partial frame")
            return None
        line = line.strip()
        if not line:
            continue
        if not line.startswith(b"ITEM:"):
            raise DumpFormatError(f"{path}: expected an 'ITEM:' line, got {line[:60]!r}")
        started = True
        item = line[5:].strip()
        if item.startswith(b"TIMESTEP"):
            timestep = int(fh.readline())
        elif item.startswith(b"NUMBER OF ATOMS"):
            natoms = int(fh.readline())
        elif item.startswith(b"BOX BOUNDS"):
            box = _parse_box(item, fh, path)
        elif item.startswith(b"TIME"):
            time = float(fh.readline())
        elif item.startswith(b"UNITS"):
            fh.readline()
        elif item.startswith(b"ATOMS"):
            if timestep is None or natoms is None or box is None:
                raise DumpFormatError(f"{path}: ATOMS block before TIMESTEP/NUMBER OF ATOMS/BOX BOUNDS")
            columns = [c.decode() for c in item.split()[1:]]
            return FrameHeader(timestep, natoms, box, columns, path, time=time)
        else:
            raise DumpFormatError(f"{path}: unknown dump item {item[:40]!r} (only text 'dump custom/atom' is supported)")


def _skip_atoms(fh, n: int) -> bool:
    """Skip ``n`` atom lines; False if the file ended early."""
    skipped = sum(1 for _ in islice(fh, n))
    return skipped == n


def _read_atoms(fh, header: FrameHeader) -> Optional[Dict[str, np.ndarray]]:
    n, ncol = header.natoms, len(header.columns)
    lines = list(islice(fh, n))
    if len(lines) < n or (lines and not lines[-1].endswith(b"\n")):
        return None                                   # truncated (run still writing)
    blob = b"".join(lines)
    # One C-level parse of the whole block; fall back to per-token parsing only
    # if some column is not numeric (e.g. an 'element' string column).
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        values = np.fromstring(blob, dtype=float, sep=" ") if n else np.empty(0)
    if values.size == n * ncol:
        table = values.reshape(n, ncol)
        cols = [table[:, k] for k in range(ncol)]
    else:
        rows = [ln.split() for ln in lines]
        if any(len(r) != ncol for r in rows):
            raise DumpFormatError(f"{header.path}: timestep {header.timestep}: atom lines do not have {ncol} columns")
        cols = []
        for k in range(ncol):
            raw = [r[k] for r in rows]
            try:
                cols.append(np.array(raw, dtype=float))
            except ValueError:
                cols.append(np.array([v.decode() for v in raw]))
    data = {}
    for name, col in zip(header.columns, cols):
        if _is_int_column(name) and col.dtype.kind == "f":
            col = np.rint(col).astype(np.int64)
        data[name] = np.ascontiguousarray(col)
    return data


# ------------------------------------------------------------------ iterating

def scan_frames(paths: Sequence[str], progress=None) -> List[FrameHeader]:
    """Headers of every frame, skipping atom data without parsing it."""
    headers = []
    for _, header in _walk(expand_paths(paths), lambda i, t: False, None, progress):
        headers.append(header)
    return headers


def _walk(paths, wanted, last, progress):
    """Yield (Frame or None, header) for every frame; only wanted ones parsed."""
    index = 0
    total_bytes = sum(os.path.getsize(p) for p in paths)
    done_bytes = 0
    if progress is not None:
        progress.start(total_bytes)
    for path in paths:
        with _Source(path) as src:
            while True:
                header = _read_header(src.fh, path)
                if header is None:
                    break
                header.index = index
                if wanted(index, header.timestep):
                    data = _read_atoms(src.fh, header)
                    if data is None:
                        warnings.warn(f"{path}: frame at timestep {header.timestep} is truncated; stopping there")
                        return
                    frame = Frame(header.timestep, header.box, data, path, index, header.time)
                else:
                    if not _skip_atoms(src.fh, header.natoms):
                        warnings.warn(f"{path}: frame at timestep {header.timestep} is truncated; stopping there")
                        return
                    frame = None
                if progress is not None:
                    progress.update(done_bytes + src.raw_pos, parsed=frame is not None,
                                    label=f"step {header.timestep}")
                yield frame, header
                index += 1
                if last is not None and index > last:
                    if progress is not None:
                        progress.finish()
                    return
        done_bytes += os.path.getsize(path)
    if progress is not None:
        progress.finish()


def iter_frames(paths, selection: Optional[FrameSelection] = None, progress=None) -> Iterator[Frame]:
    """Yield the selected frames one by one, in file order.

    ``paths`` is a path, a glob, or a list of them.  Frames that are not
    selected are skipped line by line without being parsed; reading stops as
    soon as the last selected index has been read.
    """
    paths = expand_paths([paths] if isinstance(paths, (str, os.PathLike)) else list(paths))
    selection = selection or FrameSelection()
    n = len(scan_frames(paths)) if selection.needs_count else None
    wanted, last = selection.predicate(n)
    for frame, _ in _walk(paths, wanted, last, progress):
        if frame is not None:
            yield frame


def read_frame(paths, index: int = 0) -> Frame:
    """Read a single frame by index (negative counts from the end)."""
    frames = list(iter_frames(paths, FrameSelection([index])))
    if not frames:
        raise IndexError(f"no frame {index} in {paths}")
    return frames[0]


# -------------------------------------------------------------------- writing

def _format_column(col: np.ndarray) -> List[str]:
    if col.dtype.kind in "iub":
        return [str(v) for v in col.tolist()]
    if col.dtype.kind == "f":
        return [f"{v:.10g}" for v in col.tolist()]
    return [str(v) for v in col.tolist()]


def write_dump(path_or_file, frames: Iterable[Frame], append: bool = False) -> None:
    """Write frames in LAMMPS ``dump custom`` text format (gzip if ``*.gz``);
    frames with a ``time`` get an ``ITEM: TIME`` block."""
    def emit(fh):
        for fr in frames:
            cols = list(fr.data)
            time = [] if fr.time is None else [f"ITEM: TIME\n{float(fr.time)!r}"]   # as dump_modify time yes
            lines = [*time, f"ITEM: TIMESTEP\n{fr.timestep}", f"ITEM: NUMBER OF ATOMS\n{fr.natoms}",
                     *fr.box.header_lines(), "ITEM: ATOMS " + " ".join(cols)]
            fh.write("\n".join(lines) + "\n")
            text = [_format_column(fr.data[c]) for c in cols]
            fh.writelines(" ".join(row) + "\n" for row in zip(*text))

    if hasattr(path_or_file, "write"):
        emit(path_or_file)
        return
    mode = "at" if append else "wt"
    path = str(path_or_file)
    if path.endswith(".gz"):
        # mtime=0 keeps the compressed bytes reproducible (test fixtures).
        with open(path, mode.replace("t", "b")) as raw, \
                gzip.GzipFile(fileobj=raw, mode="wb", mtime=0) as gz, \
                io.TextIOWrapper(gz, encoding="ascii") as fh:
            emit(fh)
    else:
        with open(path, mode, encoding="ascii") as fh:
            emit(fh)


# ----------------------------------------------------- fix ave/chunk, ave/time

def _ave_rows(path):
    """(line number, fields) of the non-comment, non-blank lines of a fix ave/* file."""
    with _Source(str(path)) as src:
        for n, line in enumerate(src.fh, 1):
            s = line.split()
            if s and not s[0].startswith(b"#"):
                yield n, s


def read_ave_chunk(path) -> List[np.ndarray]:
    """Blocks of a ``fix ave/chunk`` file, oldest first: one array per output
    step with a row ``[Chunk Coord1 ... Ncount value ...]`` per chunk (the
    step's header line ``Timestep Nchunks Total-count`` starts a block)."""
    blocks: List[list] = []
    for n, s in _ave_rows(path):
        if len(s) == 3:
            blocks.append([])
        elif not blocks:
            raise DumpFormatError(f"{path}:{n}: chunk row before the first 'Timestep Nchunks Total-count' line "
                                  "(not a fix ave/chunk file?)")
        else:
            blocks[-1].append([float(v) for v in s])
    return [np.array(b) for b in blocks if b]


def read_ave_time(path) -> np.ndarray:
    """The rows of a ``fix ave/time`` file (scalar mode) as a 2-d array:
    ``[TimeStep value ...]`` per output step."""
    return np.array([[float(v) for v in s] for _, s in _ave_rows(path)])
