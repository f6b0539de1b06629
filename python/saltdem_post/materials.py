"""Material of each disc (from its LAMMPS ``type``) and its marker index."""

from __future__ import annotations

from typing import Dict, Optional

import numpy as np

from .dump import Frame, match_ids

MATERIALS = ("cover", "salt", "wall")
DEFAULT_TYPES = {1: "cover", 2: "salt", 3: "wall"}
DEFAULT_MARKER_COLUMN = "i_marker"
DEFAULT_MARKER_SPACING = 60.0       # m: thickness of cover layers / width of salt bands


class MaterialMap:
    """Maps LAMMPS atom types to ``cover``, ``salt`` or ``wall``.

    Unlisted types belong to no material (they are drawn grey and ignored by
    the measurements).
    """

    def __init__(self, mapping: Optional[Dict[int, str]] = None):
        mapping = dict(DEFAULT_TYPES if mapping is None else mapping)
        bad = {m for m in mapping.values() if m not in MATERIALS}
        if bad:
            raise ValueError(f"unknown material(s) {sorted(bad)}; use {', '.join(MATERIALS)}")
        self.mapping = {int(k): v for k, v in mapping.items()}

    @classmethod
    def parse(cls, text: Optional[str]) -> "MaterialMap":
        """Parse ``"cover=1,4;salt=2;wall=3"`` (also accepts ``"1:cover,2:salt"``)."""
        if not text:
            return cls()
        mapping: Dict[int, str] = {}
        if "=" in text:
            for part in text.replace(" ", "").split(";"):
                if part:
                    name, types = part.split("=")
                    for t in types.split(","):
                        mapping[int(t)] = name
        else:
            for part in text.replace(" ", "").split(","):
                if part:
                    t, name = part.split(":")
                    mapping[int(t)] = name
        return cls(mapping)

    def types_of(self, material: str):
        return sorted(t for t, m in self.mapping.items() if m == material)

    def mask(self, types: np.ndarray, material: str) -> np.ndarray:
        if material not in MATERIALS:
            raise ValueError(f"unknown material {material!r}")
        return np.isin(types, self.types_of(material))

    def codes(self, types: np.ndarray) -> np.ndarray:
        """Index into :data:`MATERIALS` per disc; -1 for unmapped types."""
        out = np.full(len(types), -1, dtype=np.int8)
        for k, m in enumerate(MATERIALS):
            out[self.mask(types, m)] = k
        return out

    def __str__(self) -> str:
        return ";".join(f"{m}={','.join(map(str, self.types_of(m)))}" for m in MATERIALS if self.types_of(m))


def markers(frame: Frame, materials: MaterialMap, column: str = DEFAULT_MARKER_COLUMN,
            reference: Optional[Frame] = None, spacing: float = DEFAULT_MARKER_SPACING) -> np.ndarray:
    """Per-disc marker index: cover layer (counted up from the base of the
    cover) or salt band (counted from the left), as written by the decks.

    Dumps without the marker column get markers rebuilt from the positions in
    ``reference`` (default: the frame itself), matched by atom id.
    """
    if column in frame:
        return np.asarray(frame[column])
    ref = reference if reference is not None else frame
    rx, ry, rtype = ref.x, ref.y, ref["type"]
    cover, salt = materials.mask(rtype, "cover"), materials.mask(rtype, "salt")
    ref_marker = np.zeros(ref.natoms, dtype=np.int64)
    if cover.any():
        ref_marker[cover] = np.floor((ry[cover] - ry[cover].min()) / spacing)
    if salt.any():
        ref_marker[salt] = np.floor((rx[salt] - rx[salt].min()) / spacing)
    if ref is frame:
        return ref_marker
    out = np.full(frame.natoms, -1, dtype=np.int64)
    i_frame, i_ref = match_ids(frame.ids, ref.ids)
    out[i_frame] = ref_marker[i_ref]
    return out
