"""``saltdem-post outcomes`` on synthetic scenes with known answers: a planted
cover fault, thinned and welded salt, a rigidly moved cover, salt bands with
Couette and Poiseuille profiles, a keystone graben, and the command line."""

import json

import numpy as np
import pytest

from saltdem_post.cli import main
from saltdem_post.dump import Frame, iter_frames, write_dump
from saltdem_post.materials import MaterialMap
from saltdem_post.outcomes import OutcomeOptions, basement_tips, block_slip, fit_band_line, fit_line, frame_outcomes
from saltdem_post.synthetic import (COVER, SALT, WALL, SceneSpec, displaced, planted_cover_fault,
                                    reference_scene)

# 3 km x (300 m salt + 720 m cover), discs of radius 12-15 m: ~4,000 discs
SPEC = SceneSpec(width=3000.0, salt_thickness=300.0, cover_thickness=720.0, r_max=15.0)
TOP = SPEC.salt_thickness + SPEC.cover_thickness
MATERIALS = MaterialMap()


def median_cover_diameter(frame):
    return 2.0 * np.median(frame.radius[frame["type"] == COVER])


def with_end_walls(frame, spec=SPEC):
    """The frame plus two columns of touching wall discs, faces at x = 0 and x = width."""
    rw = 0.8 * spec.r_max
    y = np.arange(rw, TOP + 4 * spec.r_max, 2 * rw)
    x = np.concatenate([np.full(len(y), -rw), np.full(len(y), spec.width + rw)])
    n, extra = frame.natoms, 2 * len(y)
    add = {"id": np.arange(1, extra + 1) + frame.ids.max(), "type": np.full(extra, WALL),
           "x": x, "y": np.concatenate([y, y]), "radius": np.full(extra, rw), "i_marker": np.full(extra, -1)}
    data = {c: np.concatenate([v, add[c] if c in add else np.zeros(extra, v.dtype)]) for c, v in frame.data.items()}
    assert len(data["id"]) == n + extra
    return Frame(frame.timestep, frame.box, data, frame.path, frame.index, frame.time)


def outcomes_of(cur, ref, prev=None, **options):
    return frame_outcomes(cur, ref, ref if prev is None else prev, MATERIALS, OutcomeOptions(**options))


# ------------------------------------------------------------ cover faults

@pytest.mark.parametrize("direction, dip, throw", [("right", 55.0, 100.0), ("left", 65.0, 150.0),
                                                  ("right", 70.0, 60.0)])
def test_planted_fault_found(direction, dip, throw):
    x_interface = 1790.0 if direction == "right" else 1210.0
    ref, cur = planted_cover_fault(SPEC, x_interface, dip, throw, direction)
    sign = 1.0 if direction == "right" else -1.0
    x_surface = x_interface - sign * SPEC.cover_thickness / np.tan(np.radians(dip))
    d = median_cover_diameter(ref)
    r = outcomes_of(cur, ref, fault_x=[1500.0])           # basement fault dipping right (default)
    faults = r["faults"]["list"]
    assert r["faults"]["count"] == 1, faults
    f = faults[0]
    assert f["dip_deg"] == pytest.approx(dip, abs=3.0)
    assert f["dip_direction"] == direction
    assert f["sense"] == ("synthetic" if direction == "right" else "antithetic")
    assert f["reaches_surface"] and f["reaches_salt"] and f["active"]
    assert f["x_surface_m"] == pytest.approx(x_surface, abs=d)
    assert f["x_interface_m"] == pytest.approx(x_interface, abs=d)
    assert f["throw_m"] == pytest.approx(throw, rel=0.2)
    assert f["throw_layers"] >= 8                          # all the layers the fault crosses
    # the hanging wall's cover base dropped by the throw: the fault offsets the interface
    assert f["interface_step_m"] == pytest.approx(throw, rel=0.2)
    assert r["interface"]["offset_by_fault"] and r["interface"]["offsetting_faults"] == ["F1"]
    assert r["interface"]["relief_m"] == pytest.approx(throw, abs=d)


