"""Top-down grasps for a parallel gripper, chosen from an object's surface points.

A grasp is a TCP position, a horizontal closing direction and the opening the
fingers need. Candidates are scored on the object's own shape: for every
closing direction (15 degree steps) and a few centres along the object's long
axis, the points in the vertical slab the fingers sweep must fit between the
open fingers, something must lie between the finger pads, the palm must stay
above the object's top, and the fingers must not land on a neighbour. That one
rule covers cans (grasped near the top), boxes (across the narrow side), fruit
(above the equator where the sphere is narrower than the opening), and thin
things lying down (spoons, markers, bananas: across their local width).

All lengths are metres; the gripper numbers are the Panda hand's.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import sapien

from ladev_lib.arrays import Array

MAX_OPENING_M = 0.08
"""Distance between the Panda finger pads when fully open."""
GRASP_CLEARANCE_M = 0.002
"""Room left between the open fingers and the object (each side, both together)."""
OPENING_MARGIN_M = 0.018
"""How much wider than the object the fingers open before coming down."""
# The Panda finger's collision boxes, measured in the TCP frame: a 1.5 cm thick pad
# section up to 2 cm above the TCP, a 2.6 cm thick knuckle from there to the palm.
FINGER_HALF_WIDTH_M = 0.011
"""Half the finger width, across the closing direction."""
FINGER_PAD_THICKNESS_M = 0.015
FINGER_KNUCKLE_THICKNESS_M = 0.026
FINGER_KNUCKLE_ABOVE_TCP_M = 0.02
TIP_BELOW_TCP_M = 0.01
"""Fingertips reach this far below the TCP (panda_hand_tcp)."""
PAD_HALF_HEIGHT_M = 0.009
"""Half the height of the finger pads around the TCP."""
MAX_TAPER_M = 0.006
"""Grasps where the object narrows by more than this across the pads are tried last."""
WIDER_ABOVE_M = 0.006
"""How much wider (per side) the object may be above the pads than between them."""
FACE_CONTACT_M = 0.004
"""Each pad must meet the object over this much of its height (a face, not an edge)."""
MIN_PAD_CONTACT_M = 0.008
"""The object must span this much of the pads' width (or all of its own) to be held."""
PALM_ABOVE_TCP_M = 0.037
"""The palm's underside is this far above the TCP: the deepest an object may enter."""
PALM_HALF_LENGTH_M = 0.104
PALM_HALF_WIDTH_M = 0.032
TABLE_CLEARANCE_M = 0.012
"""Lowest TCP height above the object's bottom: the fingertips stay 2.5 mm off the table."""
NEIGHBOUR_CLEARANCE_M = 0.004
"""Gap kept between the hand and another object."""
YAW_STEP_DEG = 15
TILTS_DEG = (0.0, 25.0, -25.0, 90.0, -90.0)
"""Leans of the hand about the closing axis: upright first, leaning away from tall
neighbours when the arm does not fit beside them upright, and from the side (90 degrees)
for tall things whose top is too narrow or too slanted to hold."""
TABLE_PATCH_M = 0.16
"""Half size of the patch of table leaning hands are checked against."""
TILT_SCORE_PER_RAD = 1.0


DOWN = np.array([0.0, 0.0, -1.0])


@dataclass(frozen=True)
class Grasp:
    """A grasp: TCP position, closing direction, approach direction and finger opening."""

    position: Array
    """(3,) world TCP position at the grasp."""
    closing: Array
    """(3,) unit horizontal vector from one finger to the other."""
    width_m: float
    """Object width between the pads."""
    opening_m: float
    """Distance between the pads to open to before descending."""
    score: float
    """Lower is better."""
    approach: Array = field(default_factory=lambda: DOWN.copy())
    """(3,) unit direction the hand moves in to grasp: straight down, or leaning (``tilt``)."""
    taper_m: float = 0.0
    """How much narrower the object is at the pads' upper edge than at their lower edge.
    A squeeze on a surface that narrows towards the palm pushes the object out of the hand
    (a bottle's neck, a ball above its equator): such grasps are kept for last."""

    @property
    def tapered(self) -> bool:
        return self.taper_m > MAX_TAPER_M

    @property
    def tilt_rad(self) -> float:
        """How far the approach leans from vertical."""
        return float(np.arccos(np.clip(-self.approach[2], -1.0, 1.0)))

    def pose(self) -> sapien.Pose:
        """TCP pose: z axis along ``approach``, fingers closing along ``closing`` (Panda)."""
        return grasp_pose(self.position, self.closing, self.approach)

    def flipped(self) -> Grasp:
        """The same grasp with the hand turned half a turn (the fingers swap sides)."""
        return replace(self, closing=-self.closing)



