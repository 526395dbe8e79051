"""Collision-free placement of objects on the table.

Each object's footprint is its upright bounding box, rotated by its yaw: an
oriented rectangle. Two footprints must be at least ``min_gap_m`` apart
(separating-axis test on the rectangles grown by half the gap). Objects with
a requested position keep it; the rest are drawn uniformly in the workspace
(or in their requested region of it) by rejection sampling, largest first.

With ``search=True`` (a caller's last resort, after its own re-draws failed), a
failed sampling is followed by a systematic search: the free objects are packed
on a grid of their boxes (outward from each box's centre, then into each
corner), and a coarse region that still cannot hold its objects grows a step at
a time toward the workspace, staying on its side of the table, with a note.
Sampling that succeeds is never replaced, so scenes that place today place the
same.
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
    widen: bool = False
    """The box is a coarse region of the table ("on the left"): in a search it may grow toward the
    workspace, on its side of the table; False: a hard box (around a reference object)."""


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
    search: bool = False,
    notes: list[str] | None = None,
) -> list[Placed]:
    """Positions and yaws for every request, in request order, or PlacementError.

    ``nudge_m`` > 0: given coordinates are approximate (a description's "(0.1, 0.2)"): an object
    whose coordinates collide moves to the nearest clear point at most this far away (the caller
    sees it in the returned position); 0: they collide, PlacementError.

    ``search``: when sampling fails, search systematically before giving up, widening the boxes
    of ``widen`` requests if need be (see the module docstring); a note on every widened region
    goes to ``notes``. Sampling that succeeds gives the same layout either way.
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
    fixed_placed, fixed_prints = dict(placed), list(prints)
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
            failed = (
                f"no collision-free place for {r.obj.display_name!r} after {max_tries} tries "
                f"({len(requests)} objects in a {workspace_x[1] - workspace_x[0]:.2f} x "
                f"{workspace_y[1] - workspace_y[0]:.2f} m workspace)"
            )
            if not search:
                raise PlacementError(failed)
            found = _search(requests, free, fixed_placed, fixed_prints, workspace_x, workspace_y, grow, rng)
            if isinstance(found, str):
                raise PlacementError(f"{failed}; {found}")
            placed, widened = found
            if notes is not None:
                notes.extend(widened)
            break
    return [placed[i] for i in range(len(requests))]


# -- the systematic search: a last resort when sampling fails ------------------------

_Range = tuple[float, float]
_Box = tuple[_Range, _Range]

_GRID_STEP_M = 0.005
_GRID_MOST = 60
"""Grid points per axis at most (a box wider than 30 cm gets a coarser grid)."""
_WIDEN_CM = (1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 18, 21, 25)
"""How far a coarse region grows on each side, step by step (up to its side of the table)."""
_STRATEGIES: tuple[tuple[int, int, bool], ...] = (
    (0, 0, True),  # outward from the box's centre (objects anywhere: in a shuffled order)
    *((sx, sy, x_major) for x_major in (True, False) for sx in (1, -1) for sy in (1, -1)),  # into a corner
)


@dataclass(frozen=True)
class _Shape:
    """A grown footprint with what the overlap test needs, as plain floats (fast to test)."""

    x: float
    y: float
    radius: float
    inner: float
    """Radius of the circle inside it: two shapes whose inner circles meet overlap at any yaw."""
    bounds: tuple[float, float, float, float]
    corners: tuple[tuple[float, float], ...]
    axes: tuple[tuple[float, float], ...]
    square: bool
    """Its sides run along the table's axes: its bounds are the rectangle itself."""


@dataclass(frozen=True)
class _Template:
    """An object at one yaw, centred on the origin."""

    yaw_deg: float
    offsets: tuple[tuple[float, float], ...]
    axes: tuple[tuple[float, float], ...]
    reach: tuple[float, float]
    radius: float
    inner: float
    square: bool

    def at(self, x: float, y: float) -> _Shape:
        corners = tuple((x + dx, y + dy) for dx, dy in self.offsets)
        rx, ry = self.reach
        return _Shape(
            x, y, self.radius, self.inner, (x - rx, x + rx, y - ry, y + ry), corners, self.axes, self.square
        )


def _template(fp: Footprint) -> _Template:
    c, s = math.cos(math.radians(fp.yaw_deg)), math.sin(math.radians(fp.yaw_deg))
    offsets = tuple(
        (c * fp.half_x * sx - s * fp.half_y * sy, s * fp.half_x * sx + c * fp.half_y * sy)
        for sx, sy in ((1, 1), (1, -1), (-1, -1), (-1, 1))
    )
    reach = (max(abs(dx) for dx, _ in offsets), max(abs(dy) for _, dy in offsets))
    square = abs(s) < 1e-9 or abs(c) < 1e-9
    radius, inner = math.hypot(fp.half_x, fp.half_y), min(fp.half_x, fp.half_y)
    return _Template(fp.yaw_deg, offsets, ((c, s), (-s, c)), reach, radius, inner, square)


def _hit(a: _Shape, b: _Shape) -> bool:
    """:func:`overlaps` for shapes: a bounding-circle and a bounding-box test, then separating axes."""
    if math.hypot(a.x - b.x, a.y - b.y) > a.radius + b.radius:
        return False
    (ax0, ax1, ay0, ay1), (bx0, bx1, by0, by1) = a.bounds, b.bounds
    if ax1 < bx0 or bx1 < ax0 or ay1 < by0 or by1 < ay0:
        return False
    if a.square and b.square:
        return True
    for ux, uy in (*a.axes, *b.axes):
        pa = [px * ux + py * uy for px, py in a.corners]
        pb = [px * ux + py * uy for px, py in b.corners]
        if max(pa) < min(pb) or max(pb) < min(pa):
            return False
    return True


def _grid(lo: float, hi: float) -> list[float]:
    """Points from ``lo`` to ``hi``, both included, about ``_GRID_STEP_M`` apart, rounded to 0.1 mm."""
    if hi - lo < 1e-9:
        return [round(lo, 4)]
    n = min(_GRID_MOST, max(1, math.ceil((hi - lo) / _GRID_STEP_M - 1e-9)))
    out = [lo + (hi - lo) * k / n for k in range(n + 1)]
    # rounding must not leave the box (the spec keeps 0.1 mm)
    return [min(max(round(v, 4), math.ceil(lo * 1e4) / 1e4), math.floor(hi * 1e4) / 1e4) for v in out]


def _points(box: _Box, strategy: tuple[int, int, bool]) -> list[tuple[float, float]]:
    """The grid of a box in the order a strategy tries it."""
    (x0, x1), (y0, y1) = box
    pts = [(x, y) for x in dict.fromkeys(_grid(x0, x1)) for y in dict.fromkeys(_grid(y0, y1))]
    sx, sy, x_major = strategy
    if sx == 0:
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        pts.sort(key=lambda p: (round(math.hypot(p[0] - cx, p[1] - cy), 6), math.atan2(p[1] - cy, p[0] - cx)))
    elif x_major:
        pts.sort(key=lambda p: (sx * p[0], sy * p[1]))
    else:
        pts.sort(key=lambda p: (sy * p[1], sx * p[0]))
    return pts


def _pack(
    requests: list[PlacementRequest],
    order: list[int],
    boxes: dict[int, _Box],
    free_anywhere: set[int],
    templates: dict[int, list[_Template]],
    fixed: list[_Shape],
    strategy: tuple[int, int, bool],
    rng: np.random.Generator,
) -> dict[int, tuple[float, float, float]] | tuple[int, int]:
    """Each request in ``order`` at the first clear point of its box (in the strategy's order):
    (x, y, yaw) per request, or (the request that found none, how many were placed before it)."""
    shapes = list(fixed)
    out: dict[int, tuple[float, float, float]] = {}
    cache: dict[_Box, list[tuple[float, float]]] = {}
    for n, i in enumerate(order):
        box = boxes[i]
        if box not in cache:
            cache[box] = _points(box, strategy)
        pts = cache[box]
        if strategy[0] == 0 and i in free_anywhere:
            # an object that may go anywhere goes anywhere, not to the middle of the table
            pts = [pts[int(k)] for k in rng.permutation(len(pts))]
        inner = templates[i][0].inner
        spot = next(
            (
                (sh, t.yaw_deg)
                for x, y in pts
                if not any(math.hypot(x - o.x, y - o.y) < inner + o.inner for o in shapes)
                for t in templates[i]
                for sh in (t.at(x, y),)
                if not any(_hit(sh, other) for other in shapes)
            ),
            None,
        )
        if spot is None:
            return i, n
        shapes.append(spot[0])
        out[i] = (spot[0].x, spot[0].y, spot[1])
    return out


def _side_limit(box: _Box, workspace_x: _Range, workspace_y: _Range) -> _Box:
    """How far a coarse region may grow: the workspace, but a region on one side of the table's
    middle (along either axis) stays on that side ("left" keeps to the left half)."""

    def axis(r: _Range, w: _Range) -> _Range:
        mid = (w[0] + w[1]) / 2
        if r[1] <= mid + 1e-9:
            return (w[0], mid)
        if r[0] >= mid - 1e-9:
            return (mid, w[1])
        return w

    return axis(box[0], workspace_x), axis(box[1], workspace_y)


def _grown(box: _Box, by_m: float, limit: _Box) -> _Box:
    (x0, x1), (y0, y1) = box
    (lx0, lx1), (ly0, ly1) = limit
    return (max(lx0, x0 - by_m), min(lx1, x1 + by_m)), (max(ly0, y0 - by_m), min(ly1, y1 + by_m))


def _names(objs: list[CatalogObject]) -> str:
    names = [repr(o.display_name) for o in objs]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def _size(box: _Box) -> str:
    return f"{box[0][1] - box[0][0]:.2f} x {box[1][1] - box[1][0]:.2f} m"


def _search(
    requests: list[PlacementRequest],
    free: list[int],
    fixed_placed: dict[int, Placed],
    fixed_prints: list[Footprint],
    workspace_x: _Range,
    workspace_y: _Range,
    grow: float,
    rng: np.random.Generator,
) -> tuple[dict[int, Placed], list[str]] | str:
    """The free requests (in ``free``'s order) packed on grids of their boxes, around the objects
    already placed: (every placement, notes on widened regions), or why there is no layout.

    Every strategy is tried on the boxes as asked; when none fits everything, the coarse region
    of the object that stopped the best strategy (or of any that stopped one) grows a step, and
    the strategies run again, until a layout is found or no region can grow further.
    """
    base = {i: (_clip(requests[i].x_range, workspace_x), _clip(requests[i].y_range, workspace_y)) for i in free}
    anywhere = {i for i in free if requests[i].x_range is None and requests[i].y_range is None}
    group = {i: base[i] for i in free if requests[i].widen and i not in anywhere}
    members: dict[_Box, list[int]] = {}
    for i, g in group.items():
        members.setdefault(g, []).append(i)
    limits = {g: _side_limit(g, workspace_x, workspace_y) for g in members}
    level = dict.fromkeys(members, 0)

    def box_at(g: _Box, k: int) -> _Box:
        return g if k == 0 else _grown(g, _WIDEN_CM[k - 1] / 100, limits[g])

    templates: dict[int, list[_Template]] = {}
    for i in free:
        r = requests[i]
        turns = [r.yaw_deg] if r.yaw_deg is not None else list(_TURNS)
        templates[i] = [_template(footprint(r.obj, 0.0, 0.0, yaw, grow)) for yaw in turns]
    fixed = [_template(fp).at(fp.x, fp.y) for fp in fixed_prints]
    while True:
        boxes = {i: box_at(group[i], level[group[i]]) if i in group else base[i] for i in free}
        stops: list[tuple[int, int]] = []
        for strategy in _STRATEGIES:
            got = _pack(requests, free, boxes, anywhere, templates, fixed, strategy, rng)
            if isinstance(got, tuple):
                stops.append(got)
                continue
            placed = dict(fixed_placed)
            prints = list(fixed_prints)
            for i in free:
                x, y, yaw = got[i]
                fp = footprint(requests[i].obj, x, y, yaw, grow)
                if any(overlaps(fp, other) for other in prints):
                    break  # the fast test and the exact one disagree at a touch: not this layout
                placed[i] = Placed(requests[i].obj, x, y, yaw)
                prints.append(fp)
            else:
                notes = [
                    f"the region of {_names([requests[i].obj for i in members[g]])} ({_size(g)}) could not "
                    f"hold them: widened by {_WIDEN_CM[level[g] - 1]} cm on each side where the table "
                    f"allows, to {_size(box_at(g, level[g]))}"
                    for g in members
                    if level[g] > 0
                ]
                return placed, notes
        best = max(stops, key=lambda s: s[1])[0]
        growable = [g for g in members if level[g] < len(_WIDEN_CM) and box_at(g, level[g] + 1) != box_at(g, level[g])]
        can_grow = [g for g in growable if g == group.get(best)] or [
            g for g in growable if any(group.get(i) == g for i, _ in stops)
        ]
        if not can_grow:
            widened = [g for g in members if level[g] > 0]
            return "a systematic search found no layout either" + (
                f" (with the region of {_names([requests[i].obj for g in widened for i in members[g]])} "
                "widened as far as its side of the table allows)"
                if widened
                else ""
            )
        for g in can_grow:
            level[g] += 1


def _clip(wanted: tuple[float, float] | None, bounds: tuple[float, float]) -> tuple[float, float]:
    """``wanted`` inside ``bounds``; an empty intersection collapses to the nearest edge."""
    if wanted is None:
        return bounds
    lo, hi = max(wanted[0], bounds[0]), min(wanted[1], bounds[1])
    if lo > hi:
        edge = bounds[0] if wanted[1] < bounds[0] else bounds[1]
        return (edge, edge)
    return (lo, hi)