def test_planted_fault_in_noise_and_distributed_strain():
    """Disc-scale jitter (non-affine noise) and a gentle homogeneous shear of
    the whole cover: the threshold follows the cover's median and only the
    planted band is a fault."""
    ref, cur = planted_cover_fault(SPEC, 1790.0, 60.0, 100.0)
    rng = np.random.default_rng(7)
    cover = cur["type"] == COVER
    shear = np.column_stack([0.01 * (cur.y[cover] - SPEC.salt_thickness), np.zeros(cover.sum())])
    cur = displaced(cur, cover, shear + rng.normal(0.0, 1.0, (cover.sum(), 2)))
    r = outcomes_of(cur, ref, fault_x=[1500.0])
    det = r["faults"]["detection"]["finite"]
    assert det["threshold"] > 0.02 and det["threshold"] == pytest.approx(4 * det["median_strain"])
    assert r["faults"]["count"] == 1
    f = r["faults"]["list"][0]
    assert f["dip_deg"] == pytest.approx(60.0, abs=3.0)
    assert f["throw_m"] == pytest.approx(100.0, rel=0.2)


def test_blind_fault_tips_out_below_the_surface():
    """A fault in the lower half of the cover only: it reaches the salt, not the surface."""
    ref = reference_scene(SPEC)
    a = np.radians(60.0)
    plane_x = 1500.0 - (ref.y - SPEC.salt_thickness) / np.tan(a)
    hanging = (ref["type"] == COVER) & (ref.x > plane_x) & (ref.y < SPEC.salt_thickness + 400.0)
    cur = displaced(ref, hanging, 60.0 * np.array([np.cos(a), -np.sin(a)]))
    f = outcomes_of(cur, ref, fault_x=[1500.0])["faults"]["list"]
    assert len(f) == 1 and f[0]["reaches_salt"] and not f[0]["reaches_surface"]
    assert f[0]["x_surface_m"] is None
    assert f[0]["upper_tip_depth_m"] == pytest.approx(TOP - (SPEC.salt_thickness + 400.0), abs=100.0)


def test_band_line_fit_ignores_the_slipped_ends():
    """A band's footwall and hanging-wall halves are offset along it by the
    slip; the trimmed fit keeps the band's direction, a plain PCA tilts."""
    rng = np.random.default_rng(3)
    a = np.radians(55.0)
    t, n = np.array([np.cos(a), -np.sin(a)]), np.array([np.sin(a), np.cos(a)])
    s = rng.uniform(0.0, 1000.0, 400)
    side = np.where(rng.random(400) < 0.5, -1.0, 1.0)
    offset = rng.uniform(5.0, 50.0, 400) * side
    xy = s[:, None] * t + offset[:, None] * n + np.where(side > 0, 200.0, 0.0)[:, None] * t
    plain = np.degrees(np.arctan2(-fit_line(xy)[1][1], fit_line(xy)[1][0]))
    trimmed = np.degrees(np.arctan2(-fit_band_line(xy)[1][1], fit_band_line(xy)[1][0]))
    assert abs(plain - 55.0) > 1.5
    assert trimmed == pytest.approx(55.0, abs=0.5)


def test_distributed_shear_zone_is_not_a_fault():
    """A 600 m wide zone of homogeneous shear (the cover flexed down by 30 %
    of the distance across it): strong strain everywhere in the zone, but no
    localised band."""
    ref = reference_scene(SPEC)
    cover = ref["type"] == COVER
    drop = -0.3 * np.clip(ref.x - 1000.0, 0.0, 600.0)
    cur = displaced(ref, cover, np.column_stack([np.zeros(cover.sum()), drop[cover]]))
    r = outcomes_of(cur, ref, fault_x=[1500.0])
    det = r["faults"]["detection"]["finite"]
    assert det["n_strong"] > 300 and det["rejected"]["distributed"] >= 1
    assert r["faults"]["count"] == 0