def grasp_pose(position: Array, closing: Array, approach: Array = DOWN) -> sapien.Pose:
    """TCP pose whose z axis is ``approach`` and y axis ``closing`` (Panda convention)."""
    a = np.asarray(approach, dtype=float) / np.linalg.norm(approach)
    c = np.asarray(closing, dtype=float).copy()
    c -= (c @ a) * a
    c /= np.linalg.norm(c)
    ortho = np.cross(c, a)
    matrix = np.eye(4)
    matrix[:3, :3] = np.stack([ortho, c, a], axis=1)
    matrix[:3, 3] = position
    return sapien.Pose(matrix)


def top_down_pose(position: Array, closing: Array) -> sapien.Pose:
    """TCP pose approaching straight down, fingers closing along ``closing``."""
    return grasp_pose(position, closing, DOWN)


def closing_of(pose: sapien.Pose) -> Array:
    """The closing direction (TCP y axis) of a TCP pose."""
    return np.asarray(pose.to_transformation_matrix()[:3, 1], dtype=float)


def _wrist_turn(closing_xy: Array, current_xy: Array) -> float:
    """Rotation (rad) from the current closing direction to ``closing_xy``, either sign."""
    cos = float(np.clip(abs(closing_xy @ current_xy), -1.0, 1.0))
    return float(np.arccos(cos))


def top_down_grasps(
    points: Array,
    obstacles: Array | None = None,
    current_closing: Array | None = None,
    support_z: float | None = None,
    tilts_deg: tuple[float, ...] = TILTS_DEG,
) -> list[Grasp]:
    """Feasible grasps from above of the object sampled by ``points``, best first.

    ``obstacles`` are points of every other object (for finger clearance);
    ``current_closing`` the gripper's present closing direction (less wrist turn is
    preferred); ``support_z`` the height of what the object rests on (default: its
    own bottom). ``tilts_deg`` are the leans of the hand about the closing axis to
    consider; a leaning grasp is checked exactly like an upright one, in the frame of
    the leaning hand.
    """
    from ladev_lib.policies.geometry import footprint_rectangle

    pts = np.asarray(points, dtype=float)
    bottom = float(pts[:, 2].min()) if support_z is None else float(support_z)
    centre, axes, half = footprint_rectangle(pts[:, :2])
    current = np.array([0.0, 1.0]) if current_closing is None else np.asarray(current_closing[:2])
    current = current / (np.linalg.norm(current) + 1e-12)
    obst = None if obstacles is None or len(obstacles) == 0 else np.asarray(obstacles, float)

    # Centres along the long axis: elongated things are held near the middle when they can
    # be, anywhere along their length when they must (a knife by its handle).
    reach = float(half[0] - half[1]) if half[0] - half[1] >= 0.01 else 0.0
    offsets = np.arange(0.0, reach + 1e-9, 0.01)
    offsets = np.unique(np.concatenate([offsets, -offsets]))
    max_width = MAX_OPENING_M - GRASP_CLEARANCE_M

    # A fixed fan of closing directions, plus the object's own sides (boxes are held square).
    side = float(np.arctan2(axes[1][1], axes[1][0]))
    yaws = np.concatenate([np.deg2rad(np.arange(0, 180, YAW_STEP_DEG)), [side, side + np.pi / 2]])
    grasps: list[Grasp] = []
    table = _table_points(centre, bottom)
    for tilt in np.deg2rad(tilts_deg):
        side_grasp = abs(tilt) > np.pi / 4
        # Upright, the table is kept off by the fingertip clearance; leaning, it is an
        # obstacle like any other (the lower fingertip corner, the palm of a side grasp).
        floor = bottom if tilt == 0 else -np.inf
        tilted_obstacles = table if obst is None else np.vstack([obst, table])
        # Side grasps hold the object by its middle part; the others come down from above.
        heights = _side_heights(pts, bottom) if side_grasp else [0.0]
        for yaw in yaws:
            c = np.array([np.cos(yaw), np.sin(yaw), 0.0])
            o = np.array([-c[1], c[0]])
            rot = _rotation(c, -tilt)
            for off in [0.0] if side_grasp else offsets:
                foot = centre + off * axes[0]
                # Judge a leaning grasp in the leaning hand's frame: turn the world about the
                # closing axis through the grasp's foot, so the hand stands upright in it.
                pivot = np.array([foot[0], foot[1], bottom])
                if tilt:
                    p_obj = (pts - pivot) @ rot.T + pivot
                    p_obs = (tilted_obstacles - pivot) @ rot.T + pivot
                else:
                    p_obj, p_obs = pts, obst
                for height in heights:
                    grasp_xy = (pivot + rot @ np.array([0.0, 0.0, height]))[:2]
                    grasp = _evaluate(p_obj[:, :2], p_obj[:, 2], grasp_xy, c[:2], o, floor,
                                      max_width, p_obs)
                    if grasp is None:
                        continue
                    position = (grasp.position - pivot) @ rot + pivot  # back to the world
                    approach = DOWN @ rot
                    turn = _wrist_turn(c[:2], current)
                    score = (4.0 * abs(off) + 2.0 * grasp.width_m + 0.02 * turn
                             + TILT_SCORE_PER_RAD * abs(float(tilt)))
                    # Of the two equivalent hand orientations, the one nearer the current one.
                    closing = c if c[:2] @ current >= 0 else -c
                    grasps.append(Grasp(position, closing, grasp.width_m, grasp.opening_m, score,
                                        approach, grasp.taper_m))
    grasps.sort(key=lambda g: g.score)
    return grasps


