"""Object geometry for privileged planners: surface points of an actor's collision shapes.

The oracle reasons on point sets, not on boxes: a banana, a mug with its handle or
a bottle with a cap are poorly described by one oriented box, while a few
thousand surface points answer every question the skills ask (how wide is the
object between the fingers here, how high is its top under the palm, where is
the floor of this bowl) with the same few lines of numpy.

Points are sampled from the collision shapes PhysX simulates (primitives and
convex hulls), so what the planner sees is what the robot will touch.
ManiSkill's ``get_component_meshes`` builds cylinders and capsules along z,
while PhysX puts their axis along x; we build primitives ourselves for that
reason.
"""

from __future__ import annotations

from dataclasses import dataclass
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


def _shape_mesh(shape: physx.PhysxCollisionShape) -> trimesh.Trimesh | None:
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
    meshes = [m for m in (_shape_mesh(s) for s in body.get_collision_shapes()) if m is not None]
    if not meshes:
        raise ValueError(f"body {body.entity.name!r} has no collision shape to plan with")
    merged = trimesh.util.concatenate(meshes)
    assert isinstance(merged, trimesh.Trimesh)
    return merged


def surface_points(mesh: trimesh.Trimesh, count: int = SURFACE_SAMPLES, seed: int = 0) -> Array:
    """Vertices plus ``count`` area-weighted samples of the surface (deterministic)."""
    samples, _ = trimesh.sample.sample_surface(mesh, count, seed=seed)
    return np.vstack([np.asarray(mesh.vertices), np.asarray(samples)])


def transform_points(pose: sapien.Pose, points: Array) -> Array:
    m = pose.to_transformation_matrix()
    return np.asarray(np.asarray(points) @ m[:3, :3].T + m[:3, 3])


@dataclass(frozen=True)
class ObjectGeometry:
    """Surface points of one object, in the world frame at the time they were taken."""

    name: str
    points: Array
    """(N, 3) world-frame points on the collision surface."""

    @classmethod
    def of_actor(cls, name: str, actor: Any, count: int = SURFACE_SAMPLES) -> ObjectGeometry:
        body = body_of(actor)
        local = surface_points(body_mesh(body), count)
        return cls(name, transform_points(body.get_entity_pose(), local))

    @property
    def bottom_z(self) -> float:
        return float(self.points[:, 2].min())

    @property
    def top_z(self) -> float:
        return float(self.points[:, 2].max())

    @property
    def xy(self) -> Array:
        return self.points[:, :2]

    def footprint(self) -> tuple[Array, Array, Array]:
        """Minimum-area rectangle around the xy projection: (centre, axes, half extents).

        ``axes`` rows are unit vectors, the first along the long side.
        """
        return footprint_rectangle(self.xy)


def footprint_rectangle(xy: Array) -> tuple[Array, Array, Array]:
    """Minimum-area rectangle of 2-D points: (centre, axes (long first), half extents)."""
    transform, extents = trimesh.bounds.oriented_bounds_2D(np.asarray(xy, dtype=float))
    to_world = np.linalg.inv(transform)  # rectangle frame -> input frame
    axes = to_world[:2, :2].T.copy()  # rows: rectangle x and y axes in the input frame
    centre = to_world[:2, 2].copy()
    half = np.asarray(extents, dtype=float) / 2
    if half[1] > half[0]:
        axes, half = axes[::-1].copy(), half[::-1].copy()
    return centre, axes, half