def test_keystone_graben_two_synthetic_faults():
    """Keystone kinematics in the cover: the graben block slides down the left
    fault and the right block moves right by twice the heave; each fault is
    synthetic to the basement fault beneath it."""
    ref = reference_scene(SPEC)
    a = np.radians(60.0)
    cover = ref["type"] == COVER
    left = 1210.0 - (ref.y - SPEC.salt_thickness) / np.tan(a)
    right = 1790.0 + (ref.y - SPEC.salt_thickness) / np.tan(a)
    key, block = cover & (ref.x > left) & (ref.x < right), cover & (ref.x >= right)
    slip = 100.0 / np.sin(a)
    cur = displaced(ref, key, slip * np.array([np.cos(a), -np.sin(a)]))
    cur = displaced(cur, block, (2 * slip * np.cos(a), 0.0))
    r = outcomes_of(cur, ref, scene="keystone", fault_x=[1210.0, 1790.0])
    faults = r["faults"]["list"]
    assert [f["dip_direction"] for f in faults] == ["right", "left"]
    assert all(f["sense"] == "synthetic" for f in faults)
    assert all(f["throw_m"] == pytest.approx(100.0, rel=0.2) for f in faults)
    assert [f["dip_deg"] for f in faults] == pytest.approx([60.0, 60.0], abs=3.0)
    # the cover above each fault deforms outside the graben's base by about cover / tan(dip)
    spread = SPEC.cover_thickness / np.tan(a)
    for side in ("left", "right"):
        assert r["keystone"][side]["extent_m"] == pytest.approx(spread, rel=0.35)
    assert [g["region"] for g in r["salt_flow"]["regions"]] == ["left block", "graben", "right block"]


def test_keystone_raft_sheared_at_its_base_is_not_deformed():
    """A cover that slides right as one raft over the salt, sheared only in its lowest discs,
    is not a deformed cover on either side of the graben (the basal shear is in every column);
    counting those discs reads the whole half-section as deformed.  A zone of strain far from
    the graben (as at a moving end wall) counts in its side's width, not in the extent of the
    zone that starts at the graben."""
    spec = SceneSpec(width=6000.0, salt_thickness=300.0, cover_thickness=720.0, r_max=15.0)
    ref = reference_scene(spec)
    cover = ref["type"] == COVER
    z = ref.y[cover] - spec.salt_thickness
    d = median_cover_diameter(ref)
    ux = 200.0 + 40.0 * np.clip(z / (2.0 * d), 0.0, 1.0)    # the lowest two discs shear, the rest glides
    cur = displaced(ref, cover, np.column_stack([ux, np.zeros(cover.sum())]))
    tips = [1210.0, 1790.0]
    r = outcomes_of(cur, ref, scene="keystone", fault_x=tips)
    assert r["faults"]["detection"]["incremental"]["n_strong"] > 0    # the basal shear is strong
    for side in ("left", "right"):
        assert r["keystone"][side]["width_m"] == 0.0 and r["keystone"][side]["extent_m"] == 0.0
    end = cover & (ref.x > spec.width - 300.0)
    sheared = displaced(cur, end, np.column_stack([np.zeros(end.sum()),
                                                   -0.5 * (ref.x[end] - (spec.width - 300.0))]))
    r2 = outcomes_of(sheared, ref, scene="keystone", fault_x=tips)
    assert r2["keystone"]["right"]["width_m"] > 0.0
    assert r2["keystone"]["right"]["extent_m"] == 0.0
    # controls: counting every disc reads the whole half-section as deformed; a zone that starts
    # at the graben counts in the extent
    r0 = outcomes_of(cur, ref, scene="keystone", fault_x=tips, deformed_basal=0.0)
    assert r0["keystone"]["left"]["width_m"] > 0.8 * 1210.0
    near = cover & (ref.x > 1900.0) & (ref.x < 2200.0)
    r3 = outcomes_of(displaced(cur, near, np.column_stack([np.zeros(near.sum()), -0.5 * (ref.x[near] - 1900.0)])),
                     ref, scene="keystone", fault_x=tips)
    assert 2200.0 - 1790.0 <= r3["keystone"]["right"]["extent_m"] < 1000.0    # (strain smears past 2200)


# ------------------------------------------------------------ salt

def thinned(ref, x0, x1, keep_below):
    """Salt discs in x0 < x < x1 above ``keep_below`` become cover."""
    data = dict(ref.data)
    t = ref["type"].copy()
    t[(t == SALT) & (ref.x > x0) & (ref.x < x1) & (ref.y > keep_below)] = COVER
    data["type"] = t
    return Frame(ref.timestep, ref.box, data, index=ref.index)


