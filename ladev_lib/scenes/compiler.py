"""Operations -> a concrete, validated :class:`SceneSpec`, or a rejection with its reason.

    outcome = compile_operations(ops, catalog, seed=7, resolver=ObjectResolver(catalog))
    outcome.spec, outcome.reason, outcome.notes

What it does, in order:

1. resolves every named object against the catalog (:mod:`ladev_lib.scenes.resolve`);
   an unavailable object is left out and reported by name in the notes (or,
   with ``unknown_objects: reject``, rejects the scene; with ``substitute``,
   becomes a random one); one the task names rejects the scene;
2. makes sure the task's source and target are in the scene (they take the
   place of a random object, or are added) and that the task is possible with
   them (a put_in target must be a container the source fits in);
3. draws the random objects from the object set, never twins of the source or
   target, and places everything without collision with the minimum gap:
   coordinates as given, regions ("on the left") and relations ("near the
   bowl") as boxes of the workspace, the rest anywhere; a failed placement
   re-draws the random choices a few times before giving up;
4. applies lighting and camera changes, clamped to the study's bounds with a
   note when clamped; silence keeps the defaults;
5. validates the spec against the catalog and the bounds, and, for a study
   scene, against its design (object count, object set, environment, task).

Nothing here raises for a bad description: the outcome carries the reason.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError

from ladev_lib.catalog import Catalog, CatalogObject
from ladev_lib.scenes.feasibility import task_feasibility
from ladev_lib.scenes.operations import AddObject, Position, SceneOperations, TaskOperation
from ladev_lib.scenes.placement import PlacementError, PlacementRequest, place_objects
from ladev_lib.scenes.resolve import ObjectResolver, Resolution
from ladev_lib.scenes.sampling import sample_camera, sample_lighting, target_candidates
from ladev_lib.scenes.spec import CameraOffset, Lighting, SceneBounds, SceneSpec, parse_scene_spec
from ladev_lib.vocabulary import (
    OBJECT_SETS,
    TASKS_WITH_TARGET,
    ObjectSetName,
    Robot,
    TaskType,
    as_task,
)


class CompileConfig(BaseModel):
    """The ``compile:`` section of the configuration."""

    model_config = ConfigDict(extra="forbid")

    reader: Literal["tagged", "rules"] = Field(
        default="tagged",
        description="How the offline backend reads a description: tagged (the learned span tagger marks the "
        "phrases, the value rules read them) or rules (the rule reader alone). Other backends ignore it.",
    )
    min_gap_m: float = Field(default=0.02, ge=0, le=0.2, description="Minimum gap between objects.")
    match_threshold: float = Field(
        default=0.75, ge=0, le=1.01,
        description="Cosine similarity an embedding match needs; above 1 switches embedding matching off.",
    )
    embedding_model: str = Field(default="all-MiniLM-L6-v2", description="Sentence embedding model for matching.")
    unknown_objects: Literal["omit", "reject", "substitute"] = Field(
        default="omit",
        description="An object not in the catalog is left out and reported by name (omit), rejects the scene, "
        "or becomes a random one (substitute). One the task names always rejects the scene.",
    )
    default_num_objects: tuple[int, int] = Field(
        default=(1, 4), description="Range of objects (source + distractors) when the text names none."
    )
    default_object_set: ObjectSetName = Field(
        default="simpler", description="Set random objects come from when neither text nor study says."
    )
    near_distance_m: float = Field(
        default=0.06, gt=0, le=0.3, description="Largest edge-to-edge distance that still counts as 'near'."
    )
    placement_attempts: int = Field(default=10, ge=1, le=100, description="Re-draws of random choices.")
    check_design: bool = Field(default=True, description="Reject study scenes that do not match their design.")


APPROXIMATE_NUDGE_M = 0.15
"""Farthest an object at colliding coordinates read from a description is moved."""


@dataclass(frozen=True)
class DesignExpectation:
    """What a study scene must be (from ``scenes.parquet``)."""

    task: str
    num_objects: int
    object_set: str
    environment: str


@dataclass
class CompileOutcome:
    """A spec, or the reason there is none; notes on every adjustment."""

    spec: SceneSpec | None
    reason: str | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.spec is not None


class _Reject(Exception):
    """Internal: stop compiling with this reason."""


@dataclass
class _Slot:
    """One object to place: fixed, of a category, or random; where; and its role."""

    obj: CatalogObject | None = None
    category: str | None = None
    position: Position | None = None
    role: str = "distractor"
    mention: str | None = None


def _same(slot: _Slot, res: Resolution) -> bool:
    """Does this slot hold the object (or an object of the category) a mention resolved to?"""
    if res.obj is not None:
        return slot.obj is not None and slot.obj.id == res.obj.id
    if res.category is not None:
        return slot.category == res.category or (slot.obj is not None and slot.obj.category == res.category)
    return False


# -- regions of the workspace, from the robot's point of view ----------------------

_BAND = 1 / 3  # a side region is the outer third of the workspace along its axis


def region_box(
    region: str, bounds: SceneBounds
) -> tuple[tuple[float, float], tuple[float, float]]:
    """(x_range, y_range) of a named region of the workspace."""
    (x0, x1), (y0, y1) = bounds.workspace_x_m, bounds.workspace_y_m
    dx, dy = (x1 - x0) * _BAND, (y1 - y0) * _BAND
    xr, yr = (x0, x1), (y0, y1)
    parts = region.split("_")
    if "center" in parts:
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        return (cx - dx / 2, cx + dx / 2), (cy - dy / 2, cy + dy / 2)
    if "front" in parts:
        xr = (x1 - dx, x1)
    if "back" in parts:
        xr = (x0, x0 + dx)
    if "left" in parts:
        yr = (y1 - dy, y1)
    if "right" in parts:
        yr = (y0, y0 + dy)
    return xr, yr


def relation_box(
    relation: str, ref_x: float, ref_y: float, distance: float
) -> tuple[tuple[float, float], tuple[float, float]]:
    """(x_range, y_range) where an object related to a reference at (ref_x, ref_y) may go."""
    side = 0.05
    if relation == "left_of":
        return (ref_x - side, ref_x + side), (ref_y + 0.03, ref_y + distance + side)
    if relation == "right_of":
        return (ref_x - side, ref_x + side), (ref_y - distance - side, ref_y - 0.03)
    if relation == "in_front_of":
        return (ref_x + 0.03, ref_x + distance + side), (ref_y - side, ref_y + side)
    if relation == "behind":
        return (ref_x - distance - side, ref_x - 0.03), (ref_y - side, ref_y + side)
    # 'near': the square inscribed in the circle of radius `distance`, so every point is near.
    half = distance / math.sqrt(2)
    return (ref_x - half, ref_x + half), (ref_y - half, ref_y + half)


# -- the compiler ----------------------------------------------------------------------


class _Compilation:
    def __init__(
        self,
        ops: SceneOperations,
        catalog: Catalog,
        bounds: SceneBounds,
        config: CompileConfig,
        resolver: ObjectResolver,
        rng: np.random.Generator,
        object_set: str,
    ) -> None:
        self.ops, self.catalog, self.bounds, self.config = ops, catalog, bounds, config
        self.resolver, self.rng, self.object_set = resolver, rng, object_set
        self.notes: list[str] = []
        self.slots: list[_Slot] = []
        self.nudge_m = 0.0
        """How far an object at colliding coordinates may move (0: they are exact and collide)."""
        self.search = False
        """Placement searches systematically (and widens crowded regions) where sampling fails."""

    # -- objects -------------------------------------------------------------
    def resolve(self, mention: str, what: str) -> Resolution:
        res = self.resolver.resolve(mention)
        if res.kind == "embedding":
            self.notes.append(f"matched {res.describe()}")
        if not res.ok and (what != "object" or self.config.unknown_objects == "reject"):
            raise _Reject(f"unknown object: {res.describe()}" + ("" if what == "object" else f" ({what})"))
        return res

    def build_slots(self) -> None:
        for op in self.ops.objects:
            slot = self._slot_for(op)
            if slot is not None:
                self.slots.append(slot)
        if not self.ops.objects:
            lo, hi = self.config.default_num_objects
            n = int(self.rng.integers(lo, hi + 1))
            self.slots = [_Slot() for _ in range(n)]
            self.notes.append(f"no objects named: {n} random object(s)")
        # An object named only as a reference ("near the bowl") is in the scene too.
        for slot in list(self.slots):
            pos = slot.position
            if pos is not None and pos.relation is not None and pos.reference:
                res = self.resolve(pos.reference, "position reference")
                if not any(s is not slot and _same(s, res) for s in self.slots):
                    self._ensure(res, "reference", pos.reference)

    def _slot_for(self, op: AddObject) -> _Slot | None:
        if op.object is None or not op.object.strip():
            return _Slot(position=op.position)
        res = self.resolve(op.object, "object")
        if not res.ok and self.config.unknown_objects == "omit":
            self.notes.append(f"unavailable: {res.describe()}; left out")
            return None
        if not res.ok:
            self.notes.append(f"unavailable: {res.describe()}; a random object takes its place")
            return _Slot(position=op.position, mention=op.object)
        return _Slot(obj=res.obj, category=res.category, position=op.position, mention=op.object)

    def _ensure(self, res: Resolution, role: str, mention: str) -> _Slot:
        """The slot holding this object (or category); it takes a random slot or is added."""
        for slot in self.slots:
            if slot.role == "distractor" and _same(slot, res):
                return slot
        if res.obj is not None:
            # "two fruits" + "pick up the orange": the orange is one of the fruits.
            for slot in self.slots:
                if slot.role == "distractor" and slot.obj is None and slot.category == res.obj.category:
                    slot.obj, slot.mention = res.obj, mention
                    return slot
        for slot in self.slots:
            if slot.obj is None and slot.category is None and slot.role == "distractor":
                slot.obj, slot.category, slot.mention = res.obj, res.category, mention
                self.notes.append(f"the {role} {mention!r} was not among the described objects; it takes a random one's place")
                return slot
        slot = _Slot(obj=res.obj, category=res.category, mention=mention)
        self.slots.append(slot)
        self.notes.append(f"the {role} {mention!r} was not among the described objects; added")
        return slot

    # -- task ----------------------------------------------------------------
    def assign_task(self, task: TaskOperation) -> None:
        needs_target = task.type in TASKS_WITH_TARGET
        if task.source:
            src = self._ensure(self.resolve(task.source, "task source"), "source", task.source)
        else:
            src = self._pick_source()
        src.role = "source"
        if not needs_target:
            if task.target:
                self.notes.append(f"pick_up has no target; {task.target!r} ignored")
            return
        if task.target:
            tres = self.resolve(task.target, "task target")
            if tres.obj is not None and src.obj is not None and tres.obj.id == src.obj.id and not any(
                s is not src and s.obj is not None and s.obj.id == tres.obj.id for s in self.slots
            ):
                raise _Reject(f"impossible task: source and target are the same object ({task.target!r})")
            tgt = self._ensure(tres, "target", task.target)
            if tgt is src:
                raise _Reject(f"impossible task: source and target are the same object ({task.target!r})")
        else:
            tgt = self._pick_target(task.type, src)
        tgt.role = "target"

    def _pick_source(self) -> _Slot:
        for slot in self.slots:
            if slot.obj is not None and slot.obj.graspable:
                return slot
        for slot in self.slots:
            if slot.obj is None and slot.category is None:
                slot.obj = self._random_from([o for o in self._pool() if o.graspable])
                self.notes.append(f"no graspable object named: the source is a random {slot.obj.display_name!r}")
                return slot
        if self.slots and self.slots[0].category is not None:
            return self.slots[0]
        raise _Reject("impossible task: no graspable object in the scene to manipulate")

    def _pick_target(self, task: str, src: _Slot) -> _Slot:
        if src.obj is None and src.category is not None:
            src.obj = self._pick_in_category(src.category, exclude=set())
        assert src.obj is not None
        for slot in self.slots:
            if slot is not src and slot.obj is not None and task_feasibility(task, src.obj, slot.obj) is None:
                return slot
        candidates = target_candidates(task, src.obj, self._pool()) or target_candidates(
            task, src.obj, list(self.catalog)
        )
        if not candidates:
            raise _Reject(f"impossible task: no object in the catalog can be the {task} target for {src.obj.display_name!r}")
        choice = self._random_from(candidates)
        for slot in self.slots:
            if slot.obj is None and slot.category is None and slot.role == "distractor":
                slot.obj = choice
                self.notes.append(f"no target named: a random {choice.display_name!r}")
                return slot
        slot = _Slot(obj=choice)
        self.slots.append(slot)
        self.notes.append(f"no target named: added a random {choice.display_name!r}")
        return slot

    # -- random draws ------------------------------------------------------------
    def _pool(self) -> list[CatalogObject]:
        # an unknown set name selects nothing, as it always has: the draw then reports the empty pool
        return self.catalog.select(sets=[s for s in OBJECT_SETS if s == self.object_set])

    def _random_from(self, pool: list[CatalogObject]) -> CatalogObject:
        return pool[int(self.rng.integers(len(pool)))]

    def _pick_in_category(self, category: str, exclude: set[str]) -> CatalogObject:
        members = [o for o in self.catalog if o.category == category and o.id not in exclude]
        preferred = [o for o in members if o.set == self.object_set] or members
        if not preferred:
            raise _Reject(f"not enough objects of category {category!r} in the catalog")
        return self._random_from(preferred)

    def draw(self) -> list[CatalogObject]:
        """A concrete object per slot: fixed ones as they are, the rest drawn now."""
        fixed = [s.obj for s in self.slots if s.obj is not None]
        task_ids = {s.obj.id for s in self.slots if s.obj is not None and s.role != "distractor"}
        used = {o.id for o in fixed}
        out: list[CatalogObject] = []
        for slot in self.slots:
            if slot.obj is not None:
                out.append(slot.obj)
                continue
            if slot.category is not None:
                obj = self._pick_in_category(slot.category, exclude=used | task_ids)
                if slot.role == "source" and not obj.graspable:
                    graspable = [o for o in self.catalog if o.category == slot.category and o.graspable]
                    if not graspable:
                        raise _Reject(f"impossible task: no graspable {slot.category} in the catalog")
                    obj = self._random_from(graspable)
            else:
                pool = [o for o in self._pool() if o.id not in used]
                if not pool:
                    raise _Reject(f"too many objects: the {self.object_set} set has no more distinct objects")
                obj = self._random_from(pool)
            used.add(obj.id)
            out.append(obj)
        return out

    # -- placement ---------------------------------------------------------------
    def place(self, objs: list[CatalogObject]) -> list[tuple[float, float, float]]:
        """(x, y, yaw) per slot; relations are placed after their references."""
        placed: dict[int, tuple[float, float, float]] = {}
        pending = list(range(len(self.slots)))
        refs = {i: self._reference_index(i, objs) for i in pending}
        for _ in range(len(self.slots) + 1):
            ready = [i for i in pending if refs[i] is None or refs[i] in placed]
            if not ready:
                raise _Reject("cannot place the objects: their relative positions refer to each other in a circle")
            requests: list[PlacementRequest] = []
            order: list[int] = []
            for i, (x, y, yaw) in placed.items():
                requests.append(PlacementRequest(objs[i], x, y, yaw))
                order.append(i)
            for i in ready:
                requests.append(self._request(i, objs, placed, refs[i]))
                order.append(i)
            result = place_objects(
                requests, self.bounds.workspace_x_m, self.bounds.workspace_y_m, self.rng,
                min_gap_m=self.config.min_gap_m, nudge_m=self.nudge_m, search=self.search, notes=self.notes,
            )
            for i, p, r in zip(order, result, requests, strict=True):
                placed[i] = (p.x, p.y, p.yaw_deg)
                if r.x is not None and r.y is not None and math.hypot(p.x - r.x, p.y - r.y) > 1e-3:
                    self.notes.append(
                        f"{p.obj.display_name!r} moved {math.hypot(p.x - r.x, p.y - r.y) * 100:.1f} cm from "
                        f"({r.x:.2f}, {r.y:.2f}) to ({p.x:.2f}, {p.y:.2f}): the given point collides"
                    )
            pending = [i for i in pending if i not in placed]
            if not pending:
                break
        return [placed[i] for i in range(len(self.slots))]

    def _reference_index(self, i: int, objs: list[CatalogObject]) -> int | None:
        pos = self.slots[i].position
        if pos is None or pos.relation is None or pos.reference is None:
            return None
        res = self.resolver.resolve(pos.reference)
        for j, obj in enumerate(objs):
            if j != i and (
                (res.obj is not None and obj.id == res.obj.id)
                or (res.category is not None and obj.category == res.category)
            ):
                return j
        raise _Reject(f"cannot place {objs[i].display_name!r} {pos.relation} {pos.reference!r}: no such object in the scene")

    def _request(
        self, i: int, objs: list[CatalogObject], placed: dict[int, tuple[float, float, float]], ref: int | None
    ) -> PlacementRequest:
        obj, pos = objs[i], self.slots[i].position
        if pos is None:
            return PlacementRequest(obj)
        if pos.x is not None and pos.y is not None:
            x, y = pos.x, pos.y
            if self.nudge_m > 0:
                # a description's coordinates state no frame: a point off the table is taken to its nearest edge
                (x0, x1), (y0, y1) = self.bounds.workspace_x_m, self.bounds.workspace_y_m
                x, y = min(max(x, x0), x1), min(max(y, y0), y1)
                if (x, y) != (pos.x, pos.y):
                    self.notes.append(
                        f"{obj.display_name!r} at ({pos.x:.2f}, {pos.y:.2f}) is off the workspace: placed at its edge, "
                        f"({x:.2f}, {y:.2f})"
                    )
            return PlacementRequest(obj, x, y)
        if pos.region is not None:
            xr, yr = region_box(pos.region, self.bounds)
            return PlacementRequest(obj, x_range=xr, y_range=yr, widen=True)
        assert ref is not None and pos.relation is not None
        rx, ry, _ = placed[ref]
        # 'near' is measured between the footprints' edges, not their centres.
        reach = self.config.near_distance_m + obj.footprint_radius_m + objs[ref].footprint_radius_m
        xr, yr = relation_box(pos.relation, rx, ry, reach)
        return PlacementRequest(obj, x_range=xr, y_range=yr)

    # -- environment -------------------------------------------------------------
    def lighting(self) -> Lighting:
        ops = self.ops.lighting
        if not ops:
            return Lighting()
        if len(ops) > 1:
            self.notes.append(f"{len(ops)} lighting changes: the last one applies")
        op = ops[-1]
        if op.random:
            return sample_lighting("lighting", self.rng, self.bounds)
        limit = self.bounds.lighting_max_delta
        delta = op.intensity_delta
        if abs(delta) > limit:
            clamped = math.copysign(limit, delta)
            self.notes.append(f"lighting change {delta:+.2f} clamped to {clamped:+.2f} (bound ±{limit})")
            delta = clamped
        return Lighting(intensity_delta=round(delta, 4))

    def camera(self) -> CameraOffset:
        ops = self.ops.camera
        if not ops:
            return CameraOffset()
        if any(op.random for op in ops):
            return sample_camera("camera", self.rng, self.bounds)
        t = np.sum([op.translation_m for op in ops], axis=0)
        r = np.sum([op.rotation_deg for op in ops], axis=0)
        max_t, max_r = self.bounds.camera_max_translation_m, self.bounds.camera_max_rotation_deg
        norm = float(np.linalg.norm(t))
        if norm > max_t + 1e-9:
            self.notes.append(f"camera move {norm * 100:.1f} cm clamped to {max_t * 100:.1f} cm")
            # Truncate towards zero so that rounding cannot push the move past the bound.
            t = np.trunc(t * (max_t / norm) * 1e4) / 1e4
        for k, axis in enumerate(("roll", "pitch", "yaw")):
            if abs(r[k]) > max_r + 1e-9:
                self.notes.append(f"camera {axis} {r[k]:+.1f} deg clamped to {math.copysign(max_r, r[k]):+.1f} deg")
                r[k] = math.copysign(max_r, r[k])
        return CameraOffset.rounded(t, r)


def compile_operations(
    ops: SceneOperations,
    catalog: Catalog,
    *,
    seed: int = 0,
    bounds: SceneBounds | None = None,
    config: CompileConfig | None = None,
    resolver: ObjectResolver | None = None,
    object_set: str | None = None,
    default_task: str | None = "pick_up",
    robot: Robot = "panda",
    scene_id: str | None = None,
    expected: DesignExpectation | None = None,
    approximate_coordinates: bool = False,
) -> CompileOutcome:
    """Operations -> a validated SceneSpec (see the module docstring), never raising for data.

    ``approximate_coordinates``: the operations' coordinates were read from a description
    ("ADD plate to (-0.1, 0.05)", no frame or tolerance stated), so an object whose point
    collides moves to the nearest clear point (up to 15 cm, with a note); otherwise colliding
    coordinates reject the scene.
    """
    bounds = bounds or SceneBounds()
    config = config or CompileConfig()
    resolver = resolver or ObjectResolver(catalog, config.match_threshold, embedding_model=config.embedding_model)
    chosen_set = ops.object_set or object_set or config.default_object_set
    comp = _Compilation(ops, catalog, bounds, config, resolver, np.random.default_rng(seed), chosen_set)
    comp.nudge_m = APPROXIMATE_NUDGE_M if approximate_coordinates else 0.0
    try:
        spec = _compile(comp, seed, default_task, robot, scene_id, expected)
    except _Reject as exc:
        return CompileOutcome(None, str(exc), comp.notes)
    return CompileOutcome(spec, None, comp.notes)


def _compile(
    comp: _Compilation,
    seed: int,
    default_task: str | None,
    robot: Robot,
    scene_id: str | None,
    expected: DesignExpectation | None,
) -> SceneSpec:
    ops, bounds = comp.ops, comp.bounds
    if ops.error:
        raise _Reject(f"the description could not be read as a scene: {ops.error}")
    task = ops.task or (TaskOperation(type=_task_type(default_task)) if default_task else None)
    if task is None:
        raise _Reject("no task: give an instruction or a task type")
    comp.build_slots()
    comp.assign_task(task)
    if len(comp.slots) > bounds.max_objects:
        raise _Reject(
            f"too many objects: {len(comp.slots)} requested, the study allows at most {bounds.max_objects}"
        )
    last_error = ""
    unplaced: list[CatalogObject] | None = None
    for _ in range(comp.config.placement_attempts):
        objs = comp.draw()
        src_obj = objs[_index(comp, "source")]
        tgt_obj = objs[_index(comp, "target")] if task.type in TASKS_WITH_TARGET else None
        named = _fixed(comp, "source") and (tgt_obj is None or _fixed(comp, "target"))
        why = task_feasibility(task.type, src_obj, tgt_obj, strict=not named)
        if why:
            if _fixed(comp, "source") and (tgt_obj is None or _fixed(comp, "target")):
                raise _Reject(f"impossible task: {why}")
            last_error = why
            continue
        try:
            poses = comp.place(objs)
        except PlacementError as exc:
            last_error = str(exc)
            if all(s.obj is not None and s.position is not None and s.position.x is not None for s in comp.slots):
                break  # nothing random left to re-draw (nor for a search to move)
            unplaced = objs
            continue
        return _finish(comp, objs, poses, task.type, seed, robot, scene_id, expected)
    if unplaced is not None:
        # Sampling failed every time: search the last draw's layout systematically, widening crowded
        # regions (with a note). Only here, so that scenes that placed before place the same.
        comp.search = True
        try:
            poses = comp.place(unplaced)
        except PlacementError as exc:
            last_error = str(exc)
        else:
            return _finish(comp, unplaced, poses, task.type, seed, robot, scene_id, expected)
    raise _Reject(f"cannot place the objects without collision: {last_error}")


def _index(comp: _Compilation, role: str) -> int:
    return next(i for i, s in enumerate(comp.slots) if s.role == role)


def _fixed(comp: _Compilation, role: str) -> bool:
    return comp.slots[_index(comp, role)].obj is not None


def _finish(
    comp: _Compilation,
    objs: list[CatalogObject],
    poses: list[tuple[float, float, float]],
    task_type: str,
    seed: int,
    robot: Robot,
    scene_id: str | None,
    expected: DesignExpectation | None,
) -> SceneSpec:
    counts: dict[str, int] = {}
    names: list[str] = []
    for obj in objs:
        counts[obj.id] = counts.get(obj.id, 0) + 1
        names.append(obj.id if counts[obj.id] == 1 else f"{obj.id}_{counts[obj.id]}")
    objects = [
        {
            "name": name,
            "id": obj.id,
            "x": round(x, 4),
            "y": round(y, 4),
            "yaw_deg": round(math.remainder(yaw, 360.0), 2),
            "role": slot.role,
        }
        for name, obj, (x, y, yaw), slot in zip(names, objs, poses, comp.slots, strict=True)
    ]
    src = names[_index(comp, "source")]
    tgt = names[_index(comp, "target")] if task_type in TASKS_WITH_TARGET else None
    data = {
        "scene_id": scene_id,
        "robot": robot,
        "objects": objects,
        "lighting": comp.lighting().model_dump(),
        "camera": comp.camera().model_dump(),
        "task": {"type": task_type, "source": src, "target": tgt},
        "seed": seed,
    }
    try:
        spec = parse_scene_spec(data, catalog=comp.catalog, bounds=comp.bounds)
    except ValidationError as exc:
        raise _Reject("invalid scene: " + "; ".join(e["msg"].removeprefix("Value error, ") for e in exc.errors())) from None
    if expected is not None and comp.config.check_design:
        problems = design_mismatches(spec, expected, comp.catalog)
        if problems:
            raise _Reject("does not match the study design: " + "; ".join(problems))
    return spec


def design_mismatches(spec: SceneSpec, expected: DesignExpectation, catalog: Catalog) -> list[str]:
    """How a compiled scene differs from what its study design asked for."""
    out: list[str] = []
    if spec.task.type != expected.task:
        out.append(f"task is {spec.task.type}, the design wants {expected.task}")
    counted = sum(1 for o in spec.objects if o.role != "target")
    if counted != expected.num_objects:
        out.append(
            f"{counted} object(s) besides the target, the design wants {expected.num_objects}"
        )
    off_set = sorted({o.id for o in spec.objects if catalog.get(o.id).set != expected.object_set})
    if off_set:
        out.append(f"objects not from the {expected.object_set} set: {', '.join(off_set)}")
    lit, cam = spec.lighting.intensity_delta != 0, not spec.camera.is_default
    wanted = {"default": (False, False), "lighting": (True, False), "camera": (False, True)}[expected.environment]
    if (lit, cam) != wanted:
        have = "lighting and camera changed" if lit and cam else "lighting changed" if lit else (
            "camera moved" if cam else "default lighting and camera"
        )
        out.append(f"environment level {expected.environment!r}, but the scene has {have}")
    return out


def _task_type(name: str) -> TaskType:
    """The study's or caller's task name, checked: an unknown one rejects the scene with the reason."""
    try:
        return as_task(name)
    except ValueError as exc:
        raise _Reject(str(exc)) from None
