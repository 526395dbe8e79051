"""Where to put a held object down: on a support, into a container, or next to a target.

Pure geometry on point sets (world frame, metres). The held object is given
relative to the TCP, together with the fingers that hold it, so every check
covers what the hand carries down: the object and the fingers around it.

- ``place_on``: over the centre of the target's top surface, at the gripper yaw
  (now, or a quarter turn either way) that keeps the most of the object over it.
- ``place_in``: over the centre of the container's opening (its rim), at the yaw
  that fits the opening best, lowered as deep as the container lets it go.
- ``place_near``: the spot around the target that is closest to it while the
  object and fingers keep a gap to the target, a larger gap to everything else,
  and the object ends closer to the target than to any other object.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.spatial import ConvexHull, Delaunay, cKDTree

from ladev_lib.arrays import Array
from ladev_lib.policies.geometry import footprint_rectangle
from ladev_lib.policies.grasping import (
    FINGER_HALF_WIDTH_M,
    FINGER_KNUCKLE_ABOVE_TCP_M,
    FINGER_KNUCKLE_THICKNESS_M,
    FINGER_PAD_THICKNESS_M,
    PALM_ABOVE_TCP_M,
    PALM_HALF_LENGTH_M,
    PALM_HALF_WIDTH_M,
    TIP_BELOW_TCP_M,
)

YAW_OPTIONS_RAD = (0.0, np.pi / 2, -np.pi / 2)
"""Turns of the wrist allowed between grasp and release (turning the held object)."""
TARGET_GAP_M = 0.012
"""move_near: gap between the released object (and fingers) and the target."""
OTHER_GAP_M = 0.02
"""move_near: gap kept to every other object."""
MIN_TRAVEL_M = 0.05
"""move_near: the object's centre moves at least this far."""
CLOSEST_MARGIN_M = 0.015
"""move_near: the object must end this much closer to the target than to any other."""
FITTED_YAWS = 4
"""on / in: how many wrist turns (best fitting first) to try lowering with."""
DESCENT_CLEARANCE_M = 0.004
DESCENT_STEP_M = 0.004


@dataclass(frozen=True)
class HeldObject:
    """What the gripper carries, relative to the TCP position (world axes)."""

    object_points: Array
    """(N, 3) the held object's surface, minus the TCP position."""
    finger_points: Array
    """(M, 3) the open fingers at release, minus the TCP position."""
    palm_points: Array = field(default_factory=lambda: np.zeros((0, 3)))
    """(K, 3) the hand's palm, minus the TCP position (checked on the way down only)."""

    def turned(self, yaw: float) -> HeldObject:
        """The same hand turned by ``yaw`` about the vertical through the TCP."""
        c, s = np.cos(yaw), np.sin(yaw)
        rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        return HeldObject(self.object_points @ rot.T, self.finger_points @ rot.T, self.palm_points @ rot.T)

    @property
    def all_points(self) -> Array:
        return np.vstack([self.object_points, self.finger_points, self.palm_points])

    @property
    def bottom_below_tcp(self) -> float:
        """How far the object's lowest point is below the TCP."""
        return float(-self.object_points[:, 2].min())


@dataclass(frozen=True)
class Placement:
    """A release: TCP position and the wrist turn to apply while carrying."""

    tcp_xy: Array
    yaw: float
    tcp_z: float | None = None
    """Set when the release height is decided by the geometry (on / in)."""


def finger_points(tcp_rotation: Array, opening_m: float) -> Array:
    """Points filling both open fingers (pad and knuckle), relative to the TCP (world axes).

    ``tcp_rotation`` is the TCP's 3x3 orientation: its y axis is the closing direction
    and its z axis points from the palm to the fingertips.
    """
    sideways = np.linspace(-FINGER_HALF_WIDTH_M, FINGER_HALF_WIDTH_M, 3)
    parts = []
    for thickness, z0, z1 in (
        (FINGER_PAD_THICKNESS_M, -TIP_BELOW_TCP_M, FINGER_KNUCKLE_ABOVE_TCP_M),
        (FINGER_KNUCKLE_THICKNESS_M, FINGER_KNUCKLE_ABOVE_TCP_M, PALM_ABOVE_TCP_M),
    ):
        across = np.linspace(opening_m / 2, opening_m / 2 + thickness, 4)
        above = np.linspace(z0, z1, 5)
        grid = np.array(np.meshgrid(sideways, across, above, indexing="ij")).reshape(3, -1).T
        for sign in (1.0, -1.0):
            # TCP frame: x sideways, y closing, z towards the fingertips (so "above" is -z).
            local = np.stack([grid[:, 0], sign * grid[:, 1], -grid[:, 2]], axis=1)
            parts.append(local @ np.asarray(tcp_rotation, dtype=float).T)
    return np.vstack(parts)


