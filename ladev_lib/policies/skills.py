"""Motion skills for the Panda: pick an object and put it on, in, or near another.

    skill = plan_task(env.unwrapped, "put_on", "green_cube", "plate")
    for action in skill:              # one pd_joint_pos action per control step
        env.step(action)
    skill.outcome                     # status "done" | "failed", reason, attempts, log

``TaskSkill`` is a small state machine written as a generator: each phase
(approach, descend, grasp, lift, carry, lower, release, retreat) is planned from
the state the simulator is in when the phase starts, so the plan follows the
world between phases. It re-grasps when the object slips or lands wrong, up to
``max_attempts`` times. The caller steps the simulator between actions.

It reads the scene through a read-only :class:`~ladev_lib.sim.view.SceneView`
(object names and surface points, the robot's joints and hand, whether it
holds something, the control time step), never the env. It never reads an instruction: the task type and object
names come from the caller (the oracle reads them from the scene spec; the
grounded policy from language).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

import numpy as np
import sapien

from ladev_lib.arrays import Array
from ladev_lib.policies.geometry import ObjectGeometry
from ladev_lib.policies.grasping import OPENING_MARGIN_M, Grasp, closing_of, top_down_grasps
from ladev_lib.policies.motion import ArmMotion, SkillFailure
from ladev_lib.policies.placing import (
    HeldObject,
    Placement,
    finger_points,
    lowest_free_height,
    palm_points,
    place_in,
    place_near,
    place_on,
)
from ladev_lib.policies.planner import ArmPath
from ladev_lib.vocabulary import TASKS, TaskType, narrow

if TYPE_CHECKING:
    from ladev_lib.sim.view import SceneView


PRE_GRASP_HEIGHT_M = 0.08
"""Approach ends this far above the grasp, then the hand comes straight down."""
CARRY_CLEARANCE_M = 0.04
"""The lifted object's bottom clears its neighbours' tops (and the target's) by this much."""
CARRY_LIFT_M = 0.08
"""move_near / put_on / put_in lift the object at least this far before carrying it."""
NEIGHBOURHOOD_M = 0.15
"""Objects this close (xy) to the source count as neighbours when lifting it."""
HAND_RADIUS_M = 0.11
"""Horizontal reach of the open hand around the TCP (half the palm's length, plus margin)."""
REACHED_TOLERANCE_M = 0.015
"""The hand must get this close to the grasp before closing."""
LIFT_HEIGHT_M = 0.12
"""pick_up lifts the object's bottom this far."""
RELEASE_GAP_M = 0.005
"""move_near: the object is let go this far above the table."""
MOVED_M = 0.03
"""move_near: the object must have moved this far (SimplerEnv's threshold)."""
NEAR_MARGIN_M = 0.08
"""move_near counts as near within both half diagonals plus this (SimplerEnv allows 5-10 cm)."""
GRASP_CANDIDATES = 8
IK_SOLUTIONS = 3
"""Arm postures tried per grasp."""
PLACE_CANDIDATES = 8
CLOSE_STEPS = 10
OPEN_STEPS = 6
HOLD_STEPS = 8
SETTLE_STEPS = 10


class TaskSkill(ArmMotion):
    """Solve one task in a ManiSkill Panda env, one ``pd_joint_pos`` action at a time."""

    def __init__(
        self,
        view: SceneView,
        task_type: str,
        source: str,
        target: str | None = None,
        *,
        region: tuple[tuple[float, float], tuple[float, float]] | None = None,
        max_attempts: int = 3,
    ) -> None:
        task = narrow(task_type, TASKS, "task_type")
        if task != "pick_up" and target is None:
            raise ValueError(f"{task} needs a target object")
        objects = view.object_names()
        for role, name in (("source", source), ("target", target)):
            if name is not None and name not in objects:
                raise KeyError(f"{role} {name!r} is not in the scene (objects: {', '.join(objects)})")
        super().__init__(view)
        self.task_type: TaskType = task
        self.source = source
        self.target = target
        self.max_attempts = max_attempts
        start = self._geometries()
        self.table_z = min(g.bottom_z for g in start.values())
        self.region = region or _region_around(start)
        self._start_centre = start[source].footprint()[0]
        self._emitted = 0
        self._failed_grasps: list[tuple[Grasp, bool]] = []
        """Grasps that failed, and whether the object slipped out of them."""
        self._actions = self._run()

    # -- iteration -----------------------------------------------------------
    def __iter__(self) -> Iterator[Array]:
        return self

    def __next__(self) -> Array:
        action = next(self._actions)
        self._emitted += 1
        steps = self.outcome.phase_steps
        steps[self.outcome.phase] = steps.get(self.outcome.phase, 0) + 1
        return action

    def _holding(self) -> bool:
        return self.view.is_grasping(self.source)

    # -- the task ------------------------------------------------------------
    def _run(self) -> Iterator[Array]:
        reason = ""
        for attempt in range(1, self.max_attempts + 1):
            self.outcome.attempts = attempt
            emitted_before = self._emitted
            try:
                if not self._holding():
                    yield from self._pick()
                if self.task_type == "pick_up":
                    self._phase("hold")
                    yield from self._wait(HOLD_STEPS)
                    if self._holding():
                        return self._finish()
                    reason = f"{self.source} slipped out of the gripper while held"
                else:
                    yield from self._place()
                    reason = self._placed_wrong()
                    if not reason:
                        return self._finish()
            except SkillFailure as exc:
                reason = str(exc)
                final = exc.final
            else:
                final = False
            self._note(f"attempt {attempt} failed: {reason}")
            if self._holding():
                yield from self._set_down()
            elif self._gripper_action < self._gripper.action(self._gripper.max_opening):
                yield from self._gripper_steps(self._gripper.max_opening, OPEN_STEPS)
                yield from self._retreat()
            if final or self._emitted == emitted_before:  # nothing moved: the same would happen
                break
        self.outcome.status = "failed"
        self.outcome.reason = reason or "gave up"
        return None

    def _set_down(self) -> Iterator[Array]:
        """Put the held object back down below the hand (after a failed attempt), let go."""
        self._phase("set_down")
        geoms = self._geometries()
        src = geoms[self.source]
        rest = [g.points for n, g in geoms.items() if n != self.source]
        obstacles = np.vstack(rest) if rest else np.zeros((0, 3))
        held = self._held(src)
        tcp = self._tcp()
        xy = np.asarray(tcp.p[:2], dtype=float)
        floor = self.table_z + held.bottom_below_tcp + RELEASE_GAP_M
        z = lowest_free_height(held, xy, obstacles, float(tcp.p[2]), floor)
        if z is not None and z < float(tcp.p[2]) - 0.005:
            down = sapien.Pose([0.0, 0.0, z - float(tcp.p[2])]) * tcp
            path = self.planner.screw(self._qpos(), down, avoid=False)
            if path is not None:
                yield from self._follow(path)
        yield from self._gripper_steps(self._gripper.max_opening, OPEN_STEPS)
        yield from self._retreat()

    # -- pick ----------------------------------------------------------------
    def _pick(self) -> Iterator[Array]:
        self._phase("approach")
        geoms = self._geometries()
        src = geoms[self.source]
        others = [g.points for n, g in geoms.items() if n != self.source]
        obstacles = np.vstack(others) if others else np.zeros((0, 3))
        grasps = [
            g for g in top_down_grasps(src.points, obstacles, closing_of(self._tcp()))
            if not any(_same_grasp(g, bad, slipped) for bad, slipped in self._failed_grasps)
        ]
        if not grasps:
            raise SkillFailure(f"no grasp of {self.source} fits the gripper here", final=True)
        chosen = self._choose_grasp(grasps, geoms, obstacles)
        if chosen is None:
            raise SkillFailure(
                f"none of {min(len(grasps), 4 * GRASP_CANDIDATES)} grasps of {self.source} is "
                "reachable without collision"
            )
        grasp, approach, descend = chosen
        self._note(f"grasp at {np.round(grasp.position, 3).tolist()} width {grasp.width_m:.3f} "
                   f"via {approach.method}")
        self._gripper_action = self._gripper.action(grasp.opening_m)
        yield from self._follow(approach)
        self._phase("descend")
        yield from self._follow(descend, precise=True)
        off = float(np.linalg.norm(np.asarray(self._tcp().p) - grasp.position))
        if off > REACHED_TOLERANCE_M:
            self._failed_grasps.append((grasp, False))
            raise SkillFailure(f"the hand stopped {off:.3f} m short of the grasp of {self.source}")
        self._phase("grasp")
        yield from self._gripper_steps(self._gripper.min_opening, CLOSE_STEPS)
        self._phase("lift")
        tcp = self._tcp()
        depth = float(tcp.p[2]) - src.bottom_z
        up = sapien.Pose([0.0, 0.0, self._lift_height(geoms, depth) - float(tcp.p[2])]) * tcp
        yield from self._follow(self._straight(up, "lift", obstacles, held=src))
        if not self._holding():
            self._failed_grasps.append((grasp, True))
            raise SkillFailure(f"grasp of {self.source} did not hold (width {grasp.width_m:.3f} m)")

    def _choose_grasp(self, grasps: list[Grasp], geoms: dict[str, ObjectGeometry],
                      obstacles: Array) -> tuple[Grasp, ArmPath, ArmPath] | None:
        """The first grasp (best first, either hand orientation) with a free way there and down.

        Works back from the grasp: an arm configuration at the grasp that touches no other
        object, the configuration above it in the same arm posture (just above the object,
        or above the tallest object when the arm does not fit beside a tall neighbour), a
        straight way down between the two, and a way from here to the top one.
        Near the grasp the hand's clearance was checked on the points themselves, to the
        millimetre; the planner's coarser cells only guard the rest of the arm.
        """
        src = geoms[self.source]
        self.planner.detach()
        qpos = self._qpos()
        tallest = max((g.top_z for n, g in geoms.items() if n != self.source), default=src.top_z)
        arm_obstacles = _away_from_hand(obstacles, src.points.mean(axis=0))
        # Upright grasps first; leaning ones (away from a tall neighbour) when none works;
        # then from the side; grasps on a taper (a bottle's neck) only when nothing else works.
        firm = [g for g in grasps if not g.tapered]
        upright = [g for g in firm if g.tilt_rad < 1e-3][:GRASP_CANDIDATES]
        leaning = [g for g in firm if 1e-3 <= g.tilt_rad < np.pi / 4][:GRASP_CANDIDATES]
        side = [g for g in firm if g.tilt_rad >= np.pi / 4][:GRASP_CANDIDATES]
        tapered = [g for g in grasps if g.tapered][:GRASP_CANDIDATES]
        options = [g for best in upright + leaning + side + tapered for g in (best, best.flipped())]
        for grasp in options:
            pose = grasp.pose()
            # Along a leaning approach, the way back up to clear the tallest object is longer.
            high = (max(tallest, src.top_z) + 0.06 - grasp.position[2]) / max(0.5, -grasp.approach[2])
            self.planner.set_obstacles(arm_obstacles)
            for at_grasp in self.planner.ik_solutions(qpos, pose, avoid=True)[:IK_SOLUTIONS]:
                for height in (PRE_GRASP_HEIGHT_M, high):
                    pre = pose * sapien.Pose([0.0, 0.0, -height])  # back along the approach
                    above = self.planner.local_ik(at_grasp, pre)
                    if above is None:
                        continue
                    self.planner.set_obstacles(arm_obstacles)
                    descend = self.planner.screw(above, pose, avoid=True)
                    if descend is None:
                        continue
                    self.planner.set_obstacles(np.vstack([obstacles, src.points]))
                    if self.planner.collides(above, avoid=True):
                        continue
                    approach = self.planner.to_qpos(qpos, above, avoid=True)
                    if approach is not None:
                        return grasp, approach, descend
        return None

    def _lift_height(self, geoms: dict[str, ObjectGeometry], depth: float) -> float:
        """TCP height to lift to: the object's bottom clear of its neighbours, or LIFT_HEIGHT_M up."""
        src = geoms[self.source]
        if self.task_type == "pick_up":
            return src.bottom_z + LIFT_HEIGHT_M + depth
        centre = src.xy.mean(axis=0)
        near = [g.top_z for n, g in geoms.items()
                if n != self.source and np.min(np.linalg.norm(g.xy - centre, axis=1)) < NEIGHBOURHOOD_M]
        bottom = max([src.bottom_z + CARRY_LIFT_M] + [top + CARRY_CLEARANCE_M for top in near])
        return bottom + depth

    # -- place ---------------------------------------------------------------
    def _held(self, src: ObjectGeometry) -> HeldObject:
        tcp = self._tcp()
        opening = self._release_opening(src)
        rotation = tcp.to_transformation_matrix()[:3, :3]
        return HeldObject(src.points - np.asarray(tcp.p), finger_points(rotation, opening),
                          palm_points(rotation))

    def _release_opening(self, src: ObjectGeometry) -> float:
        # Open a little wider than the object, not fully: the fingers stay clear of neighbours.
        closing = closing_of(self._tcp())[:2]
        across = src.points[:, :2] @ closing
        width = float(across.max() - across.min())
        return min(self._gripper.max_opening, width + OPENING_MARGIN_M)

    def _place(self) -> Iterator[Array]:
        assert self.target is not None
        self._phase("carry")
        geoms = self._geometries()
        src, tgt = geoms[self.source], geoms[self.target]
        others = {n: g.points for n, g in geoms.items() if n not in (self.source, self.target)}
        other_pts = np.vstack(list(others.values())) if others else np.zeros((0, 3))
        everything = np.vstack([tgt.points, other_pts])
        held = self._held(src)
        tcp = self._tcp()
        carry_z = max(float(tcp.p[2]), tgt.top_z + held.bottom_below_tcp + CARRY_CLEARANCE_M)
        candidates = self._placements(held, src, tgt, others, other_pts, carry_z)
        if not candidates:
            raise SkillFailure(
                f"no free spot to put {self.source} {self.task_type.split('_')[1]} {self.target}",
                final=True,
            )
        # Plan with every other object as an obstacle and the held object as part of the hand.
        self.planner.set_obstacles(everything)
        self._attach(src)
        qpos = self._qpos()
        chosen: tuple[sapien.Pose, ArmPath] | None = None
        for placement in candidates[:PLACE_CANDIDATES]:
            q = (sapien.Pose(q=_yaw_quat(placement.yaw)) * tcp).q
            release_z = placement.tcp_z
            if release_z is None:  # on the table
                release_z = self.table_z + held.turned(placement.yaw).bottom_below_tcp + RELEASE_GAP_M
            release = sapien.Pose([placement.tcp_xy[0], placement.tcp_xy[1], release_z], q)
            if not self.planner.reachable(qpos, release, avoid=False):
                continue
            above = sapien.Pose([placement.tcp_xy[0], placement.tcp_xy[1], carry_z], q)
            carry = self.planner.plan(qpos, above, avoid=True)
            if carry is not None:
                chosen = (release, carry)
                break
        self.planner.detach()
        if chosen is None:
            raise SkillFailure(
                f"none of {min(len(candidates), PLACE_CANDIDATES)} spots to put {self.source} "
                f"{self.task_type.split('_')[1]} {self.target} is reachable"
            )
        release, carry = chosen
        self._note(f"carry: {carry.method}, {len(carry.qpos)} steps, release at "
                   f"{np.round(release.p, 3).tolist()}")
        yield from self._follow(carry)
        if not self._holding():
            raise SkillFailure(f"{self.source} fell while carried")
        self._phase("lower")
        yield from self._follow(self._straight(release, "lower", everything, held=src), precise=True)
        self._phase("release")
        yield from self._gripper_steps(self._release_opening(src), OPEN_STEPS)
        yield from self._retreat()
        yield from self._wait(SETTLE_STEPS)

    def _placements(self, held: HeldObject, src: ObjectGeometry, tgt: ObjectGeometry,
                    others: dict[str, Array], other_pts: Array,
                    carry_z: float) -> list[Placement]:
        if self.task_type == "put_on":
            return place_on(held, tgt.points, other_pts, carry_z)
        if self.task_type == "put_in":
            return place_in(held, tgt.points, other_pts, carry_z)
        src_xy = src.points[:, :2].mean(axis=0)
        return place_near(held, src_xy, tgt.points, others, self.region)

    def _placed_wrong(self) -> str:
        """Why the object is not where the task wants it; empty if it looks right."""
        assert self.target is not None
        geoms = self._geometries()
        src, tgt = geoms[self.source], geoms[self.target]
        centre = src.points[:, :2].mean(axis=0)
        t_lo, t_hi = tgt.xy.min(axis=0), tgt.xy.max(axis=0)
        over_target = bool(np.all(centre >= t_lo) and np.all(centre <= t_hi))
        if self.task_type == "put_on" and not (over_target and src.bottom_z > tgt.top_z - 0.02):
            return f"{self.source} did not come to rest on {self.target}"
        if self.task_type == "put_in" and not (over_target and src.bottom_z < tgt.top_z):
            return f"{self.source} did not end inside {self.target}"
        if self.task_type == "move_near":
            if src.bottom_z > self.table_z + 0.02:
                return f"{self.source} did not come to rest on the table"
            return self._not_near(geoms)
        return ""

    def _not_near(self, geoms: dict[str, ObjectGeometry]) -> str:
        """move_near, checked as SimplerEnv does on box centres: near, and nearest the target."""
        assert self.target is not None
        centre = {n: g.footprint()[0] for n, g in geoms.items()}
        half_diag = {n: float(np.linalg.norm(g.footprint()[2])) for n, g in geoms.items()}
        moved = float(np.linalg.norm(centre[self.source] - self._start_centre))
        if moved < MOVED_M:
            return f"{self.source} moved only {moved:.3f} m"
        d_target = float(np.linalg.norm(centre[self.source] - centre[self.target]))
        if d_target > half_diag[self.source] + half_diag[self.target] + NEAR_MARGIN_M:
            return f"{self.source} ended {d_target:.3f} m from {self.target}, not near it"
        for name in geoms:
            if name not in (self.source, self.target):
                d = float(np.linalg.norm(centre[self.source] - centre[name]))
                if d <= d_target:
                    return f"{self.source} ended nearer {name} ({d:.3f} m) than {self.target}"
        return ""


def plan_task(
    env: Any,
    task_type: str,
    source: str,
    target: str | None = None,
    **options: Any,
) -> TaskSkill:
    """The skill that does ``task_type`` with objects ``source`` (and ``target``) in ``env``.

    ``env`` is the scene env (made with ``control_mode="pd_joint_pos"``); the skill reads it
    through its read-only view (:func:`ladev_lib.sim.view.scene_view`). ``options`` go to
    :class:`TaskSkill` (``region``, ``max_attempts``). Iterate the result for actions,
    stepping the env after each; read ``outcome`` at the end.
    """
    from ladev_lib.sim.view import scene_view

    return TaskSkill(scene_view(env), task_type, source, target, **options)


def _away_from_hand(points: Array, tcp: Array) -> Array:
    """Obstacle points the arm must avoid beyond the hand's own reach around a grasp.

    Around the grasp the hand's clearance was checked on the points themselves (to
    millimetres); the planner's coarser cells would reject grasps that fit.
    """
    near = (np.linalg.norm(points[:, :2] - tcp[:2], axis=1) < HAND_RADIUS_M) & (
        points[:, 2] < tcp[2] + PRE_GRASP_HEIGHT_M + 0.05
    )
    return np.asarray(points[~near])


def _same_grasp(a: Grasp, b: Grasp, slipped: bool) -> bool:
    """Too like grasp ``b`` (which failed) to be worth trying: the same spot and direction;
    after a slip also any grasp from above at the same height on the object (it has the
    same shape there wherever it rolled to: a tapered neck that let go will let go again)."""
    same_spot = np.linalg.norm(a.position - b.position) < 0.01 and abs(a.closing @ b.closing) > 0.96
    from_above = a.tilt_rad < np.pi / 4 and b.tilt_rad < np.pi / 4
    same_height = from_above and abs(a.position[2] - b.position[2]) < 0.015
    return bool(same_spot or (slipped and same_height))


def _yaw_quat(yaw: float) -> Array:
    return np.array([np.cos(yaw / 2), 0.0, 0.0, np.sin(yaw / 2)])


def _region_around(geoms: dict[str, ObjectGeometry]) -> tuple[tuple[float, float], tuple[float, float]]:
    """Where objects may be put down when no workspace is given: around those there now."""
    pts = np.vstack([g.xy for g in geoms.values()])
    lo, hi = pts.min(axis=0) - 0.1, pts.max(axis=0) + 0.1
    return (float(lo[0]), float(hi[0])), (float(lo[1]), float(hi[1]))
