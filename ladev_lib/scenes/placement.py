"""Collision-free placement of objects on the table.

Each object's footprint is its upright bounding box, rotated by its yaw: an
oriented rectangle. Two footprints must be at least ``min_gap_m`` apart
(separating-axis test on the rectangles grown by half the gap). Objects with
a requested position keep it; the rest are drawn uniformly in the workspace
(or in their requested region of it) by rejection sampling, largest first.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.catalog import CatalogObject


@dataclass(frozen=True)
class Footprint:
    x: float
    y: float
    yaw_deg: float
    half_x: float
    half_y: float

    def corners(self) -> Array:
        c, s = math.cos(math.radians(self.yaw_deg)), math.sin(math.radians(self.yaw_deg))
        local = np.array([[1, 1], [1, -1], [-1, -1], [-1, 1]], dtype=float) * [self.half_x, self.half_y]
        rot = np.array([[c, -s], [s, c]])
        out: Array = local @ rot.T + [self.x, self.y]
        return out

    def axes(self) -> list[Array]:
        c, s = math.cos(math.radians(self.yaw_deg)), math.sin(math.radians(self.yaw_deg))
        return [np.array([c, s]), np.array([-s, c])]


def footprint(obj: CatalogObject, x: float, y: float, yaw_deg: float, grow_m: float = 0.0) -> Footprint:
    return Footprint(x, y, yaw_deg, obj.size_m[0] / 2 + grow_m, obj.size_m[1] / 2 + grow_m)


def overlaps(a: Footprint, b: Footprint) -> bool:
    """Separating-axis test for two oriented rectangles."""
    if math.hypot(a.x - b.x, a.y - b.y) > math.hypot(a.half_x, a.half_y) + math.hypot(b.half_x, b.half_y):
        return False
    ca, cb = a.corners(), b.corners()
    for axis in (*a.axes(), *b.axes()):
        pa, pb = ca @ axis, cb @ axis
        if pa.max() < pb.min() or pb.max() < pa.min():
            return False
    return True


@dataclass(frozen=True)
class PlacementRequest:
    obj: CatalogObject
    x: float | None = None
    y: float | None = None
    yaw_deg: float | None = None
    x_range: tuple[float, float] | None = None
    """Where a free object may go (clipped to the workspace); None: anywhere."""
    y_range: tuple[float, float] | None = None


@dataclass(frozen=True)
class Placed:
    obj: CatalogObject
    x: float
    y: float
    yaw_deg: float


class PlacementError(ValueError):
    """The objects cannot be placed without collision in the workspace."""


def _place_fixed(
    requests: list[PlacementRequest],
    fixed: list[int],
    yaws: dict[int, float],
    grow: float,
    placed: dict[int, Placed],
    prints: list[Footprint],
) -> str | None:
    """Place the objects at given coordinates; the first collision, described, or None."""
    for i in fixed:
        r = requests[i]
        assert r.x is not None and r.y is not None
        fp = footprint(r.obj, r.x, r.y, yaws[i], grow)
        for j, other in zip(placed, prints, strict=True):
            if overlaps(fp, other):
                return f"{r.obj.display_name!r} at ({r.x:.2f}, {r.y:.2f}) overlaps {requests[j].obj.display_name!r}"
        placed[i] = Placed(r.obj, r.x, r.y, yaws[i])
        prints.append(fp)
    return None


_TURNS = (0.0, 90.0, 45.0, 135.0)
_MAX_TURN_STEPS = 20000


def _turn_fixed(
    requests: list[PlacementRequest], fixed: list[int], yaws: dict[int, float], grow: float
) -> dict[int, float] | None:
    """Yaws for the objects at given coordinates that clear each other (given yaws kept), or None."""
    options: list[list[Footprint]] = []
    for i in fixed:
        r = requests[i]
        assert r.x is not None and r.y is not None
        turns = [yaws[i]] if r.yaw_deg is not None else [*_TURNS, yaws[i]]
        options.append([footprint(r.obj, r.x, r.y, yaw, grow) for yaw in turns])
    chosen: list[Footprint] = []
    steps = 0

    def search(k: int) -> bool:
        nonlocal steps
        if k == len(options):
            return True
        for fp in options[k]:
            steps += 1
            if steps > _MAX_TURN_STEPS:
                return False
            if not any(overlaps(fp, other) for other in chosen):
                chosen.append(fp)
                if search(k + 1):
                    return True
                chosen.pop()
        return False

    if not search(0):
        return None
    return {i: fp.yaw_deg for i, fp in zip(fixed, chosen, strict=True)}


def _nudge_fixed(
    requests: list[PlacementRequest],
    fixed: list[int],
    yaws: dict[int, float],
    grow: float,
    nudge_m: float,
    workspace_x: tuple[float, float],
    workspace_y: tuple[float, float],
) -> dict[int, tuple[float, float, float]] | None:
    """(x, y, yaw) for the objects at given coordinates, each moved as little as it must, in request order."""
    out: dict[int, tuple[float, float, float]] = {}
    prints: list[Footprint] = []
    for i in fixed:
        r = requests[i]
        assert r.x is not None and r.y is not None
        turns = [yaws[i]] if r.yaw_deg is not None else [*_TURNS, yaws[i]]
        spot = next(
            (
                fp
                for x, y in _rings(r.x, r.y, nudge_m, workspace_x, workspace_y)
                for fp in (footprint(r.obj, x, y, yaw, grow) for yaw in turns)
                if not any(overlaps(fp, other) for other in prints)
            ),
            None,
        )
        if spot is None:
            return None
        out[i] = (round(spot.x, 4), round(spot.y, 4), spot.yaw_deg)
        prints.append(spot)
    return out


def _rings(
    x0: float, y0: float, reach_m: float, workspace_x: tuple[float, float], workspace_y: tuple[float, float],
    step: float = 0.005,
) -> Iterator[tuple[float, float]]:
    """The given point, then points on rings ``step`` apart out to ``reach_m`` (inside the workspace)."""
    yield x0, y0
    for k in range(1, int(round(reach_m / step)) + 1):
        for a in range(8 * k):
            angle = 2 * math.pi * a / (8 * k)
            x, y = x0 + k * step * math.cos(angle), y0 + k * step * math.sin(angle)
            if workspace_x[0] <= x <= workspace_x[1] and workspace_y[0] <= y <= workspace_y[1]:
                yield x, y


def place_objects(
    requests: list[PlacementRequest],
    workspace_x: tuple[float, float],
    workspace_y: tuple[float, float],
    rng: np.random.Generator,
    min_gap_m: float = 0.02,
    max_tries: int = 400,
    nudge_m: float = 0.0,
) -> list[Placed]:
    """Positions and yaws for every request, in request order, or PlacementError.

    ``nudge_m`` > 0: given coordinates are approximate (a description's "(0.1, 0.2)"): an object
    whose coordinates collide moves to the nearest clear point at most this far away (the caller
    sees it in the returned position); 0: they collide, PlacementError.
    """
    grow = min_gap_m / 2
    placed: dict[int, Placed] = {}
    prints: list[Footprint] = []

    fixed = [i for i, r in enumerate(requests) if r.x is not None and r.y is not None]
    free = [i for i, r in enumerate(requests) if i not in fixed]
    yaws: dict[int, float] = {}
    for i in fixed:
        given = requests[i].yaw_deg
        yaws[i] = given if given is not None else float(rng.uniform(-180, 180))
    clash = _place_fixed(requests, fixed, yaws, grow, placed, prints)
    if clash is not None:
        # Objects at given coordinates with no given yaw may turn (square to the table, across it,
        # diagonally) to clear each other; only tried when the drawn yaws collide, so scenes that
        # placed before place the same. The turns are searched together (an earlier object may
        # have to turn for a later one to fit), depth first, in request order.
        turned = _turn_fixed(requests, fixed, yaws, grow)
        if turned is None and nudge_m > 0:
            moved = _nudge_fixed(requests, fixed, yaws, grow, nudge_m, workspace_x, workspace_y)
            if moved is not None:
                requests = [
                    PlacementRequest(r.obj, *moved[i][:2], moved[i][2]) if i in moved else r
                    for i, r in enumerate(requests)
                ]
                turned = {i: moved[i][2] for i in fixed}
        if turned is None:
            raise PlacementError(clash)
        placed.clear()
        prints.clear()
        for i in fixed:
            r = requests[i]
            assert r.x is not None and r.y is not None
            placed[i] = Placed(r.obj, r.x, r.y, turned[i])
            prints.append(footprint(r.obj, r.x, r.y, turned[i], grow))

    # Largest footprints first: they are the hardest to fit.
    # Objects confined to a region go before the others of the same size class.
    free.sort(
        key=lambda i: (
            requests[i].x_range is None and requests[i].y_range is None,
            -requests[i].obj.size_m[0] * requests[i].obj.size_m[1],
        )
    )
    for i in free:
        r = requests[i]
        xr = _clip(r.x_range, workspace_x)
        yr = _clip(r.y_range, workspace_y)
        for _ in range(max_tries):
            x = float(rng.uniform(*xr))
            y = float(rng.uniform(*yr))
            yaw = r.yaw_deg if r.yaw_deg is not None else float(rng.uniform(-180, 180))
            fp = footprint(r.obj, x, y, yaw, grow)
            if not any(overlaps(fp, other) for other in prints):
                placed[i] = Placed(r.obj, x, y, yaw)
                prints.append(fp)
                break
        else:
            raise PlacementError(
                f"no collision-free place for {r.obj.display_name!r} after {max_tries} tries "
                f"({len(requests)} objects in a {workspace_x[1] - workspace_x[0]:.2f} x "
                f"{workspace_y[1] - workspace_y[0]:.2f} m workspace)"
            )
    return [placed[i] for i in range(len(requests))]


def _clip(wanted: tuple[float, float] | None, bounds: tuple[float, float]) -> tuple[float, float]:
    """``wanted`` inside ``bounds``; an empty intersection collapses to the nearest edge."""
    if wanted is None:
        return bounds
    lo, hi = max(wanted[0], bounds[0]), min(wanted[1], bounds[1])
    if lo > hi:
        edge = bounds[0] if wanted[1] < bounds[0] else bounds[1]
        return (edge, edge)
    return (lo, hi)
