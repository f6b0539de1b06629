"""Strain from displacements: known homogeneous deformations are recovered exactly."""

import numpy as np
import pytest

from saltdem_post.dump import Box
from saltdem_post.strain import default_radius, strain_between


def _cloud(n=400, size=1000.0, seed=3):
    """A random (non-lattice) cloud: no special symmetry helps the fit."""
    return np.random.default_rng(seed).uniform(0.0, size, (n, 2))


def _deform(make_frame, F, shift=(0.0, 0.0), method="radius", radius=150.0):
    X = _cloud()
    x = X @ np.asarray(F).T + np.asarray(shift)
    return strain_between(make_frame(X), make_frame(x, timestep=100), radius=radius, method=method)


@pytest.mark.parametrize("gamma", [0.05, 0.3, 2.0])
@pytest.mark.parametrize("method", ["radius", "delaunay"])
def test_simple_shear_recovered_exactly(make_frame, gamma, method):
    s = _deform(make_frame, [[1.0, gamma], [0.0, 1.0]], method=method, radius=200.0)
    assert not np.isnan(s.max_shear).any()
    np.testing.assert_allclose(s.max_shear, gamma, rtol=1e-9)
    np.testing.assert_allclose(s.max_shear_small, gamma, rtol=1e-9)   # linear in H, exact too
    np.testing.assert_allclose(s.dilatation, 0.0, atol=1e-10)
    np.testing.assert_allclose(s.rotation, -np.arctan(gamma / 2.0), atol=1e-10)  # clockwise
    np.testing.assert_allclose(s.rotation_small, -gamma / 2.0, atol=1e-10)
    np.testing.assert_allclose(s.F[:, 0, 1], gamma, rtol=1e-9)
    np.testing.assert_allclose(s.d2min, 0.0, atol=1e-6)          # m^2, round-off only


def test_pure_shear(make_frame):
    k = 1.25
    s = _deform(make_frame, [[k, 0.0], [0.0, 1.0 / k]])
    s1, s2 = s.stretches
    np.testing.assert_allclose(s1, k, rtol=1e-10)
    np.testing.assert_allclose(s2, 1.0 / k, rtol=1e-10)
    np.testing.assert_allclose(s.max_shear, k - 1.0 / k, rtol=1e-10)
    np.testing.assert_allclose(s.dilatation, 0.0, atol=1e-10)
    np.testing.assert_allclose(s.rotation, 0.0, atol=1e-10)
    exx, eyy, exy = s.small_strain
    np.testing.assert_allclose(exx, k - 1.0, rtol=1e-10)
    np.testing.assert_allclose(eyy, 1.0 / k - 1.0, rtol=1e-10)
    np.testing.assert_allclose(exy, 0.0, atol=1e-10)


@pytest.mark.parametrize("angle_deg", [1.0, 30.0, 120.0])
def test_rigid_rotation_and_translation_give_zero_strain(make_frame, angle_deg):
    a = np.radians(angle_deg)
    R = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
    s = _deform(make_frame, R, shift=(5000.0, -1234.5))
    np.testing.assert_allclose(s.max_shear, 0.0, atol=1e-9)
    np.testing.assert_allclose(s.dilatation, 0.0, atol=1e-9)
    np.testing.assert_allclose(s.rotation, a if angle_deg <= 180 else a - 2 * np.pi, atol=1e-10)
    s1, s2 = s.stretches
    np.testing.assert_allclose([s1, s2], 1.0, atol=1e-9)
    if angle_deg >= 30:
        # the linearised dilatation is 2(cos a - 1): why finite measures are reported
        np.testing.assert_allclose(s.dilatation_small, 2 * (np.cos(a) - 1), atol=1e-9)


def test_pure_translation(make_frame):
    s = _deform(make_frame, np.eye(2), shift=(100.0, 50.0))
    np.testing.assert_allclose(s.max_shear, 0.0, atol=1e-12)
    np.testing.assert_allclose(s.max_shear_small, 0.0, atol=1e-12)
    np.testing.assert_allclose(s.displacement, [[100.0, 50.0]] * len(s.ids), atol=1e-9)


def test_isotropic_expansion_dilatation(make_frame):
    e = 0.02
    s = _deform(make_frame, (1 + e) * np.eye(2))
    np.testing.assert_allclose(s.dilatation, (1 + e) ** 2 - 1, rtol=1e-9)
    np.testing.assert_allclose(s.dilatation_small, 2 * e, rtol=1e-9)
    np.testing.assert_allclose(s.max_shear, 0.0, atol=1e-10)


