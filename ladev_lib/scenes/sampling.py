"""Random valid scenes for a task: the fallback where a description is silent,
and the source of seeded test scenes.

    spec = sample_scene("put_on", num_objects=3, object_set="simpler", rng=rng, catalog=catalog)
"""

from __future__ import annotations

import math

import numpy as np

from ladev_lib.catalog import Catalog, CatalogObject
from ladev_lib.scenes.feasibility import task_feasibility
from ladev_lib.scenes.placement import PlacementError, PlacementRequest, place_objects
from ladev_lib.scenes.spec import (
    CameraOffset,
    Lighting,
    ObjectPlacement,
    SceneBounds,
    SceneSpec,
    TaskSpec,
    parse_scene_spec,
)
from ladev_lib.vocabulary import ObjectSetName, Robot, Role, as_task


def target_candidates(task: str, source: CatalogObject, pool: list[CatalogObject]) -> list[CatalogObject]:
    """Objects of ``pool`` the task can use as its target with this source."""
    return [
        t
        for t in pool
        if t.id != source.id and task_feasibility(task, source, t) is None
    ]


def sample_lighting(environment: str, rng: np.random.Generator, bounds: SceneBounds) -> Lighting:
    """Default lighting, or a change of 0.1 to the bound in either direction."""
    if environment != "lighting":
        return Lighting()
    magnitude = float(rng.uniform(0.1, bounds.lighting_max_delta))
    return Lighting(intensity_delta=round(magnitude * (1 if rng.random() < 0.5 else -1), 3))


def sample_camera(environment: str, rng: np.random.Generator, bounds: SceneBounds) -> CameraOffset:
    """Default camera, or a random move within the bounds (at least a fifth of each)."""
    if environment != "camera":
        return CameraOffset()
    direction = rng.normal(size=3)
    direction /= np.linalg.norm(direction)
    dist = rng.uniform(0.2, 1.0) * bounds.camera_max_translation_m
    angles = rng.uniform(-1.0, 1.0, size=3) * bounds.camera_max_rotation_deg
    return CameraOffset.rounded(direction * dist, angles)


def sample_scene(
    task: str,
    num_objects: int,
    object_set: ObjectSetName,
    rng: np.random.Generator,
    catalog: Catalog,
    bounds: SceneBounds | None = None,
    *,
    environment: str = "default",
    robot: Robot = "panda",
    seed: int = 0,
    scene_id: str | None = None,
    min_gap_m: float = 0.02,
    attempts: int = 20,
) -> SceneSpec:
    """A random, valid scene: source, target (if the task has one), distractors, placed.

    ``num_objects`` counts the objects the policy chooses among: the source and the
    distractors. The target of move_near / put_on / put_in (the reference object or
    receptacle) comes in addition, as in the paper, where a one-object scene holds
    "only the target object" for every task.
    """
    bounds = bounds or SceneBounds()
    pool = catalog.select(sets=[object_set])
    needs_target = task != "pick_up"
    if num_objects < 1:
        raise ValueError(f"num_objects must be at least 1, got {num_objects}")
    total = num_objects + (1 if needs_target else 0)
    last_error = ""
    for _ in range(attempts):
        graspable = [o for o in pool if o.graspable]
        source = graspable[int(rng.integers(len(graspable)))]
        chosen = [source]
        if needs_target:
            targets = target_candidates(task, source, pool)
            if not targets:
                last_error = f"no target in {object_set} fits {source.display_name!r} for {task}"
                continue
            chosen.append(targets[int(rng.integers(len(targets)))])
        others = [o for o in pool if o.id not in {c.id for c in chosen}]
        for idx in rng.permutation(len(others))[: total - len(chosen)]:
            chosen.append(others[int(idx)])
        try:
            placed = place_objects(
                [PlacementRequest(o) for o in chosen],
                bounds.workspace_x_m,
                bounds.workspace_y_m,
                rng,
                min_gap_m=min_gap_m,
            )
        except PlacementError as exc:
            last_error = str(exc)
            continue
        roles: list[Role] = ["source", "target"] if needs_target else ["source"]
        objects = [
            ObjectPlacement(
                name=p.obj.id,
                id=p.obj.id,
                x=round(p.x, 4),
                y=round(p.y, 4),
                yaw_deg=round(math.remainder(p.yaw_deg, 360.0), 2),
                role=roles[i] if i < len(roles) else "distractor",
            )
            for i, p in enumerate(placed)
        ]
        data = SceneSpec.model_construct(
            scene_id=scene_id,
            robot=robot,
            objects=tuple(objects),
            lighting=sample_lighting(environment, rng, bounds),
            camera=sample_camera(environment, rng, bounds),
            task=TaskSpec(type=as_task(task), source=source.id, target=chosen[1].id if needs_target else None),
            seed=seed,
        ).model_dump()
        return parse_scene_spec(data, catalog=catalog, bounds=bounds)
    raise ValueError(f"could not sample a valid {task} scene with {num_objects} objects: {last_error}")
