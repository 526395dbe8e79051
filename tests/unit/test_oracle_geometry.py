"""The oracle's geometry, without a simulator: grasp choice and placement on point sets."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from ladev_lib.policies.geometry import footprint_rectangle, surface_points
from ladev_lib.policies.grasping import (
    MAX_OPENING_M,
    TABLE_CLEARANCE_M,
    closing_of,
    grasp_pose,
    top_down_grasps,
)
from ladev_lib.policies.placing import (
    TARGET_GAP_M,
    HeldObject,
    finger_points,
    lowest_free_height,
    place_in,
    place_near,
    place_on,
)


def box(size: tuple[float, float, float], at: tuple[float, float] = (0.0, 0.0), yaw_deg: float = 0.0,
        z0: float = 0.0) -> np.ndarray:
    """Surface points of a box standing on z = z0."""
    mesh = trimesh.creation.box(extents=size)
    mesh.apply_translation([0.0, 0.0, size[2] / 2 + z0])
    mesh.apply_transform(trimesh.transformations.rotation_matrix(np.radians(yaw_deg), [0, 0, 1]))
    mesh.apply_translation([at[0], at[1], 0.0])
    return surface_points(mesh, 1500)


def sphere(diameter: float, at: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    mesh = trimesh.creation.icosphere(subdivisions=3, radius=diameter / 2)
    mesh.apply_translation([at[0], at[1], diameter / 2])
    return surface_points(mesh, 1500)


def cylinder(diameter: float, height: float, at: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    mesh = trimesh.creation.cylinder(radius=diameter / 2, height=height)
    mesh.apply_translation([at[0], at[1], height / 2])
    return surface_points(mesh, 1500)


def open_box(size: tuple[float, float, float], wall: float = 0.01) -> np.ndarray:
    """A container: floor and four walls."""
    sx, sy, sz = size
    parts = [
        ((sx, sy, wall), (0, 0, wall / 2)),
        ((wall, sy, sz), (sx / 2 - wall / 2, 0, sz / 2)),
        ((wall, sy, sz), (-sx / 2 + wall / 2, 0, sz / 2)),
        ((sx, wall, sz), (0, sy / 2 - wall / 2, sz / 2)),
        ((sx, wall, sz), (0, -sy / 2 + wall / 2, sz / 2)),
    ]
    meshes = []
    for extents, centre in parts:
        m = trimesh.creation.box(extents=extents)
        m.apply_translation(centre)
        meshes.append(m)
    return surface_points(trimesh.util.concatenate(meshes), 3000)


def held_cube(side: float, grasp_depth: float) -> HeldObject:
    """A cube held from above, the TCP ``grasp_depth`` below its top, gripper along y."""
    pts = box((side, side, side))
    rel = pts - np.array([0.0, 0.0, side - grasp_depth])
    rotation = grasp_pose(np.zeros(3), np.array([0.0, 1.0, 0.0])).to_transformation_matrix()[:3, :3]
    return HeldObject(rel, finger_points(rotation, side + 0.02))


# -- geometry -------------------------------------------------------------------------
def test_footprint_rectangle_finds_a_rotated_box() -> None:
    centre, axes, half = footprint_rectangle(box((0.12, 0.04, 0.02), at=(0.1, -0.05), yaw_deg=30)[:, :2])
    assert np.allclose(centre, [0.1, -0.05], atol=1e-3)
    assert np.allclose(half, [0.06, 0.02], atol=1e-3)
    assert abs(abs(axes[0] @ [np.cos(np.radians(30)), np.sin(np.radians(30))]) - 1) < 1e-3


# -- grasps ---------------------------------------------------------------------------
def test_box_is_grasped_across_its_narrow_side() -> None:
    grasps = top_down_grasps(box((0.10, 0.05, 0.04), yaw_deg=30))
    best = grasps[0]
    long_axis = np.array([np.cos(np.radians(30)), np.sin(np.radians(30)), 0.0])
    assert abs(best.closing @ long_axis) < 0.05
    assert best.width_m == pytest.approx(0.05, abs=0.004)
    assert best.tilt_rad == 0.0
    assert TABLE_CLEARANCE_M - 1e-6 <= best.position[2] <= 0.04
    # The pose closes the fingers along ``closing`` and points the fingers down.
    m = best.pose().to_transformation_matrix()
    assert np.allclose(m[:3, 1], best.closing) and np.allclose(m[:3, 2], [0, 0, -1])
    assert np.allclose(closing_of(best.pose()), best.closing)


def test_object_wider_than_the_gripper_has_no_grasp() -> None:
    assert top_down_grasps(box((0.10, 0.09, 0.05))) == []


def test_wide_sphere_is_grasped_above_its_equator() -> None:
    grasps = top_down_grasps(sphere(0.08))
    assert grasps, "an 8 cm ball fits the 8 cm opening above its equator"
    best = grasps[0]
    assert best.position[2] > 0.04 + 0.005
    assert best.width_m <= MAX_OPENING_M


def test_tall_can_is_grasped_near_its_top() -> None:
    best = top_down_grasps(cylinder(0.066, 0.123))[0]
    # The palm keeps the hand from going deeper than about 3 cm below the top.
    assert 0.123 - 0.04 < best.position[2] < 0.123 - 0.01
    assert best.width_m == pytest.approx(0.066, abs=0.004)


def test_long_flat_object_is_held_by_its_raised_part() -> None:
    """A knife-like object: a 1.5 cm handle and a 3 mm blade; only the handle is graspable."""
    handle = box((0.06, 0.02, 0.015), at=(-0.06, 0.0))
    blade = box((0.12, 0.02, 0.003), at=(0.03, 0.0))
    grasps = top_down_grasps(np.vstack([handle, blade]))
    assert grasps
    assert grasps[0].position[0] < -0.025, "the best grasp is on the handle"
    assert all(g.position[0] < -0.01 for g in grasps), "no grasp pinches the bare blade"


def test_neighbour_beside_the_object_turns_the_fingers_away() -> None:
    cube = box((0.03, 0.03, 0.03))
    free = top_down_grasps(cube)
    assert any(abs(g.closing[0]) > 0.95 for g in free), "without neighbours, closing along x is fine"
    wall = box((0.02, 0.2, 0.2), at=(0.055, 0.0))  # 4 cm beside the cube, on +x
    blocked = top_down_grasps(cube, obstacles=wall, tilts_deg=(0.0,))
    assert blocked, "closing along y keeps the fingers off the neighbour"
    assert all(abs(g.closing[0]) < 0.5 for g in blocked)


def test_a_hand_that_cannot_stand_beside_a_tall_neighbour_leans_away() -> None:
    cube = box((0.02, 0.02, 0.03))
    wall = box((0.3, 0.02, 0.3), at=(0.0, 0.038))  # tall, 1.8 cm beside the cube on +y
    upright = top_down_grasps(cube, obstacles=wall, tilts_deg=(0.0,))
    leaning = [g for g in top_down_grasps(cube, obstacles=wall) if g.tilt_rad > 0]
    assert not upright, "upright, the palm would hit the tall wall"
    assert leaning and all(g.approach[1] > 0 for g in leaning), "the palm leans away from the wall"


# -- placing --------------------------------------------------------------------------
def test_lowest_free_height_stops_above_an_obstacle() -> None:
    held = held_cube(0.03, grasp_depth=0.015)
    block = box((0.1, 0.1, 0.05))
    z = lowest_free_height(held, np.zeros(2), block, z_high=0.3, z_low=0.0)
    assert z is not None
    bottom = z - held.bottom_below_tcp
    assert 0.05 < bottom < 0.05 + 0.012
    assert lowest_free_height(held, np.array([0.5, 0.5]), block, 0.3, 0.02) == 0.02


def test_place_on_releases_over_the_middle_of_the_target_just_above_it() -> None:
    held = held_cube(0.03, grasp_depth=0.015)
    target = box((0.12, 0.08, 0.02), at=(0.2, 0.1), yaw_deg=20)
    spots = place_on(held, target, np.zeros((0, 3)), z_high=0.3)
    assert spots
    best = spots[0]
    assert best.tcp_z is not None
    centre = best.tcp_xy + held.turned(best.yaw).object_points[:, :2].mean(axis=0)
    assert np.allclose(centre, [0.2, 0.1], atol=0.01)
    bottom = best.tcp_z - held.bottom_below_tcp
    assert 0.02 < bottom < 0.035


def test_place_in_lowers_the_object_below_the_rim() -> None:
    held = held_cube(0.03, grasp_depth=0.015)
    bowl = open_box((0.16, 0.12, 0.08))
    spots = place_in(held, bowl, np.zeros((0, 3)), z_high=0.3)
    assert spots
    tcp_z = spots[0].tcp_z
    assert tcp_z is not None
    assert tcp_z - held.bottom_below_tcp < 0.08 - 0.02, "the cube goes into the box"


def test_place_near_keeps_a_gap_and_ends_nearest_the_target() -> None:
    held = held_cube(0.03, grasp_depth=0.015)
    target = box((0.05, 0.05, 0.05))
    other = box((0.05, 0.05, 0.05), at=(0.12, 0.0))
    spots = place_near(held, np.array([-0.2, 0.0]), target, {"other": other}, ((-0.5, 0.5), (-0.5, 0.5)))
    assert spots
    spot = spots[0]
    turned = held.turned(spot.yaw)
    obj = turned.object_points[:, :2] + spot.tcp_xy
    centre = obj.mean(axis=0)
    gap = np.min(np.linalg.norm(obj[:, None, :] - target[None, ::5, :2], axis=2))
    assert gap >= TARGET_GAP_M - 0.003
    assert np.linalg.norm(centre) + 0.01 < np.linalg.norm(centre - [0.12, 0.0])
    assert np.linalg.norm(centre) < 0.025 + 0.02 + 0.05, "right next to the target"


def test_place_near_finds_nothing_when_the_only_room_is_closer_to_another_object() -> None:
    held = held_cube(0.03, grasp_depth=0.015)
    target = box((0.05, 0.05, 0.05))
    region = ((-0.05, 0.05), (-0.05, 0.05))  # no room beside the target inside this region
    assert place_near(held, np.zeros(2), target, {}, region) == []


def test_bottle_neck_grasps_are_marked_tapered_and_the_body_is_held_from_the_side() -> None:
    body = trimesh.creation.cylinder(radius=0.03, height=0.14)
    body.apply_translation([0.0, 0.0, 0.07])
    neck = trimesh.creation.cone(radius=0.03, height=0.06)  # narrows from 6 cm to a point
    neck.apply_translation([0.0, 0.0, 0.14])
    bottle = surface_points(trimesh.util.concatenate([body, neck]), 3000)
    grasps = top_down_grasps(bottle)
    from_above = [g for g in grasps if g.tilt_rad < 0.1]
    side = [g for g in grasps if g.tilt_rad > 1.5 and not g.tapered]
    assert from_above and all(g.tapered for g in from_above), "the neck narrows into the palm"
    assert side, "the straight body can be held from the side"
    best = side[0]
    assert abs(best.approach[2]) < 1e-6, "a side grasp approaches horizontally"
    assert 0.04 < best.position[2] < 0.13 and best.width_m <= MAX_OPENING_M