def test_matching_by_id_shuffled_and_missing(make_frame):
    X = _cloud(300)
    gamma = 0.4
    x = X @ np.array([[1.0, gamma], [0.0, 1.0]]).T
    ids = np.arange(1, 301)
    order = np.random.default_rng(1).permutation(300)[:-5]    # shuffled, 5 discs lost
    ref = make_frame(X, ids=ids)
    cur = make_frame(x[order], ids=ids[order])
    s = strain_between(ref, cur, radius=200.0)
    assert len(s.ids) == 295 and np.all(np.diff(s.ids) > 0)
    np.testing.assert_allclose(s.max_shear, gamma, rtol=1e-9)


def test_periodic_x_minimum_image(make_frame):
    L = 1000.0
    X = _cloud(400, size=L)
    gamma = 0.1
    x = X @ np.array([[1.0, gamma], [0.0, 1.0]]).T
    x[:, 0] = np.mod(x[:, 0], L)                                # LAMMPS wraps atoms back into the box
    box = Box(np.array([0.0, -100.0, -0.5]), np.array([L, 1100.0, 0.5]), boundary=("pp", "ff", "pp"))
    s = strain_between(make_frame(X, box=box), make_frame(x, box=box), radius=150.0)
    np.testing.assert_allclose(s.max_shear, gamma, rtol=1e-9)   # including discs at the seam
    box_f = Box(box.lo, box.hi, boundary=("ff", "ff", "pp"))
    s_f = strain_between(make_frame(X, box=box_f), make_frame(x, box=box_f), radius=150.0)
    assert np.nanmax(np.abs(s_f.max_shear - gamma)) > 1.0     # without wrapping the seam is wrong


def test_heterogeneous_field_and_nonaffine_residual(make_frame):
    X = _cloud(2000, size=2000.0)
    # a shear band: u_x = 0 below y = 800, rising linearly by 200 m across the 400 m band
    ux = np.clip((X[:, 1] - 800.0) / 400.0, 0.0, 1.0) * 200.0
    x = X + np.column_stack([ux, np.zeros(len(X))])
    s = strain_between(make_frame(X), make_frame(x), radius=100.0)
    y = s.ref_xy[:, 1]
    ok = np.isfinite(s.max_shear)               # a few sparse corner discs have < 3 neighbours
    assert ok.mean() > 0.99
    inside, outside = ok & (y > 920) & (y < 1080), ok & ((y < 600) | (y > 1400))
    assert inside.sum() > 100 and outside.sum() > 500
    np.testing.assert_allclose(s.max_shear[inside], 0.5, rtol=1e-9)   # gamma = 200/400
    np.testing.assert_allclose(s.max_shear[outside], 0.0, atol=1e-9)
    noisy = x + np.random.default_rng(5).normal(0, 1.0, x.shape)
    s2 = strain_between(make_frame(X), make_frame(noisy), radius=100.0)
    # D2min is zero where the neighbourhood moves affinely, positive at the
    # band's kinks and everywhere once noise is added.
    assert np.max(s.d2min[inside | outside]) < 1e-6
    assert np.nanmax(s.d2min) > 10.0
    assert np.nanmedian(s2.d2min) > 0.5


def test_isolated_disc_is_undefined_and_default_radius(make_frame):
    X = np.vstack([_cloud(100, size=200.0), [[5000.0, 5000.0]]])
    f = make_frame(X, radius=10.0)
    assert default_radius(f) == pytest.approx(40.0)             # two disc diameters
    s = strain_between(f, make_frame(X + 1.0, radius=10.0))
    assert np.isnan(s.max_shear[-1]) and s.n_neighbours[-1] == 0
    assert s.summary()["n_undefined"] >= 1
    table = s.table()
    assert set(["id", "x", "y", "max_shear", "dilatation", "rotation", "d2min"]) <= set(table)
    assert all(len(v) == 101 for v in table.values())


def test_max_shear_is_independent_of_volume_change(make_frame):
    a, gamma = 1.1, 0.5
    s = _deform(make_frame, a * np.array([[1.0, gamma], [0.0, 1.0]]))
    np.testing.assert_allclose(s.max_shear, gamma, rtol=1e-9)          # a shape measure
    np.testing.assert_allclose(s.dilatation, a ** 2 - 1, rtol=1e-9)
