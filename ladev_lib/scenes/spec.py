"""``SceneSpec``: a concrete, validated description of one test scene.

Frames and units
----------------
Object positions are in the *workspace frame*, shared by every robot: origin
at the centre of the workspace on the table top, ``x`` pointing away from the
robot (forward), ``y`` to the robot's left, ``z`` up; metres. Each robot maps
this frame onto its own world (``ladev_lib.sim``), so one spec can be rolled
out with any embodiment. Yaw is about ``z`` in degrees, counter-clockwise seen
from above.

Lighting is a relative change of every light's intensity: the scene's lights
are scaled by ``1 + intensity_delta``; the paper bounds it to ±0.5.

The camera change is relative to the robot's default policy camera:
``translation_m`` is added to its position, in the workspace frame
(``[0, 0.03, 0]`` moves it 3 cm to the robot's left); ``rotation_deg`` is
applied in the camera's own frame as roll (about its viewing axis), pitch
(positive tilts the view down) and yaw (positive pans the view left).

Validation
----------
Rules that need nothing else hold always (roles, task arity, lighting range).
Rules that need the catalog or the study's bounds run when those are given,
through :func:`parse_scene_spec` or ``model_validate(..., context=...)``:
unknown object ids, capabilities (a put_in target must be a container),
positions outside the workspace, camera changes beyond the configured bounds.
Every message starts with the offending field and names the allowed range.
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationInfo, model_validator

from ladev_lib.scenes.feasibility import task_feasibility
from ladev_lib.vocabulary import TASKS_WITH_TARGET, Robot, Role, TaskType

if TYPE_CHECKING:
    from ladev_lib.catalog import Catalog

SCENE_SPEC_VERSION: Literal[1] = 1

MAX_LIGHTING_DELTA = 0.5


class SceneBounds(BaseModel):
    """Limits a study puts on scenes. Defaults follow the paper."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    workspace_x_m: tuple[float, float] = (-0.15, 0.15)
    workspace_y_m: tuple[float, float] = (-0.25, 0.25)
    max_objects: int = Field(
        default=6, ge=1, le=12, description="Objects in a scene, the target included."
    )
    lighting_max_delta: float = Field(default=0.5, gt=0, le=MAX_LIGHTING_DELTA)
    camera_max_translation_m: float = Field(default=0.05, ge=0, le=0.5)
    camera_max_rotation_deg: float = Field(default=5.0, ge=0, le=45)


class ObjectPlacement(BaseModel):
    """One object on the table."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    name: str = Field(
        min_length=1,
        description="Instance name, unique in the scene; the task refers to objects by it. "
        "Usually the catalog id, with a suffix (_2, _3) for repeats.",
    )
    id: str = Field(min_length=1, description="Catalog id of the object model.")
    x: float = Field(description="Forward position in the workspace frame, metres.")
    y: float = Field(description="Leftward position in the workspace frame, metres.")
    yaw_deg: float = Field(default=0.0, ge=-180.0, le=180.0, description="Yaw about z, degrees.")
    role: Role = Field(default="distractor", description="source | target | distractor")


class Lighting(BaseModel):
    """Scene lighting relative to the default."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    intensity_delta: float = Field(
        default=0.0,
        ge=-MAX_LIGHTING_DELTA,
        le=MAX_LIGHTING_DELTA,
        description="Relative change of every light's intensity: lights x (1 + delta). "
        "Allowed range [-0.5, 0.5].",
    )