def palm_points(tcp_rotation: Array) -> Array:
    """Points on the underside and sides of the palm, relative to the TCP (world axes)."""
    across = np.linspace(-PALM_HALF_LENGTH_M, PALM_HALF_LENGTH_M, 9)
    sideways = np.linspace(-PALM_HALF_WIDTH_M, PALM_HALF_WIDTH_M, 3)
    above = np.linspace(PALM_ABOVE_TCP_M, PALM_ABOVE_TCP_M + 0.06, 3)
    grid = np.array(np.meshgrid(sideways, across, above, indexing="ij")).reshape(3, -1).T
    local = np.stack([grid[:, 0], grid[:, 1], -grid[:, 2]], axis=1)  # TCP z points to the fingertips
    return np.asarray(local @ np.asarray(tcp_rotation, dtype=float).T)


def lowest_free_height(
    held: HeldObject,
    tcp_xy: Array,
    obstacles: Array,
    z_high: float,
    z_low: float,
    clearance: float = DESCENT_CLEARANCE_M,
) -> float | None:
    """Lowest TCP height reachable straight down from ``z_high`` without touching obstacles.

    None if even ``z_high`` is blocked.
    """
    pts = held.all_points + np.array([tcp_xy[0], tcp_xy[1], 0.0])
    # Only obstacles under the hand's footprint can be met on the way straight down.
    lo, hi = pts[:, :2].min(axis=0) - clearance, pts[:, :2].max(axis=0) + clearance
    below = obstacles[np.all((obstacles[:, :2] >= lo) & (obstacles[:, :2] <= hi), axis=1)]
    if len(below) == 0:
        return z_low
    tree = cKDTree(below)
    best: float | None = None
    for z in np.arange(z_high, z_low - 1e-9, -DESCENT_STEP_M):
        dist, _ = tree.query(pts + np.array([0.0, 0.0, z]), k=1, distance_upper_bound=clearance)
        if np.isfinite(dist).any():
            break
        best = float(z)
    return best


def _inside_fraction(xy: Array, rect: tuple[Array, Array, Array]) -> float:
    centre, axes, half = rect
    rel = (xy - centre) @ axes.T
    return float(np.mean(np.all(np.abs(rel) <= half, axis=1)))


def _yaws_by_fit(held: HeldObject, centre: Array,
                 rect: tuple[Array, Array, Array]) -> list[float]:
    """Wrist turns (15 degree steps, up to a quarter turn), best fit over ``rect`` first.

    The fit is the share of the held object over the rectangle; smaller turns win ties.
    """
    def fit(yaw: float) -> float:
        turned = held.turned(yaw)
        rel = turned.object_points[:, :2] - turned.object_points[:, :2].mean(axis=0)
        return _inside_fraction(rel + centre, rect) - 0.02 * abs(yaw)
    options = [float(v) for v in np.deg2rad(np.arange(-90, 91, 15))]
    return sorted(options, key=fit, reverse=True)[:FITTED_YAWS]


def _tcp_for_object_at(held: HeldObject, object_xy: Array) -> Array:
    """TCP xy that puts the held object's footprint centre at ``object_xy``."""
    return np.asarray(object_xy - held.object_points[:, :2].mean(axis=0))


def _lowered(held: HeldObject, centre: Array, rect: tuple[Array, Array, Array],
             obstacles: Array, z_high: float, floor_z: float) -> list[Placement]:
    out = []
    for yaw in _yaws_by_fit(held, centre, rect):
        turned = held.turned(yaw)
        tcp_xy = _tcp_for_object_at(turned, centre)
        z = lowest_free_height(turned, tcp_xy, obstacles, z_high, floor_z + turned.bottom_below_tcp)
        if z is not None:
            out.append(Placement(tcp_xy, yaw, z))
    return out


def place_on(held: HeldObject, target: Array, others: Array, z_high: float) -> list[Placement]:
    """Releases over the middle of the target's top surface, just above it, best first."""
    top = target[target[:, 2] >= target[:, 2].max() - 0.01]
    rect = footprint_rectangle(top[:, :2])
    obstacles = np.vstack([target, others]) if len(others) else target
    return _lowered(held, rect[0], rect, obstacles, z_high, float(target[:, 2].max()))