def _table_points(centre: Array, z: float) -> Array:
    """A patch of the table around an object, as obstacle points for leaning hands."""
    ticks = np.arange(-TABLE_PATCH_M, TABLE_PATCH_M + 1e-9, 0.008)
    gx, gy = np.meshgrid(ticks, ticks)
    return np.stack([gx.ravel() + centre[0], gy.ravel() + centre[1], np.full(gx.size, z - 0.001)], axis=1)


def _side_heights(points: Array, bottom: float) -> list[float]:
    """Heights above the object's foot to hold it at from the side (middle part, palm clear)."""
    tall = float(points[:, 2].max()) - bottom
    lowest = PALM_HALF_WIDTH_M + NEIGHBOUR_CLEARANCE_M + 0.004  # the palm stays off the table
    return sorted({round(max(lowest, f * tall), 3) for f in (0.5, 0.35, 0.65)})


def _rotation(axis: Array, angle: float) -> Array:
    """Rotation matrix about a unit ``axis`` by ``angle`` (right hand)."""
    x, y, z = axis / np.linalg.norm(axis)
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.asarray(np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * (k @ k))


def _evaluate(
    xy: Array,
    z: Array,
    centre: Array,
    c: Array,
    o: Array,
    bottom: float,
    max_width: float,
    obstacles: Array | None,
) -> Grasp | None:
    """The grasp with fingers closing along ``c`` through ``centre``, or None if none fits."""
    rel = xy - centre
    along_c, along_o = rel @ c, rel @ o
    in_slab = np.abs(along_o) <= FINGER_HALF_WIDTH_M + 0.004
    if not in_slab.any():
        return None
    under_palm = (np.abs(along_o) <= PALM_HALF_WIDTH_M) & (np.abs(along_c) <= PALM_HALF_LENGTH_M)
    palm_top = float(z[under_palm].max())
    slab_top = float(z[in_slab].max())
    # As deep as the palm and the table allow; higher up where the object is too wide
    # (a sphere is narrower above its equator).
    deepest = max(bottom + TABLE_CLEARANCE_M, palm_top - (PALM_ABOVE_TCP_M - 0.008))
    highest = slab_top + PAD_HALF_HEIGHT_M - 0.008  # the pads must still overlap the object
    for tcp_z in np.arange(deepest, highest + 1e-9, 0.005):
        swept = in_slab & (z >= tcp_z - TIP_BELOW_TCP_M)
        pads = in_slab & (np.abs(z - tcp_z) <= PAD_HALF_HEIGHT_M)
        if not pads.any() or np.ptp(along_o[pads]) < MIN_PAD_CONTACT_M:
            continue  # nothing, or only an edge, between the pads
        lo, hi = float(along_c[swept].min()), float(along_c[swept].max())
        if hi - lo > max_width:
            continue  # too wide here: higher up, where a ball is narrower
        pad_lo, pad_hi = float(along_c[pads].min()), float(along_c[pads].max())
        if pad_lo - lo > WIDER_ABOVE_M or hi - pad_hi > WIDER_ABOVE_M:
            continue  # wider above the pads: the fingers would close on that, not the pads
        if not (_face_contact(along_c[pads], z[pads], pad_lo)
                and _face_contact(along_c[pads], z[pads], pad_hi)):
            continue  # a pad would touch a corner or a slope, not a face
        grasp_xy = centre + 0.5 * (lo + hi) * c
        opening = min(MAX_OPENING_M, hi - lo + OPENING_MARGIN_M)
        if obstacles is not None and _fingers_hit(obstacles, grasp_xy, c, o, float(tcp_z), opening):
            continue
        position = np.array([grasp_xy[0], grasp_xy[1], float(tcp_z)])
        taper = _taper(along_c[pads], z[pads], float(tcp_z))
        return Grasp(position, np.array([c[0], c[1], 0.0]), hi - lo, opening, 0.0, taper_m=taper)
    return None


