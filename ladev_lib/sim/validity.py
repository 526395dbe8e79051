"""Is a built scene physically valid? A verdict with reasons (data, not exceptions).

Run it on an env right after ``reset`` (the env has spawned and settled the objects):

    verdict = check_scene(env.unwrapped)
    if not verdict.valid:
        row.status, row.reason = "invalid_scene", "; ".join(verdict.reasons)

Checks (each a named boolean in ``verdict.checks``):
- ``no_interpenetration``: no two objects, nor an object and the robot, overlap by more
  than 3 mm when spawned (PhysX contact separation after the first step).
- ``at_rest``: while settling, no object slid more than ``max_shift_m`` in xy (round
  objects: plus their radius, as scanned balls roll onto a facet), tilted more than
  ``max_tilt_deg`` (round objects excepted), or dropped below the table top; and all are still
  when settling ends.
- ``reachable``: the source and the target lie within the robot's reach (horizontal
  distance from the robot base, per robot profile).
- ``visible``: the source and the target each cover at least ``min_pixels`` pixels of
  the policy camera's segmentation (skipped when the env has no policy camera).
- ``not_already_done``: the task's success predicate is false before the robot acts.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ladev_lib.arrays import Array

if TYPE_CHECKING:
    from ladev_lib.sim.env import LadevSceneEnv


@dataclass(frozen=True)
class ValidityThresholds:
    max_shift_m: float = 0.02
    max_tilt_deg: float = 30.0
    max_drop_m: float = 0.02
    """How far below its spawn height an object may end up (it fell off the table beyond)."""
    max_speed_m_s: float = 0.02
    max_spin_rad_s: float = 0.2
    min_pixels: int = 20


@dataclass(frozen=True)
class ValidityVerdict:
    """Outcome of :func:`check_scene`: ``valid`` when every check passed."""

    valid: bool
    reasons: tuple[str, ...]
    checks: dict[str, bool]
    details: dict[str, Any] = field(default_factory=dict)

    @property
    def reason(self) -> str:
        return "; ".join(self.reasons)


def _tilt_deg(q_from: Array, q_to: Array) -> float:
    """Angle between the two orientations' z axes (how far the object tipped)."""

    def z_axis(q: Array) -> Array:
        w, x, y, z = q
        return np.array([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])

    c = float(np.clip(z_axis(q_from) @ z_axis(q_to), -1.0, 1.0))
    return math.degrees(math.acos(c))


def _is_round(env: LadevSceneEnv, name: str) -> bool:
    """Round objects may turn while settling; only rolling away counts for them."""
    return env.catalog.get(env.spec.object(name).id).shape == "sphere"


def _at_rest(env: LadevSceneEnv, th: ValidityThresholds) -> tuple[list[str], dict[str, Any]]:
    reasons: list[str] = []
    report = env.spawn_report
    moves: dict[str, Any] = {}
    for name, spawn in report.spawn_poses.items():
        settled = report.settled_poses[name]
        shift = float(np.hypot(*(settled[:2] - spawn[:2])))
        tilt = _tilt_deg(spawn[3:], settled[3:])
        drop = float(spawn[2] - settled[2])
        speed, spin = report.settled_speeds[name]
        round_ = _is_round(env, name)
        moves[name] = {"shift_m": shift, "tilt_deg": tilt, "drop_m": drop, "speed": speed, "spin": spin}
        if drop > th.max_drop_m + env.built[name].bottom_z:
            reasons.append(f"{name!r} fell off the table while settling (dropped {drop * 100:.0f} cm)")
        elif tilt > th.max_tilt_deg and not round_:
            reasons.append(f"{name!r} fell over while settling (tilted {tilt:.0f} deg)")
        elif shift > th.max_shift_m + (float(env.built[name].half_extents[0]) if round_ else 0.0):
            reasons.append(f"{name!r} slid or rolled {shift * 100:.1f} cm while settling")
        elif speed > th.max_speed_m_s or spin > th.max_spin_rad_s:
            reasons.append(f"{name!r} is still moving after settling ({speed:.3f} m/s, {spin:.2f} rad/s)")
    return reasons, moves


def _task_objects(env: LadevSceneEnv) -> list[tuple[str, str]]:
    task = env.spec.task
    out = [("source", task.source)]
    if task.target is not None:
        out.append(("target", task.target))
    return out


def _reachability(env: LadevSceneEnv) -> tuple[list[str], dict[str, float]]:
    lo, hi = env.profile.reach_m
    reasons, dists = [], {}
    for role, name in _task_objects(env):
        d = env.profile.horizontal_reach(env.box_center_world(name)[:2])
        dists[name] = d
        if d > hi:
            reasons.append(f"{role} {name!r} is {d:.2f} m from the robot base, beyond its reach ({hi:.2f} m)")
        elif d < lo:
            reasons.append(f"{role} {name!r} is {d:.2f} m from the robot base, too close to reach ({lo:.2f} m)")
    return reasons, dists


def _visibility(env: LadevSceneEnv, th: ValidityThresholds) -> tuple[list[str], dict[str, int]]:
    seg = env.policy_segmentation()
    reasons, pixels = [], {}
    for role, name in _task_objects(env):
        ids = env.objects[name].per_scene_id.cpu().numpy()
        n = int(np.isin(seg, ids).sum())
        pixels[name] = n
        if n < th.min_pixels:
            reasons.append(
                f"{role} {name!r} covers {n} px of the policy camera (at least {th.min_pixels} needed)"
            )
    return reasons, pixels


def check_scene(env: LadevSceneEnv, thresholds: ValidityThresholds | None = None) -> ValidityVerdict:
    """Judge the scene ``env`` has just built (call after ``reset``)."""
    th = thresholds or ValidityThresholds()
    checks: dict[str, bool] = {}
    reasons: list[str] = []
    details: dict[str, Any] = {}

    pen = env.spawn_report.penetrations
    checks["no_interpenetration"] = not pen
    reasons += [f"{a!r} and {b!r} overlap by {d * 1000:.0f} mm at spawn" for a, b, d in pen]

    rest_reasons, details["settling"] = _at_rest(env, th)
    checks["at_rest"] = not rest_reasons
    reasons += rest_reasons

    reach_reasons, details["reach_m"] = _reachability(env)
    checks["reachable"] = not reach_reasons
    reasons += reach_reasons

    if env.image_size is not None:
        vis_reasons, details["visible_px"] = _visibility(env, th)
        checks["visible"] = not vis_reasons
        reasons += vis_reasons
    else:
        details["visible_px"] = "not checked: the env has no policy camera"

    done = bool(env.evaluate()["success"][0])
    checks["not_already_done"] = not done
    if done:
        reasons.append(f"the {env.spec.task.type} task is already accomplished before the robot acts")

    return ValidityVerdict(valid=all(checks.values()), reasons=tuple(reasons), checks=checks, details=details)
