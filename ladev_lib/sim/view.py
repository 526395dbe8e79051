"""A read-only view of a LADEV scene for privileged policies.

Privileged policies (the oracle, ``grounded``) plan with the true state of the
scene: object poses and shapes, the robot's joints and hand, whether the hand
holds something. They get it through :class:`SceneView`, built here from the
env's own API, never the env itself: a policy cannot step, reset or edit the
simulation it is judged in. The view's methods read; none writes.

    view = scene_view(env.unwrapped)
    view.object_names()                   # ("coke_can", "plate")
    view.surface_points("plate")          # (N, 3) world-frame points on its collision surface
    view.robot.qpos(), view.robot.tcp_pose()
    view.is_grasping("coke_can")

Surface points come from the collision shapes PhysX simulates (primitives and
convex hulls), so what a planner sees is what the robot will touch.
ManiSkill's ``get_component_meshes`` builds cylinders and capsules along z,
while PhysX puts their axis along x; the shapes are built here for that reason.
This module is the one place outside the env that reads ManiSkill's entity
lists (``Actor._objs``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import sapien
import sapien.physx as physx
import trimesh
import trimesh.creation

from ladev_lib.arrays import Array

SURFACE_SAMPLES = 3000
"""Points sampled per object, on top of the mesh vertices (1 cm spacing on a can)."""

# PhysX cylinders and capsules lie along their local x axis; trimesh builds them along z.
_Z_TO_X = np.array(
    [[0.0, 0.0, 1.0, 0.0], [0.0, 1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
)


def shape_mesh(shape: physx.PhysxCollisionShape) -> trimesh.Trimesh | None:
    """The shape as a mesh in its body's frame; None for planes."""
    mesh: trimesh.Trimesh
    if isinstance(shape, physx.PhysxCollisionShapePlane):
        return None
    if isinstance(shape, physx.PhysxCollisionShapeBox):
        mesh = trimesh.creation.box(extents=2 * np.asarray(shape.half_size))
    elif isinstance(shape, physx.PhysxCollisionShapeSphere):
        mesh = trimesh.creation.icosphere(subdivisions=2, radius=shape.radius)
    elif isinstance(shape, physx.PhysxCollisionShapeCapsule):
        mesh = trimesh.creation.capsule(height=2 * shape.half_length, radius=shape.radius)
        mesh.apply_transform(_Z_TO_X)
    elif isinstance(shape, physx.PhysxCollisionShapeCylinder):
        mesh = trimesh.creation.cylinder(radius=shape.radius, height=2 * shape.half_length)
        mesh.apply_transform(_Z_TO_X)
    elif isinstance(
        shape, physx.PhysxCollisionShapeConvexMesh | physx.PhysxCollisionShapeTriangleMesh
    ):
        vertices = np.asarray(shape.vertices) * np.asarray(shape.scale)
        mesh = trimesh.Trimesh(vertices=vertices, faces=np.asarray(shape.get_triangles()))
    else:
        raise TypeError(f"unsupported collision shape {type(shape).__name__}")
    mesh.apply_transform(shape.get_local_pose().to_transformation_matrix())
    return mesh


def body_of(actor: Any) -> physx.PhysxRigidBaseComponent:
    """The PhysX body of a ManiSkill ``Actor`` (first sub-scene), or of a SAPIEN entity."""
    entity = actor._objs[0] if hasattr(actor, "_objs") else actor
    body = entity.find_component_by_type(physx.PhysxRigidBaseComponent)
    if body is None:
        raise ValueError(f"actor {getattr(actor, 'name', actor)!r} has no physical body")
    return body


def body_mesh(body: physx.PhysxRigidBaseComponent) -> trimesh.Trimesh:
    """All collision shapes of a body merged into one mesh, in the body's frame."""
    meshes = [m for m in (shape_mesh(s) for s in body.get_collision_shapes()) if m is not None]
    if not meshes:
        raise ValueError(f"body {body.entity.name!r} has no collision shape to plan with")
    merged = trimesh.util.concatenate(meshes)
    assert isinstance(merged, trimesh.Trimesh)
    return merged


def sample_surface(mesh: trimesh.Trimesh, count: int = SURFACE_SAMPLES, seed: int = 0) -> Array:
    """Vertices plus ``count`` area-weighted samples of the surface (deterministic)."""
    samples, _ = trimesh.sample.sample_surface(mesh, count, seed=seed)
    return np.vstack([np.asarray(mesh.vertices), np.asarray(samples)])


def transform_points(pose: sapien.Pose, points: Array) -> Array:
    """``points`` (N, 3) moved by ``pose``."""
    m = pose.to_transformation_matrix()
    return np.asarray(np.asarray(points) @ m[:3, :3].T + m[:3, 3])


def _first(tensor: Any) -> Array:
    """Row 0 of a batched ManiSkill tensor as float numpy."""
    return np.asarray(tensor[0].detach().cpu().numpy(), dtype=float)


class RobotView:
    """The robot as a planner reads it: its model files, joints, hand and gripper range."""

    def __init__(self, agent: Any) -> None:
        self._agent = agent

    @property
    def urdf_path(self) -> str:
        return str(self._agent.urdf_path)

    def link_names(self) -> list[str]:
        return [link.get_name() for link in self._agent.robot.get_links()]

    def active_joint_names(self) -> list[str]:
        return [joint.get_name() for joint in self._agent.robot.get_active_joints()]

    def base_pose(self) -> sapien.Pose:
        pose: sapien.Pose = self._agent.robot.pose.sp
        return pose

    def qpos(self) -> Array:
        return _first(self._agent.robot.get_qpos())

    def qvel(self) -> Array:
        return _first(self._agent.robot.get_qvel())

    def tcp_pose(self) -> sapien.Pose:
        pose: sapien.Pose = self._agent.tcp.pose.sp
        return pose

    def gripper_limits(self) -> tuple[float, float]:
        """(lower, upper) finger joint targets of the gripper controller (m per finger)."""
        ctrl = self._agent.controller.controllers.get("gripper")
        cfg = getattr(ctrl, "config", None)
        lower = float(np.atleast_1d(getattr(cfg, "lower", -0.01))[0])
        upper = float(np.atleast_1d(getattr(cfg, "upper", 0.04))[0])
        return lower, upper


class SceneView:
    """Objects and robot of one LADEV scene, read-only (see the module docstring)."""

    def __init__(self, env: Any) -> None:
        self._env = env
        self.robot = RobotView(env.agent)
        self.control_timestep = float(env.control_timestep)

    def object_names(self) -> tuple[str, ...]:
        return tuple(self._env.objects)

    def object_pose(self, name: str) -> Array:
        """World pose [x, y, z, qw, qx, qy, qz]."""
        return np.asarray(self._env.object_poses()[name], dtype=float)

    def surface_points(self, name: str, count: int = SURFACE_SAMPLES) -> Array:
        """(N, 3) world-frame points on the object's collision surface, now."""
        body = body_of(self._env.objects[name])
        local = sample_surface(body_mesh(body), count)
        return transform_points(body.get_entity_pose(), local)

    def is_grasping(self, name: str) -> bool:
        return bool(self._env.agent.is_grasping(self._env.objects[name])[0])


def scene_view(env: Any) -> SceneView:
    """The read-only view of a ``LADEV-Scene-v1`` env (wrapped or not)."""
    return SceneView(getattr(env, "unwrapped", env))