def _taper(along_c: Array, z: Array, tcp_z: float) -> float:
    """Width at the pads' lower edge minus width at their upper edge (z up, in the hand frame)."""
    lower, upper = z < tcp_z - 0.003, z > tcp_z + 0.003
    if not lower.any() or not upper.any():
        return 0.0
    return float(np.ptp(along_c[lower]) - np.ptp(along_c[upper]))


def _face_contact(along_c: Array, z: Array, extreme: float) -> bool:
    """True if the object's surface where a pad meets it (at ``extreme`` along the closing
    direction) runs along the pad for a few millimetres, rather than touching it at an
    edge: the points within 3 mm of the extreme span at least 4 mm of the pad's height."""
    touching = np.abs(along_c - extreme) <= 0.003
    return bool(touching.any() and np.ptp(z[touching]) >= FACE_CONTACT_M)

def _fingers_hit(
    obstacles: Array,
    grasp_xy: Array,
    c: Array,
    o: Array,
    tcp_z: float,
    opening: float,
) -> bool:
    """True if an obstacle point lies where the open hand (plus clearance) would go.

    The hand is two fingers from the tips to the palm, the space between them, and
    the palm with everything above it (the hand comes straight down).
    """
    rel = obstacles[:, :2] - grasp_xy
    along_c, along_o = np.abs(rel @ c), np.abs(rel @ o)
    zs = obstacles[:, 2]
    m = NEIGHBOUR_CLEARANCE_M
    near = along_o <= FINGER_HALF_WIDTH_M + m
    knuckle_z = tcp_z + FINGER_KNUCKLE_ABOVE_TCP_M
    pads = (
        near
        & (zs >= tcp_z - TIP_BELOW_TCP_M - m)
        & (along_c <= opening / 2 + FINGER_PAD_THICKNESS_M + m)
    )
    knuckles = near & (zs >= knuckle_z) & (along_c <= opening / 2 + FINGER_KNUCKLE_THICKNESS_M + m)
    palm = (
        (zs >= tcp_z + PALM_ABOVE_TCP_M - m)
        & (along_c <= PALM_HALF_LENGTH_M + m)
        & (along_o <= PALM_HALF_WIDTH_M + m)
    )
    return bool((pads | knuckles | palm).any())
