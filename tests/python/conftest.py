"""Shared test helpers.  The package is imported from python/ in the checkout:
pytest.ini's ``pythonpath = python`` puts it on the module path."""

import os

import numpy as np
import pytest

from saltdem_post.dump import Box, Frame

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))

FIXTURE = os.path.join(HERE, "data", "small_scene.dump.gz")


def build_frame(xy, ids=None, types=None, radius=10.0, timestep=0, box=None, **columns):
    """A Frame from positions (N x 2) with default ids 1..N, type 1, radius."""
    xy = np.asarray(xy, float)
    n = len(xy)
    data = {"id": np.arange(1, n + 1) if ids is None else np.asarray(ids),
            "type": np.ones(n, dtype=np.int64) if types is None else np.asarray(types),
            "x": xy[:, 0].copy(), "y": xy[:, 1].copy(),
            "radius": np.broadcast_to(np.asarray(radius, float), (n,)).copy()}
    data.update({k: np.asarray(v) for k, v in columns.items()})
    if box is None:
        lo, hi = xy.min(axis=0) - 50.0, xy.max(axis=0) + 50.0
        box = Box(np.array([lo[0], lo[1], -0.5]), np.array([hi[0], hi[1], 0.5]), boundary=("ff", "ff", "pp"))
    return Frame(timestep, box, data)


@pytest.fixture
def make_frame():
    return build_frame


@pytest.fixture
def fixture_path():
    assert os.path.exists(FIXTURE), "run tests/python/data/make_fixture.py to create the fixture"
    return FIXTURE


@pytest.fixture
def repo_root():
    return REPO