def test_thin_salt_minimum_and_weld():
    ref = reference_scene(SPEC)
    thin = thinned(ref, 400.0, 700.0, 100.0)                 # four rows of salt left: ~100 m
    r = outcomes_of(thin, thin, fault_x=[1000.0])
    mn = r["salt"]["minimum"]
    bw = r["salt"]["bin_width_m"]
    assert 400.0 - bw < mn["x_m"] < 700.0 + bw
    assert mn["thickness_m"] == pytest.approx(105.0, abs=15.0)
    assert r["salt"]["welds"]["count"] == 0
    assert mn["rel_footwall_edge_m"] == pytest.approx(mn["x_m"] - 1000.0)
    assert mn["side"] == "footwall"                          # left of a fault dipping right

    welded = thinned(thin, 1500.0, 1800.0, -1.0)             # no salt at all in 1.5-1.8 km
    r = outcomes_of(welded, welded, fault_x=[1000.0])
    mn, w = r["salt"]["minimum"], r["salt"]["welds"]
    assert mn["thickness_m"] == 0.0 and 1500.0 < mn["x_m"] < 1800.0
    assert mn["side"] == "hanging wall" and mn["rel_tip_m"] == pytest.approx(mn["x_m"] - 1000.0)
    assert w["count"] == 1
    assert w["x_range_m"][0] == pytest.approx(1500.0, abs=r["salt"]["bin_width_m"])
    assert w["x_range_m"][1] == pytest.approx(1800.0, abs=r["salt"]["bin_width_m"])
    assert w["total_width_m"] == pytest.approx(300.0, abs=2 * r["salt"]["bin_width_m"])


def test_salt_body_pinch_out_and_crest():
    """A pinch-out: no salt left of 600 m; a crest: the salt right of 2 km thinned to 100 m.
    The body's extent starts at the pinch-out, its thickest column lies in 0.6-2 km; a change
    of either moves the reading (so the test can fail)."""
    ref = reference_scene(SPEC)
    body = thinned(thinned(ref, -1e9, 600.0, -1.0), 2000.0, 1e9, 100.0)
    b = outcomes_of(body, body, fault_x=[1000.0])["salt"]["body"]
    bw = outcomes_of(body, body, fault_x=[1000.0])["salt"]["bin_width_m"]
    assert b["extent_m"][0] == pytest.approx(600.0, abs=bw)
    assert 600.0 - bw < b["x_max_m"] < 2000.0 + bw
    assert b["max_thickness_m"] == pytest.approx(SPEC.salt_thickness, abs=60.0)
    wider = thinned(ref, -1e9, 300.0, -1.0)
    assert outcomes_of(wider, wider, fault_x=[1000.0])["salt"]["body"]["extent_m"][0] == \
        pytest.approx(300.0, abs=bw)


def salt_band_scene(profile_left, profile_right, fault_x=1500.0):
    """Salt displaced horizontally by u(eta), eta = y / salt thickness:
    ``profile_left`` left of ``fault_x``, ``profile_right`` right of it."""
    ref = reference_scene(SPEC)
    salt = ref["type"] == SALT
    eta = np.clip(ref.y / SPEC.salt_thickness, 0.0, 1.0)
    u = np.where(ref.x < fault_x, profile_left(eta), profile_right(eta))
    return ref, displaced(ref, salt, np.column_stack([u[salt], np.zeros(salt.sum())]))


def test_salt_flow_couette_and_poiseuille():
    # diverging at the boundary, so that no band crosses into the other region
    ref, cur = salt_band_scene(lambda e: -80.0 * e,                     # linear, to the left
                               lambda e: 120.0 * 4.0 * e * (1.0 - e))   # parabola, to the right
    r = outcomes_of(cur, ref, fault_x=[1500.0])
    regions = {g["region"]: g for g in r["salt_flow"]["regions"]}
    fw, hw = regions["footwall"], regions["hanging wall"]
    assert fw["character"] == "Couette" and fw["direction"] == "left"
    assert hw["character"] == "Poiseuille" and hw["direction"] == "right"
    assert fw["n_dominant"] == fw["n_bands"] >= 10 and hw["n_dominant"] == hw["n_bands"] >= 10
    bands = r["salt_flow"]["bands"]
    couette = [b for b in bands if b["region"] == "footwall"]
    assert all(b["r2"] > 0.99 and b["couette_m"] < 0 and abs(b["poiseuille_m"]) < 0.1 * abs(b["couette_m"])
               for b in couette)
    poiseuille = [b for b in bands if b["region"] == "hanging wall"]
    assert all(b["poiseuille_m"] > 0 and b["r2"] > 0.99 and b["r2_linear"] < 0.5 for b in poiseuille)


