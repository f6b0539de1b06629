"""Salt thickness, welds, fault displacement and Couette + Poiseuille profiles."""

import numpy as np
import pytest

from saltdem_post.dump import read_frame
from saltdem_post.materials import MaterialMap, markers
from saltdem_post.measure import (column_union_length, fault_displacement, fit_couette_poiseuille,
                                  salt_thickness, vertical_profile)
from saltdem_post.synthetic import SceneSpec, reference_scene

COVER, SALT, WALL = 1, 2, 3
D = 20.0   # disc diameter of the square-lattice columns


def column_stack(make_frame, layers_at, width=1000.0, d=D, **columns):
    """Square lattice of touching discs; ``layers_at(x)`` gives the
    bottom-up list of (type, rows) for the column at x."""
    pts, types = [], []
    for x in np.arange(d / 2, width, d):
        y = d / 2
        for typ, rows in layers_at(x):
            for _ in range(rows):
                pts.append((x, y))
                types.append(typ)
                y += d
    return make_frame(np.array(pts), types=np.array(types), radius=d / 2, **columns)


def test_layered_column_thickness_is_exact(make_frame):
    f = column_stack(make_frame, lambda x: [(WALL, 1), (SALT, 7), (COVER, 10)])
    p = salt_thickness(f)
    assert p.bin_width == pytest.approx(40.0)              # two disc diameters
    assert len(p.x) == 25
    np.testing.assert_allclose(p.thickness, 7 * D, atol=1e-9)
    np.testing.assert_allclose(p.base, D, atol=1e-9)
    np.testing.assert_allclose(p.top, 8 * D, atol=1e-9)
    assert p.welds() == [] and p.minimum()["thickness_m"] == pytest.approx(7 * D)
    assert p.weld_thickness == pytest.approx(D)


def test_cover_inside_salt_is_not_counted(make_frame):
    f = column_stack(make_frame, lambda x: [(WALL, 1), (SALT, 4), (COVER, 3), (SALT, 4), (COVER, 5)])
    p = salt_thickness(f)
    np.testing.assert_allclose(p.thickness, 8 * D, atol=1e-9)          # two 80 m salt layers
    np.testing.assert_allclose(p.top - p.base, 11 * D, atol=1e-9)      # extent includes the cover


def test_hexagonal_random_packing_thickness(make_frame):
    spec = SceneSpec()
    f = reference_scene(spec)
    p = salt_thickness(f)
    # salt fills y = 0 .. ~220 m (halfway between last salt and first cover row)
    dy = 2 * spec.r_max * np.sqrt(3) / 2
    nominal = spec.r_max + 4 * dy + dy / 2
    assert np.all(np.abs(p.thickness - nominal) < 0.5 * p.weld_thickness)
    assert np.mean(p.thickness) == pytest.approx(nominal, abs=5.0)


def test_weld_detection_and_minimum(make_frame):
    def layers(x):
        if 400 < x < 600:
            return [(WALL, 1), (COVER, 12)]                    # salt gone: cover on basement
        if 600 < x < 700:
            return [(WALL, 1), (SALT, 1), (COVER, 11)]         # one disc of salt left
        return [(WALL, 1), (SALT, 6), (COVER, 6)]
    f = column_stack(make_frame, layers)
    p = salt_thickness(f)
    welds = p.welds()
    assert len(welds) == 1
    w = welds[0]
    assert w["x_start_m"] == pytest.approx(400.0) and w["x_end_m"] == pytest.approx(600.0)
    assert w["width_m"] == pytest.approx(200.0) and w["min_thickness_m"] == 0.0
    mn = p.minimum()
    assert mn["thickness_m"] == 0.0 and 400 < mn["x_m"] < 600 and mn["welded"]
    np.testing.assert_allclose(p.thickness[(p.x > 600) & (p.x < 700)], D)   # thin but not welded
    # a stricter weld criterion also catches the one-disc layer
    p30 = salt_thickness(f, weld_thickness=30.0)
    assert [(w["x_start_m"], w["x_end_m"]) for w in p30.welds()] == [(400.0, 680.0)]
    assert p.summary()["welded_length_m"] == pytest.approx(200.0)