def place_in(held: HeldObject, container: Array, others: Array, z_high: float) -> list[Placement]:
    """Releases over the middle of the container's rim, as deep as each fits, best first."""
    rim = container[container[:, 2] >= container[:, 2].max() - 0.012]
    centre, axes, half = footprint_rectangle(rim[:, :2])
    # The opening: the rim rectangle less a wall, so the fit looks at the hole.
    inner = (centre, axes, np.maximum(half - 0.01, 0.005))
    obstacles = np.vstack([container, others]) if len(others) else container
    return _lowered(held, centre, inner, obstacles, z_high, float(container[:, 2].min()))


class _Outline:
    """A convex 2-D footprint: its boundary at 5 mm spacing, for fast clearance checks."""

    def __init__(self, xy: Array, spacing: float = 0.005):
        hull = ConvexHull(xy)
        corners = xy[hull.vertices]
        pts = []
        for a, b in zip(corners, np.roll(corners, -1, axis=0), strict=True):
            n = max(1, int(np.ceil(np.linalg.norm(b - a) / spacing)))
            pts.append(a + np.outer(np.arange(n) / n, b - a))
        self.boundary = np.vstack(pts)
        self.centre = footprint_rectangle(corners)[0]  # the box centre, as the predicates use
        self._tri = Delaunay(corners)
        self._tree = cKDTree(self.boundary)

    def contains_any(self, pts: Array) -> bool:
        return bool((self._tri.find_simplex(pts) >= 0).any())

    def clearance(self, other: _Outline, offset: Array) -> float:
        """Distance between this outline and ``other`` moved by ``offset``; 0 if they overlap."""
        moved = other.boundary + offset
        if self.contains_any(moved) or other.contains_any(self.boundary - offset):
            return 0.0
        dist, _ = self._tree.query(moved, k=1)
        return float(np.min(dist))


def place_near(
    held: HeldObject,
    source_xy: Array,
    target: Array,
    others: dict[str, Array],
    region: tuple[tuple[float, float], tuple[float, float]],
) -> list[Placement]:
    """Release spots next to the target that keep the gaps and the ordering, closest first.

    ``source_xy`` is where the object is now (shorter carries are preferred);
    ``others`` the points of every other object by name; ``region`` the
    ((x_min, x_max), (y_min, y_max)) box the object's centre must stay in.
    Footprints are taken convex, which errs on the side of larger gaps.
    """
    tgt = _Outline(target[:, :2])
    rest = [_Outline(np.asarray(p)[:, :2]) for p in others.values() if len(p) >= 3]
    (x0, x1), (y0, y1) = region

    found: list[tuple[float, Placement]] = []
    for yaw in YAW_OPTIONS_RAD:
        turned = held.turned(yaw)
        obj_xy = turned.object_points[:, :2]
        centre = footprint_rectangle(obj_xy)[0]
        hand = _Outline(np.vstack([obj_xy, turned.finger_points[:, :2]]) - centre)
        for phi in np.deg2rad(np.arange(0, 360, 15)):
            u = np.array([np.cos(phi), np.sin(phi)])
            spot = _first_clear_spot(tgt, u, hand)
            if spot is None or not (x0 <= spot[0] <= x1 and y0 <= spot[1] <= y1):
                continue
            if any(o.clearance(hand, spot) < OTHER_GAP_M for o in rest):
                continue
            d_target = float(np.linalg.norm(spot - tgt.centre))
            if any(np.linalg.norm(spot - o.centre) < d_target + CLOSEST_MARGIN_M for o in rest):
                continue
            travel = float(np.linalg.norm(spot - source_xy))
            if travel < MIN_TRAVEL_M:
                continue  # it must visibly move (SimplerEnv counts moves over 3 cm)
            score = d_target + 0.1 * travel + 0.01 * abs(yaw)
            found.append((score, Placement(spot - centre, yaw)))
    found.sort(key=lambda item: item[0])
    return [p for _, p in found]


def _first_clear_spot(target: _Outline, direction: Array, hand: _Outline) -> Array | None:
    """Nearest hand centre along ``direction`` from the target where the hand clears it."""
    def clear(d: float) -> bool:
        return target.clearance(hand, target.centre + d * direction) >= TARGET_GAP_M

    coarse = next((d for d in np.arange(0.0, 0.4, 0.01) if clear(float(d))), None)
    if coarse is None:
        return None
    lo, hi = max(0.0, float(coarse) - 0.01), float(coarse)
    while hi - lo > 0.002:  # the clear spot nearest the target, to 2 mm
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if clear(mid) else (mid, hi)
    return np.asarray(target.centre + hi * direction)