def test_salt_flow_reversed_and_static():
    ref, cur = salt_band_scene(lambda e: -90.0 * 4.0 * e * (1.0 - e), lambda e: 60.0 * e)
    regions = {g["region"]: g for g in outcomes_of(cur, ref, fault_x=[1500.0])["salt_flow"]["regions"]}
    assert (regions["footwall"]["character"], regions["footwall"]["direction"]) == ("Poiseuille", "left")
    assert (regions["hanging wall"]["character"], regions["hanging wall"]["direction"]) == ("Couette", "right")
    still = outcomes_of(ref, ref, fault_x=[1500.0])["salt_flow"]["regions"]
    assert all(g["character"] == "static" and g["direction"] == "none" for g in still)


def test_salt_riding_as_a_plug_is_a_plug():
    """Hanging-wall salt carried along whole, with one band sheared: the region is a plug, not
    the one sheared band's Couette flow (a run's salt that does not flow must read so)."""
    ref = reference_scene(SPEC)
    salt = ref["type"] == SALT
    eta = np.clip(ref.y / SPEC.salt_thickness, 0.0, 1.0)
    sheared = (ref.x > 2000.0) & (ref.x < 2060.0)
    u = np.where(ref.x < 1500.0, 0.0, np.where(sheared, 300.0 * eta, 200.0))
    cur = displaced(ref, salt, np.column_stack([u[salt], np.zeros(salt.sum())]))
    regions = {g["region"]: g for g in outcomes_of(cur, ref, fault_x=[1500.0])["salt_flow"]["regions"]}
    hw = regions["hanging wall"]
    assert hw["counts"]["Couette"] >= 1 and hw["counts"]["plug"] >= 5
    assert (hw["character"], hw["direction"]) == ("plug", "right")
    assert hw["n_dominant"] == hw["counts"]["plug"]
    assert regions["footwall"]["character"] == "static"


# ------------------------------------------------------------ rigid cover, walls

def test_rigid_cover_moves_as_one_block_without_faults():
    ref = with_end_walls(reference_scene(SPEC))
    cover = ref["type"] == COVER
    cur = displaced(ref, cover, (100.0, 0.0))
    r = outcomes_of(cur, ref, fault_x=[1500.0])
    for third in ("left", "middle", "right"):
        assert r["cover_motion"][third]["ux_m"] == pytest.approx(100.0, abs=1e-6)
        assert r["cover_motion"][third]["uy_m"] == pytest.approx(0.0, abs=1e-6)
    assert r["faults"]["count"] == 0
    assert r["faults"]["detection"]["finite"]["n_strong"] == 0
    walls = r["end_walls"]
    d = median_cover_diameter(ref)
    # the cover left a 100 m gap at the left wall (its edge started ~ 0.1-0.2 d from it) ...
    assert walls["left"]["edge_distance_m"] == pytest.approx(100.0, abs=0.5 * d) and walls["left"]["gap"]
    # ... and runs into the right one; neither edge subsided, the salt did not move
    assert walls["right"]["edge_distance_m"] < 0 and not walls["right"]["gap"]
    assert not walls["left"]["collapse"] and not walls["right"]["collapse"]
    assert walls["left"]["salt_rise_m"] == pytest.approx(0.0) and walls["right"]["salt_rise_m"] == pytest.approx(0.0)
    assert walls["left"]["face_x_m"] == pytest.approx(0.0) and walls["right"]["face_x_m"] == pytest.approx(SPEC.width)
    # thirds are by initial x: the right third moved 300 m left stays the right third
    x0 = ref.x[cover]
    right = cover & (ref.x >= x0.min() + 2.0 * (x0.max() - x0.min()) / 3.0)
    thirds = outcomes_of(displaced(ref, right, (-300.0, 0.0)), ref)["cover_motion"]
    assert [thirds[k]["ux_m"] for k in ("left", "middle", "right")] == pytest.approx([0.0, 0.0, -300.0])


