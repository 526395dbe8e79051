"""Each task's predicates on constructed success and failure states (Panda, stand-ins).

The scene is built and settled, then objects are teleported into a success or a failure
configuration and physics runs briefly, so contacts are real when ``evaluate()`` reads them.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
import torch

from tests.sim.conftest import make_spec, settle

pytestmark = pytest.mark.sim

# One layout for every task (roles differ), so the env re-poses instead of rebuilding.
LAYOUT = [
    {"name": "green_cube", "x": 0.10, "y": 0.15},
    {"name": "plate", "x": 0.10, "y": -0.12},
    {"name": "basket", "x": -0.08, "y": -0.15},
    {"name": "apple", "x": -0.10, "y": 0.15},
    {"name": "coke_can", "x": 0.12, "y": 0.02},
]


def scene(task: str, target: str | None = None) -> Any:
    roles = {"green_cube": "source", **({target: "target"} if target else {})}
    objs = [{**o, "role": roles.get(o["name"], "distractor")} for o in LAYOUT]
    return make_spec(objs, {"type": task, "source": "green_cube", "target": target})


def preds(u: Any) -> dict[str, bool]:
    out = u.evaluate()
    assert all(isinstance(v, torch.Tensor) and v.dtype == torch.bool and v.shape == (1,) for v in out.values())
    return {k: bool(v[0]) for k, v in out.items()}


def ws(u: Any, x: float, y: float, z: float) -> np.ndarray:
    return u.workspace_to_world(x, y, z)


def drop_onto(env: Any, name: str, p_world: np.ndarray) -> None:
    env.unwrapped.teleport(name, p_world, np.array([1.0, 0, 0, 0]))
    settle(env, 0.6)


# -- pick_up ------------------------------------------------------------------------------
def _hold_action(u: Any, gripper: float) -> np.ndarray:
    arm = u.agent.robot.get_qpos()[0, :7].cpu().numpy()
    return np.concatenate([arm, [gripper]]).astype(np.float32)


def test_pick_up_success_when_grasped_and_lifted(panda_env: Any, build: Any) -> None:
    u = build(scene("pick_up"))
    assert preds(u) == {"is_grasped": False, "lifted": False, "success": False}
    cube = u.objects["green_cube"]
    body = cube._bodies[0]
    body.disable_gravity = True  # hold the cube between the open fingers while they close
    tcp = u.agent.tcp.pose.p[0].cpu().numpy()
    u.teleport("green_cube", tcp, np.array([1.0, 0, 0, 0]))
    for _ in range(10):
        panda_env.step(_hold_action(u, -1.0))
    body.disable_gravity = False
    for _ in range(10):
        panda_env.step(_hold_action(u, -1.0))
    assert preds(u) == {"is_grasped": True, "lifted": True, "success": True}
    # Open the gripper: the cube falls back to the table; no longer grasped nor lifted.
    for _ in range(20):
        panda_env.step(_hold_action(u, 1.0))
    assert preds(u) == {"is_grasped": False, "lifted": False, "success": False}


def test_pick_up_fails_when_lifted_without_grasp(panda_env: Any, build: Any) -> None:
    u = build(scene("pick_up"))
    body = u.objects["green_cube"]._bodies[0]
    body.disable_gravity = True
    try:
        u.teleport("green_cube", ws(u, 0.1, 0.15, 0.15))
        settle(panda_env, 0.1)
        p = preds(u)
    finally:
        body.disable_gravity = False
    assert p["lifted"] and not p["is_grasped"] and not p["success"]


# -- move_near -----------------------------------------------------------------------------
def test_move_near_success_next_to_target(panda_env: Any, build: Any) -> None:
    u = build(scene("move_near", "apple"))
    assert not preds(u)["success"]  # nothing moved yet
    drop_onto(panda_env, "green_cube", ws(u, -0.03, 0.12, 0.02))
    assert preds(u) == {
        "moved_source": True,
        "near_target": True,
        "closest_to_target": True,
        "nothing_knocked_over": True,
        "success": True,
    }


def test_move_near_fails_when_a_distractor_is_knocked_over(panda_env: Any, build: Any) -> None:
    u = build(scene("move_near", "apple"))
    drop_onto(panda_env, "green_cube", ws(u, -0.03, 0.12, 0.02))
    lying = np.array([np.cos(np.pi / 4), np.sin(np.pi / 4), 0.0, 0.0])  # can on its side
    u.teleport("coke_can", ws(u, 0.12, 0.02, 0.04), lying)
    settle(panda_env, 0.6)
    p = preds(u)
    assert not p["nothing_knocked_over"] and not p["success"]


def test_move_near_fails_next_to_the_wrong_object(panda_env: Any, build: Any) -> None:
    u = build(scene("move_near", "apple"))
    drop_onto(panda_env, "green_cube", ws(u, 0.04, -0.22, 0.02))  # beside the plate
    p = preds(u)
    assert p["moved_source"] and not p["closest_to_target"] and not p["success"]


# -- put_on --------------------------------------------------------------------------------
def test_put_on_success_resting_on_target(panda_env: Any, build: Any) -> None:
    u = build(scene("put_on", "plate"))
    assert not preds(u)["success"]
    drop_onto(panda_env, "green_cube", ws(u, 0.10, -0.12, 0.03))
    assert preds(u) == {"on_target": True, "resting_on_target": True, "released": True, "success": True}


def test_put_on_fails_beside_target(panda_env: Any, build: Any) -> None:
    u = build(scene("put_on", "plate"))
    drop_onto(panda_env, "green_cube", ws(u, 0.10, -0.21, 0.02))
    p = preds(u)
    assert not p["on_target"] and not p["resting_on_target"] and p["released"] and not p["success"]


def test_put_on_fails_when_resting_on_another_object_too(panda_env: Any, build: Any) -> None:
    """A cube bridging the plate's rim and the table touches the table: not on the plate."""
    u = build(scene("put_on", "plate"))
    drop_onto(panda_env, "green_cube", ws(u, 0.10, -0.12 - 0.06, 0.03))
    p = preds(u)
    assert not p["resting_on_target"] and not p["success"]


# -- put_in --------------------------------------------------------------------------------
def test_put_in_success_inside_container(panda_env: Any, build: Any) -> None:
    u = build(scene("put_in", "basket"))
    assert not preds(u)["success"]
    drop_onto(panda_env, "green_cube", ws(u, -0.08, -0.15, 0.05))
    assert preds(u) == {"inside": True, "not_on_table": True, "released": True, "success": True}


def test_put_in_fails_beside_container(panda_env: Any, build: Any) -> None:
    u = build(scene("put_in", "basket"))
    drop_onto(panda_env, "green_cube", ws(u, -0.08, -0.02, 0.02))
    p = preds(u)
    assert not p["inside"] and not p["not_on_table"] and not p["success"]