class CameraOffset(BaseModel):
    """Policy-camera change relative to the robot's default camera pose."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    translation_m: tuple[float, float, float] = Field(
        default=(0.0, 0.0, 0.0), description="[x, y, z] shift in the workspace frame, metres."
    )
    rotation_deg: tuple[float, float, float] = Field(
        default=(0.0, 0.0, 0.0),
        description="[roll, pitch, yaw] in the camera's frame, degrees "
        "(pitch > 0 tilts down, yaw > 0 pans left).",
    )

    @classmethod
    def rounded(cls, translation_m: Iterable[float], rotation_deg: Iterable[float]) -> CameraOffset:
        """From any three-number sequences (numpy arrays too), rounded to 0.1 mm and 0.01 deg."""
        t = [round(float(v), 4) for v in translation_m]
        r = [round(float(v), 2) for v in rotation_deg]
        if len(t) != 3 or len(r) != 3:
            raise ValueError(f"camera offset needs three numbers each, got {t} and {r}")
        return cls(translation_m=(t[0], t[1], t[2]), rotation_deg=(r[0], r[1], r[2]))

    @property
    def is_default(self) -> bool:
        return not any(self.translation_m) and not any(self.rotation_deg)

    @property
    def translation_norm_m(self) -> float:
        return float(sum(v * v for v in self.translation_m) ** 0.5)


class TaskSpec(BaseModel):
    """What the robot is asked to do, by object instance name."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    type: TaskType
    source: str = Field(min_length=1, description="Name of the object to manipulate.")
    target: str | None = Field(
        default=None,
        description="Name of the reference object (move_near, put_on, put_in); null for pick_up.",
    )