def test_end_wall_collapse_and_salt_rise():
    """The cover's top corner at the right wall sinks 150 m and the salt
    beside the wall rises 120 m: a collapse with salt rise."""
    ref = with_end_walls(reference_scene(SPEC))
    d = median_cover_diameter(ref)
    cover, salt = ref["type"] == COVER, ref["type"] == SALT
    corner = cover & (ref.x > SPEC.width - 6 * d)
    cur = displaced(ref, corner, (0.0, -150.0))
    cur = displaced(cur, salt & (ref.x > SPEC.width - 2 * d) & (ref.y > SPEC.salt_thickness - 3 * d), (0.0, 120.0))
    walls = outcomes_of(cur, ref)["end_walls"]
    assert walls["right"]["edge_drop_m"] == pytest.approx(150.0) and walls["right"]["collapse"]
    assert walls["right"]["salt_rise_m"] == pytest.approx(120.0, abs=1e-6)
    assert not walls["left"]["collapse"] and walls["left"]["salt_rise_m"] == pytest.approx(0.0)


def test_tilted_blocks_rotate_between_faults():
    """Two faults, the block between them rotated by -3 degrees about its
    centre: the block rotation and the fault spacing are measured.  (55
    degrees: 60-degree planes run along rows of the hexagonal packing.)"""
    ref = reference_scene(SPEC)
    a = np.radians(55.0)
    cover = ref["type"] == COVER
    x_a = 900.0 - (ref.y - SPEC.salt_thickness) / np.tan(a)
    x_b = 2100.0 - (ref.y - SPEC.salt_thickness) / np.tan(a)
    block = cover & (ref.x > x_a) & (ref.x < x_b)
    right = cover & (ref.x >= x_b)
    slip = 80.0 * np.array([np.cos(a), -np.sin(a)])
    cur = displaced(ref, block, slip)
    cur = displaced(cur, right, 2 * slip)
    c = cur.xy[block].mean(axis=0)
    th = np.radians(-3.0)
    R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    cur = displaced(cur, block, (cur.xy[block] - c) @ R.T + c - cur.xy[block])
    r = outcomes_of(cur, ref, scene="tilted", downslope="right")
    faults = r["faults"]["list"]
    assert len(faults) == 2 and all(f["sense"] == "synthetic" for f in faults)
    t = r["tilted"]
    assert t["rotation_of"] == "blocks between faults"
    assert t["mean_rotation_deg"] == pytest.approx(-3.0, abs=0.5)
    # surface traces at the footwall cutoffs: the left one static, the right
    # one on the middle block (slipped, then rotated about its centre)
    d = median_cover_diameter(ref)
    x_left = 900.0 - SPEC.cover_thickness / np.tan(a)
    cutoff = (np.array([2100.0 - SPEC.cover_thickness / np.tan(a), TOP]) + slip - c) @ R.T + c
    assert [f["x_surface_m"] for f in faults] == pytest.approx([x_left, cutoff[0]], abs=d)
    assert t["mean_fault_spacing_m"] == pytest.approx(cutoff[0] - x_left, abs=d)


# ------------------------------------------------------------ basement

def basement(make_frame, x_blocks, u_blocks):
    """A base line of wall discs split at ``x_blocks``, each block displaced by its ``u``."""
    x = np.arange(10.0, 3000.0, 20.0)
    X = np.column_stack([x, np.full(len(x), -10.0)])
    k = np.searchsorted(x_blocks, x)
    ref = make_frame(X, types=np.full(len(x), WALL))
    cur = make_frame(X + np.asarray(u_blocks, float)[k], types=np.full(len(x), WALL), timestep=10)
    return ref, cur


