"""Task success predicates, after SimplerEnv's ``evaluate()`` definitions.

Each task returns named boolean predicates (torch bool tensors of shape (1,))
and ``success``, their conjunction. Predicates are functions of the current
state and of the poses the objects settled into after spawning, so a test can
teleport objects into a success or a failure state and call ``evaluate()``.
Positions are the centres of the objects' collision boxes (``BuiltObject``),
distances in the xy plane of the world, in metres.

Shared definitions:
- *grasped*: the robot's grasp check (ManiSkill's ``is_grasping`` for Panda and
  WidowX: both fingers press the object with >= 0.5 N, each within 85 degrees of
  its closing direction; SimplerEnv's check for the Google robot).
- *touches X*: the contact force between the two bodies exceeds 1 mN.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

import torch

from ladev_lib.registry import Registry

if TYPE_CHECKING:
    from ladev_lib.sim.env import LadevSceneEnv

CONTACT_N = 1e-3
TARGET_CONTACT_N = 0.05


class Task(Protocol):
    name: str

    def evaluate(self, env: LadevSceneEnv) -> dict[str, torch.Tensor]: ...


TASKS: Registry[Task] = Registry("task")


def _t(value: bool | torch.Tensor) -> torch.Tensor:
    if isinstance(value, torch.Tensor):
        return value.reshape(1).to(torch.bool).cpu()
    return torch.tensor([bool(value)])


def _conjunction(preds: dict[str, bool | torch.Tensor]) -> dict[str, torch.Tensor]:
    out = {k: _t(v) for k, v in preds.items()}
    success = torch.ones(1, dtype=torch.bool)
    for v in out.values():
        success = success & v
    out["success"] = success
    return out


def touches_only(env: LadevSceneEnv, name: str, allowed: set[str]) -> bool:
    """``name`` touches nothing but the robot and the objects in ``allowed``."""
    others = [env.table, env.ground] + [a for n, a in env.objects.items() if n != name and n not in allowed]
    return not any(env.contact_force(env.objects[name], other) > CONTACT_N for other in others)


def xy_distance(env: LadevSceneEnv, a: str, b: str) -> float:
    pa, pb = env.box_center_world(a), env.box_center_world(b)
    return float(((pa[:2] - pb[:2]) ** 2).sum() ** 0.5)


def half_diagonal_xy(env: LadevSceneEnv, name: str) -> float:
    h = env.built[name].half_extents
    return float((h[0] ** 2 + h[1] ** 2) ** 0.5)


class PickUp:
    """**Description:** pick up the source object.

    **Success Conditions** (SimplerEnv ``GraspSingle``: lifted while grasped):
    - ``is_grasped``: the robot grasps the source.
    - ``lifted``: the source is at least 2 cm (``LIFT_M``) above the height it settled at
      and touches nothing but the robot (no table, no other object).
    """

    name = "pick_up"
    LIFT_M = 0.02

    def evaluate(self, env: LadevSceneEnv) -> dict[str, torch.Tensor]:
        src = env.spec.task.source
        rise = float(env.box_center_world(src)[2] - env.settled_center(src)[2])
        return _conjunction(
            {
                "is_grasped": env.is_grasped(src),
                "lifted": rise >= self.LIFT_M and touches_only(env, src, set()),
            }
        )


class MoveNear:
    """**Description:** move the source object near the target object.

    **Success Conditions** (SimplerEnv ``MoveNearInScene``):
    - ``moved_source``: the source moved more than 3 cm (``MOVED_M``) in xy since settling,
      and further than every other object.
    - ``near_target``: source-target xy distance < half xy diagonal of the source + that of
      the target + 10 cm (``NEAR_MARGIN_M``).
    - ``closest_to_target``: the target is the source's nearest object (within 1 cm).
    - ``nothing_knocked_over``: no other object dropped more than 2 cm in height; the source
      and the target dropped less than 15 cm (not knocked off the table).
    """

    name = "move_near"
    MOVED_M = 0.03
    NEAR_MARGIN_M = 0.10
    CLOSEST_SLACK_M = 0.01
    DROP_OTHERS_M = 0.02
    DROP_PAIR_M = 0.15

    def evaluate(self, env: LadevSceneEnv) -> dict[str, torch.Tensor]:
        src, tgt = env.spec.task.source, env.spec.task.target
        assert tgt is not None
        moved = {n: env.xy_displacement(n) for n in env.objects}
        others = [n for n in env.objects if n != src]
        moved_source = moved[src] > self.MOVED_M and all(moved[n] < moved[src] for n in others)
        dist = xy_distance(env, src, tgt)
        near = dist < half_diagonal_xy(env, src) + half_diagonal_xy(env, tgt) + self.NEAR_MARGIN_M
        closest = all(dist < xy_distance(env, src, n) + self.CLOSEST_SLACK_M for n in others)
        drops = {n: -env.z_displacement(n) for n in env.objects}
        kept = all(
            drops[n] < (self.DROP_PAIR_M if n in (src, tgt) else self.DROP_OTHERS_M) for n in env.objects
        )
        return _conjunction(
            {
                "moved_source": moved_source,
                "near_target": near,
                "closest_to_target": closest,
                "nothing_knocked_over": kept,
            }
        )


class PutOn:
    """**Description:** put the source object on the target object.

    **Success Conditions** (SimplerEnv ``PutOnInScene`` / ManiSkill ``BaseBridgeEnv``):
    - ``on_target``: the source centre is within the target's half xy diagonal + 3 mm of
      the target centre (xy), and above it by at most 2 cm (``Z_SLACK_M``) more than the
      two half heights.
    - ``resting_on_target``: the source presses on the target (contact force > 0.05 N) and
      touches nothing else but the robot (neither the table nor another object).
    - ``released``: the robot does not grasp the source.
    """

    name = "put_on"
    XY_SLACK_M = 0.003
    Z_SLACK_M = 0.02

    def evaluate(self, env: LadevSceneEnv) -> dict[str, torch.Tensor]:
        src, tgt = env.spec.task.source, env.spec.task.target
        assert tgt is not None
        ps, pt = env.box_center_world(src), env.box_center_world(tgt)
        offset = ps - pt
        xy_ok = float((offset[:2] ** 2).sum() ** 0.5) <= half_diagonal_xy(env, tgt) + self.XY_SLACK_M
        stack = float(env.built[src].half_extents[2] + env.built[tgt].half_extents[2])
        z_ok = float(offset[2]) > 0 and float(offset[2]) - stack <= self.Z_SLACK_M
        pressing = env.contact_force(env.objects[src], env.objects[tgt]) > TARGET_CONTACT_N
        return _conjunction(
            {
                "on_target": xy_ok and z_ok,
                "resting_on_target": pressing and touches_only(env, src, {tgt}),
                "released": ~env.is_grasped(src),
            }
        )


class PutIn:
    """**Description:** put the source object into the target container.

    **Success Conditions** (after SimplerEnv ``PutEggplantInBasket``, which counts the
    eggplant as in the basket when it rests on the basket's inner floor):
    - ``inside``: the source centre lies over the container's inner floor (the container's
      box shrunk by its 1 cm walls, in the container's frame), and the source's bottom is
      below the rim and no more than 1 cm below the container's bottom.
    - ``not_on_table``: the source does not touch the table (it rests in the container).
    - ``released``: the robot does not grasp the source.
    """

    name = "put_in"
    WALL_M = 0.01
    BELOW_FLOOR_SLACK_M = 0.01

    def evaluate(self, env: LadevSceneEnv) -> dict[str, torch.Tensor]:
        src, tgt = env.spec.task.source, env.spec.task.target
        assert tgt is not None
        local = env.point_in_object_frame(tgt, env.box_center_world(src))
        box = env.built[tgt]
        rel = local - box.box_center
        inner = box.half_extents[:2] - self.WALL_M
        over_floor = bool(abs(rel[0]) <= inner[0] and abs(rel[1]) <= inner[1])
        src_bottom = float(env.box_center_world(src)[2] - env.built[src].half_extents[2])
        tgt_center = env.box_center_world(tgt)
        tgt_top = float(tgt_center[2] + box.half_extents[2])
        tgt_bottom = float(tgt_center[2] - box.half_extents[2])
        height_ok = tgt_bottom - self.BELOW_FLOOR_SLACK_M <= src_bottom < tgt_top
        on_table = env.contact_force(env.objects[src], env.table) > CONTACT_N
        return _conjunction(
            {
                "inside": over_floor and height_ok,
                "not_on_table": not on_table,
                "released": ~env.is_grasped(src),
            }
        )


for _task in (PickUp(), MoveNear(), PutOn(), PutIn()):
    TASKS.add(_task.name, _task)


def get_task(name: str) -> Task:
    """The task called ``name``; an unknown name lists the known ones."""
    return TASKS.get(name)