class SceneSpec(BaseModel):
    """A concrete scene: robot, objects at poses, lighting, camera, task, seed."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    schema_version: Literal[1] = SCENE_SPEC_VERSION
    scene_id: str | None = Field(default=None, description="Identifier within a study.")
    robot: Robot = "panda"
    objects: tuple[ObjectPlacement, ...] = Field(min_length=1)
    lighting: Lighting = Lighting()
    camera: CameraOffset = CameraOffset()
    task: TaskSpec
    seed: int = Field(default=0, ge=0, description="Seed for everything random in the episode.")

    @model_validator(mode="after")
    def _validate(self, info: ValidationInfo) -> SceneSpec:
        ctx = info.context or {}
        problems = check_scene_spec(self, catalog=ctx.get("catalog"), bounds=ctx.get("bounds"))
        if problems:
            raise ValueError("; ".join(problems))
        return self

    # -- conveniences --------------------------------------------------------
    def object(self, name: str) -> ObjectPlacement:
        for o in self.objects:
            if o.name == name:
                return o
        raise KeyError(f"scene has no object named {name!r}")

    @property
    def source(self) -> ObjectPlacement:
        return self.object(self.task.source)

    @property
    def target(self) -> ObjectPlacement | None:
        return self.object(self.task.target) if self.task.target else None

    def to_json(self) -> str:
        return self.model_dump_json()

    @classmethod
    def from_json(
        cls,
        text: str,
        catalog: Catalog | None = None,
        bounds: SceneBounds | None = None,
    ) -> SceneSpec:
        return parse_scene_spec(json.loads(text), catalog=catalog, bounds=bounds)


def check_scene_spec(
    spec: SceneSpec,
    catalog: Catalog | None = None,
    bounds: SceneBounds | None = None,
) -> list[str]:
    """Every problem with ``spec``, each starting with the field it concerns."""
    problems: list[str] = []
    names = [o.name for o in spec.objects]
    for name, n in Counter(names).items():
        if n > 1:
            problems.append(f"objects: name {name!r} is used {n} times; names must be unique")

    roles = Counter(o.role for o in spec.objects)
    needs_target = spec.task.type in TASKS_WITH_TARGET
    if roles["source"] != 1:
        problems.append(f"objects[].role: exactly one object must be 'source', found {roles['source']}")
    if roles["target"] > 1:
        problems.append(f"objects[].role: at most one object may be 'target', found {roles['target']}")
    if needs_target and spec.task.target is None:
        problems.append(f"task.target: required for {spec.task.type}")
    if not needs_target and spec.task.target is not None:
        problems.append(f"task.target: must be null for {spec.task.type}")
    if needs_target and roles["target"] == 0:
        problems.append(f"objects[].role: {spec.task.type} needs one object with role 'target'")
    if not needs_target and roles["target"]:
        problems.append(f"objects[].role: {spec.task.type} has no target, but an object has role 'target'")
    if spec.task.target is not None and spec.task.target == spec.task.source:
        problems.append("task.target: must differ from task.source")

    by_name = {o.name: o for o in spec.objects}
    refs: list[tuple[str, str | None, str]] = [
        ("task.source", spec.task.source, "source"),
        ("task.target", spec.task.target, "target"),
    ]
    for field, ref, role in refs:
        if ref is None:
            continue
        name = ref
        obj = by_name.get(name)
        if obj is None:
            problems.append(f"{field}: no object named {name!r} in objects (have {', '.join(names)})")
        elif obj.role != role:
            problems.append(f"{field}: object {name!r} has role {obj.role!r}, expected {role!r}")

    if bounds is not None:
        problems += _check_bounds(spec, bounds)
    if catalog is not None:
        problems += _check_catalog(spec, catalog)
    return problems


def _check_bounds(spec: SceneSpec, b: SceneBounds) -> list[str]:
    out: list[str] = []
    if len(spec.objects) > b.max_objects:
        out.append(f"objects: {len(spec.objects)} objects, allowed 1 to {b.max_objects}")
    (x0, x1), (y0, y1) = b.workspace_x_m, b.workspace_y_m
    for i, o in enumerate(spec.objects):
        if not x0 <= o.x <= x1:
            out.append(f"objects[{i}].x: {o.x:.3f} m is outside the workspace, allowed [{x0}, {x1}] m")
        if not y0 <= o.y <= y1:
            out.append(f"objects[{i}].y: {o.y:.3f} m is outside the workspace, allowed [{y0}, {y1}] m")
    d = spec.lighting.intensity_delta
    if abs(d) > b.lighting_max_delta + 1e-9:
        out.append(
            f"lighting.intensity_delta: {d:+.3f}, allowed [-{b.lighting_max_delta}, {b.lighting_max_delta}]"
        )
    t = spec.camera.translation_norm_m
    if t > b.camera_max_translation_m + 1e-9:
        out.append(
            f"camera.translation_m: moves {t:.3f} m, allowed at most {b.camera_max_translation_m} m"
        )
    for axis, angle in zip(("roll", "pitch", "yaw"), spec.camera.rotation_deg, strict=True):
        if abs(angle) > b.camera_max_rotation_deg + 1e-9:
            out.append(
                f"camera.rotation_deg: {axis} {angle:+.1f} deg, allowed at most "
                f"{b.camera_max_rotation_deg} deg per axis"
            )
    return out


def _check_catalog(spec: SceneSpec, catalog: Catalog) -> list[str]:
    out: list[str] = []
    for i, o in enumerate(spec.objects):
        if o.id not in catalog:
            out.append(f"objects[{i}].id: unknown catalog object {o.id!r}")
    if out:
        return out
    names = {o.name for o in spec.objects}
    src = spec.source if spec.task.source in names else None
    if src is not None:
        obj = catalog.get(src.id)
        if not obj.graspable:
            out.append(f"task.source: {obj.display_name!r} ({obj.id}) is not graspable")
    tgt_name = spec.task.target
    if tgt_name and tgt_name in names:
        tgt = catalog.get(spec.object(tgt_name).id)
        if spec.task.type == "put_on" and not tgt.support:
            out.append(f"task.target: {tgt.display_name!r} cannot hold objects on top (put_on needs a support)")
        elif spec.task.type == "put_in" and not tgt.container:
            out.append(f"task.target: {tgt.display_name!r} is not a container (put_in needs one)")
        elif src is not None and catalog.get(src.id).graspable:
            why = task_feasibility(spec.task.type, catalog.get(src.id), tgt, strict=False)
            if why:
                out.append(f"task: {why}")
    return out


def parse_scene_spec(
    data: dict[str, Any] | str,
    catalog: Catalog | None = None,
    bounds: SceneBounds | None = None,
) -> SceneSpec:
    """Validate ``data`` (a dict or JSON text) into a :class:`SceneSpec`.

    Raises ``pydantic.ValidationError`` whose messages name each bad field.
    """
    if isinstance(data, str):
        data = json.loads(data)
    return SceneSpec.model_validate(data, context={"catalog": catalog, "bounds": bounds})


def scene_spec_json_schema() -> dict[str, Any]:
    """The JSON Schema of :class:`SceneSpec`, for LLM prompts and external tools."""
    return SceneSpec.model_json_schema()
