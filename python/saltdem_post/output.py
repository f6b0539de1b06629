"""CSV and JSON writers for the measurements."""

from __future__ import annotations

import json
import math
import os
from typing import Dict

import numpy as np


def _plain(obj):
    """numpy scalars/arrays -> Python; NaN/inf -> None (JSON has no NaN)."""
    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _plain(obj.tolist())
    if isinstance(obj, np.generic):
        return _plain(obj.item())
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def write_json(path: str, data) -> str:
    with open(path, "w", encoding="utf-8") as fh:
        json.dump(_plain(data), fh, indent=2)
        fh.write("\n")
    return path


def write_csv(path: str, columns: Dict[str, np.ndarray]) -> str:
    """Columns of equal length; integers written as integers."""
    names = list(columns)
    arrays = [np.asarray(columns[n]) for n in names]
    fmt = ["%d" if a.dtype.kind in "iub" else "%.10g" for a in arrays]
    table = np.column_stack(arrays).astype(float) if arrays else np.empty((0, 0))
    np.savetxt(path, table, fmt=fmt, delimiter=",", header=",".join(names), comments="")
    return path


def ensure_dir(path: str) -> str:
    os.makedirs(path, exist_ok=True)
    return path