def test_keystone_block_slip_and_tips(make_frame):
    d, a = 100.0, np.radians(60.0)
    keystone, right = d * np.array([np.cos(a), -np.sin(a)]), (2 * d * np.cos(a), 0.0)
    ref, cur = basement(make_frame, [1000.0, 2000.0], [(0.0, 0.0), keystone, right])
    slip = block_slip(ref, cur, MATERIALS, [1000.0, 2000.0])             # the keystone's, not the right block's
    assert (slip.dx, slip.dy, slip.slip) == pytest.approx((keystone[0], keystone[1], d))
    tips = basement_tips(ref, cur, MATERIALS, OutcomeOptions(scene="keystone", fault_x=(1000.0, 2000.0)))
    assert [t.dip_direction for t in tips] == ["right", "left"] and all(t.measured for t in tips)
    assert tips[0].x == pytest.approx(1000.0)                       # the left block is static
    assert tips[1].x == pytest.approx(2000.0 + 2 * d * np.cos(a))   # the right tip rides on the right block
    assert [t.slip for t in tips] == pytest.approx([d, d])
    # a normal fault dipping left: the block left of the tip goes down
    ref, cur = basement(make_frame, [1500.0], [(-50.0, -80.0), (0.0, 0.0)])
    tip, = basement_tips(ref, cur, MATERIALS, OutcomeOptions(fault_x=(1500.0,)))
    assert tip.dip_direction == "left" and tip.side(1000.0) == "hanging wall"


def test_options_are_checked():
    with pytest.raises(ValueError, match="keystone"):
        OutcomeOptions(scene="keystone", fault_x=(1000.0,))
    with pytest.raises(ValueError, match="scene"):
        OutcomeOptions(scene="graben")


# ------------------------------------------------------------ command line

def write_run(tmp_path, frames, times):
    paths = []
    for f, t in zip(frames, times):
        f.time = t
        paths.append(tmp_path / f"dump.run.{f.timestep}.txt")
        write_dump(paths[-1], [f])
    return str(tmp_path / "dump.run.*.txt")


def test_cli_outcomes_with_rate(capsys, tmp_path):
    ref, cur = planted_cover_fault(SPEC, 1790.0, 60.0, 100.0)
    half = planted_cover_fault(SPEC, 1790.0, 60.0, 50.0)[1]
    half.timestep = 500
    dumps = write_run(tmp_path, [ref, half, cur], [10.0, 1010.0, 2010.0])   # 0.05 m/s: 0, 50, 100 m
    assert [f.time for f in iter_frames(dumps)] == [10.0, 1010.0, 2010.0]
    out = tmp_path / "out"
    rc = main(["outcomes", dumps, "--rate", "0.05", "--at", "100", "--fault-x", "1500", "-o", str(out), "-q"])
    assert rc == 0, capsys.readouterr().err
    res = json.loads((out / "outcomes.json").read_text())
    st, = res["frames"]
    assert (st["frame"], st["previous_frame"]) == (2, 1)
    assert st["displacement_m"] == pytest.approx(100.0) and st["previous_displacement_m"] == pytest.approx(50.0)
    assert "0.05 m/s" in res["displacement_source"]
    f, = st["faults"]["list"]
    assert f["active"] and f["in_finite_strain"] and f["throw_m"] == pytest.approx(100.0, rel=0.2)
    md = (out / "outcomes.md").read_text()
    assert "| outcome | 100 m |" in md and "| F1 |" in md and "synthetic" in md
    assert "1 cover fault(s)" in capsys.readouterr().out

    # --rate in figure too (the same stage picking)
    rc = main(["figure", dumps, "--rate", "0.05", "--at", "100", "-o", str(out), "-q"])
    assert rc == 0
    fig = json.loads((out / "paper_figure.json").read_text())
    assert [(s["frame"], s["previous_frame"]) for s in fig["stages"]] == [(2, 1)]


def test_cli_rate_needs_time(capsys, tmp_path):
    ref, cur = planted_cover_fault(SPEC, 1790.0, 60.0, 100.0)
    dumps = write_run(tmp_path, [ref, cur], [None, None])
    assert main(["outcomes", dumps, "--rate", "0.05", "-o", str(tmp_path / "o"), "-q"]) == 2
    assert "ITEM: TIME" in capsys.readouterr().err
    # without the rate the displacement comes from --disp-per-step
    assert main(["outcomes", dumps, "--disp-per-step", "0.1", "--at", "100", "-o", str(tmp_path / "o"), "-q"]) == 0
    st, = json.loads((tmp_path / "o" / "outcomes.json").read_text())["frames"]
    assert st["frame"] == 1 and st["faults"]["count"] == 1