def test_thickness_outside_model_is_nan(make_frame):
    f = column_stack(make_frame, lambda x: [(WALL, 1), (SALT, 3), (COVER, 2)] if x < 500 else [(WALL, 1)])
    p = salt_thickness(f, x_range=(0.0, 1000.0), bin_width=100.0)
    assert np.all(np.isfinite(p.thickness[:5])) and np.all(np.isnan(p.thickness[5:]))
    assert p.welds() == []


def test_union_length_merges_pores():
    bins = np.array([0, 0, 0, 1, 1])
    lo = np.array([0.0, 9.0, 30.0, 5.0, 6.0])
    hi = np.array([8.0, 20.0, 40.0, 7.0, 8.0])
    np.testing.assert_allclose(column_union_length(bins, lo, hi, 3, gap=0.0), [29.0, 3.0, 0.0])
    np.testing.assert_allclose(column_union_length(bins, lo, hi, 3, gap=1.5), [30.0, 3.0, 0.0])
    np.testing.assert_allclose(column_union_length(bins, lo, hi, 3, gap=15.0), [40.0, 3.0, 0.0])


def test_type_mapping_is_an_option(make_frame):
    f = column_stack(make_frame, lambda x: [(7, 1), (5, 3), (4, 2)])
    m = MaterialMap.parse("cover=4;salt=5;wall=7")
    np.testing.assert_allclose(salt_thickness(f, m).thickness, 3 * D)
    assert MaterialMap.parse("4:cover,5:salt,7:wall").mapping == m.mapping
    with pytest.raises(ValueError):
        MaterialMap.parse("rock=1")


def test_markers_rebuilt_from_reference_when_column_missing(make_frame):
    f = column_stack(make_frame, lambda x: [(WALL, 1), (SALT, 2), (COVER, 6)], width=200.0)
    mk = markers(f, MaterialMap(), spacing=60.0)
    types, x, y = f["type"], f.x, f.y
    cover = types == COVER
    np.testing.assert_array_equal(mk[cover], np.floor((y[cover] - 70.0) / 60.0))   # cover base row at 70 m
    salt = types == SALT
    np.testing.assert_array_equal(mk[salt], np.floor((x[salt] - 10.0) / 60.0))
    f2 = column_stack(make_frame, lambda x: [(WALL, 1), (SALT, 2), (COVER, 6)], width=200.0,
                      i_marker=np.arange(80))
    np.testing.assert_array_equal(markers(f2, MaterialMap()), np.arange(80))


# ------------------------------------------------------------ fault

def _basement(make_frame, slip_vec, moved_right=True, loose=(0.0, 0.0)):
    x = np.arange(10.0, 2000.0, 20.0)
    X = np.column_stack([x, np.full(len(x), -10.0)])
    ref = make_frame(X, types=np.full(len(x), WALL))
    cur_xy = X.copy()
    right = x > 1000.0 if moved_right else x < 1000.0
    cur_xy[right] += slip_vec
    cur_xy[0] += loose                                      # one loose disc, ignored by the median
    return ref, make_frame(cur_xy, types=np.full(len(x), WALL), timestep=500), right.sum()


@pytest.mark.parametrize("fault_x", [None, 1000.0])
def test_fault_displacement(make_frame, fault_x):
    slip = 50.0
    vec = slip * np.array([np.cos(np.radians(60)), -np.sin(np.radians(60))])
    ref, cur, n_right = _basement(make_frame, vec, loose=(3.0, 3.0))
    fd = fault_displacement(ref, cur, fault_x=fault_x)
    assert fd.slip == pytest.approx(slip, abs=1e-9)
    assert fd.throw == pytest.approx(slip * np.sin(np.radians(60)), abs=1e-9)
    assert fd.heave == pytest.approx(25.0, abs=1e-9)
    assert fd.dy < 0 and fd.n_moving == n_right and fd.timestep == 500
    # the left block moving instead gives the same magnitude
    ref, cur, _ = _basement(make_frame, vec, moved_right=False)
    assert fault_displacement(ref, cur, fault_x=fault_x).slip == pytest.approx(slip, abs=1e-9)
    # no motion, no displacement
    ref, cur, _ = _basement(make_frame, np.zeros(2))
    assert fault_displacement(ref, cur, fault_x=fault_x).slip == 0.0


def test_fault_displacement_needs_walls(make_frame):
    f = make_frame(np.zeros((3, 2)) + np.arange(3)[:, None])
    with pytest.raises(ValueError, match="wall"):
        fault_displacement(f, f)


# ---------------------------------------------------------- profiles

def test_couette_poiseuille_fit_exact():
    y = np.linspace(100.0, 300.0, 57)
    eta = (y - 100.0) / 200.0
    u = 0.2 + 1.5 * eta + 0.8 * 4 * eta * (1 - eta)
    fit = fit_couette_poiseuille(y, u, 100.0, 300.0, viscosity=1e18)
    assert fit.u_base == pytest.approx(0.2, abs=1e-12)
    assert fit.couette == pytest.approx(1.5, abs=1e-12)
    assert fit.poiseuille == pytest.approx(0.8, abs=1e-12)
    assert fit.r2 == pytest.approx(1.0) and fit.rms < 1e-12 and fit.n == 57
    assert fit.shear_rate == pytest.approx(1.5 / 200.0)
    assert fit.pressure_gradient == pytest.approx(-8 * 1e18 * 0.8 / 200.0 ** 2)
    np.testing.assert_allclose(fit.predict(y), u, atol=1e-12)


def test_couette_poiseuille_fit_noisy_and_pure_shear():
    rng = np.random.default_rng(2)
    y = rng.uniform(0.0, 500.0, 3000)
    eta = y / 500.0
    u = -1e-10 + 3e-10 * eta - 2e-10 * 4 * eta * (1 - eta) + rng.normal(0, 2e-11, len(y))
    fit = fit_couette_poiseuille(y, u, 0.0, 500.0)
    assert fit.couette == pytest.approx(3e-10, rel=0.02)
    assert fit.poiseuille == pytest.approx(-2e-10, rel=0.02)
    assert fit.pressure_gradient is None
    pure = fit_couette_poiseuille(y, 5.0 * eta, 0.0, 500.0)
    assert pure.couette == pytest.approx(5.0) and abs(pure.poiseuille) < 1e-12
    with pytest.raises(ValueError):
        fit_couette_poiseuille(y[:2], u[:2], 0.0, 500.0)


def test_vertical_profile_from_discs(make_frame):
    layers = lambda x: [(WALL, 1), (SALT, 8), (COVER, 4)]  # noqa: E731
    ref = column_stack(make_frame, layers)
    base, top = D, 9 * D                                   # salt disc edges
    eta = np.clip((ref.y - base) / (top - base), 0, 1)
    flow = 2.0 * eta + 0.5 * 4 * eta * (1 - eta)
    ref.data["vx"] = np.where(ref["type"] == SALT, flow, 0.0)
    p = vertical_profile(ref, 500.0, "vx")
    assert p.fit.base == pytest.approx(base) and p.fit.top == pytest.approx(top)
    assert p.fit.couette == pytest.approx(2.0, abs=1e-9)
    assert p.fit.poiseuille == pytest.approx(0.5, abs=1e-9)
    assert p.halfwidth == pytest.approx(2 * D) and len(p.y) == 8 * 4  # columns 470..530 m
    assert len(p.bins["y"]) == 8 and np.all(p.bins["count"] == 4)
    # the same flow as a displacement of initially vertical marker lines
    cur = column_stack(make_frame, layers)
    cur.data["x"] = cur.x + 10.0 * np.where(cur["type"] == SALT, flow, 0.0)
    q = vertical_profile(cur, 500.0, "ux", reference=ref, halfwidth=15.0)
    assert q.fit.couette == pytest.approx(20.0, abs=1e-9)
    assert q.fit.poiseuille == pytest.approx(5.0, abs=1e-9)


def test_fixture_profile_recovers_prescribed_flow(fixture_path):
    """The fixture's salt moves with u = V (c eta + p 4 eta (1 - eta)),
    eta = y / 240 m; refitted between the salt-disc edges the Couette part is
    the velocity difference across them and the Poiseuille part scales with h^2."""
    spec = SceneSpec()
    f = read_frame(fixture_path, -1)
    p = vertical_profile(f, 300.0, "vx")
    g = lambda y: spec.couette * y / 240.0 + spec.poiseuille * 4 * (y / 240.0) * (1 - y / 240.0)  # noqa: E731
    h = p.fit.top - p.fit.base
    assert p.fit.r2 > 0.999
    assert p.fit.couette == pytest.approx(spec.slip_rate * (g(p.fit.top) - g(p.fit.base)), rel=0.01)
    assert p.fit.poiseuille == pytest.approx(spec.slip_rate * spec.poiseuille * (h / 240.0) ** 2, rel=0.01)
