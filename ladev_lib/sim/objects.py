"""Build catalog objects into a ManiSkill scene: real meshes or procedural stand-ins.

Every object is built so that its actor frame stands *upright*: a mesh's
``upright_euler_deg`` rotation is baked into its shapes' local poses, so placing an
object is a position plus a yaw about z. :class:`BuiltObject` records which way
it was built (``"mesh"`` or ``"standin"``) and its box in the actor frame, which
the task predicates and the spawn height use.

Meshes (when ``MS_ASSET_DIR`` holds them) load with the calls ManiSkill's own
loaders make: convex collision hulls from ``collision.obj``/``collision.ply``
(``add_multiple_convex_collisions_from_file``) and the visual from the first of
``textured.obj``, ``textured.dae``, ``textured.glb`` (``add_visual_from_file``).
Their density gives the catalog's mass on the hulls PhysX cooks, so the catalog is
the one source of masses for meshes and stand-ins alike.

Stand-ins have the catalog's shape, size, colour and mass. A ``container`` is an
open box (floor and four walls) so objects can be put *in* it.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np
import sapien
import trimesh
from transforms3d.euler import euler2quat

from ladev_lib.arrays import Array
from ladev_lib.catalog import CatalogObject
from ladev_lib.scenes.feasibility import CONTAINER_WALL_M

ObjectSource = Literal["mesh", "standin"]

FRICTION = 0.5  # SimplerEnv's object friction (static = dynamic), restitution 0
DAMPING = 0.1  # SimplerEnv's linear/angular damping for scene objects
_VISUAL_FILES = ("textured.obj", "textured.dae", "textured.glb")
_COLLISION_FILES = ("collision.obj", "collision.ply")


@dataclass(frozen=True)
class BuiltObject:
    """One object as built: its actor and its upright box in the actor frame."""

    name: str
    catalog_id: str
    source: ObjectSource
    box_center: Array
    """Centre of the collision box in the actor frame (m)."""
    half_extents: Array
    """Half size of the collision box along the actor's x, y, z (m)."""

    @property
    def bottom_z(self) -> float:
        """Height of the lowest collision point below the actor origin (positive, m)."""
        return float(self.half_extents[2] - self.box_center[2])


def srgb_to_linear(color: tuple[float, float, float]) -> list[float]:
    """Catalog colours are sRGB (texture medians); SAPIEN materials take linear RGB."""
    return [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in color]


def _material(obj: CatalogObject) -> sapien.render.RenderMaterial:
    return sapien.render.RenderMaterial(
        base_color=[*srgb_to_linear(obj.color), 1.0], roughness=0.6, metallic=0.0, specular=0.3
    )


def _physx_material() -> sapien.physx.PhysxMaterial:
    return sapien.physx.PhysxMaterial(
        static_friction=FRICTION, dynamic_friction=FRICTION, restitution=0.0
    )


# --- stand-ins --------------------------------------------------------------------
# SAPIEN's cylinders and capsules lie along their local x axis.
_X_TO_Z = sapien.Pose(q=euler2quat(0, -math.pi / 2, 0))
_X_TO_Y = sapien.Pose(q=euler2quat(0, 0, math.pi / 2))


def _standin_shapes(obj: CatalogObject) -> tuple[list[tuple[str, sapien.Pose, tuple[float, ...]]], Array]:
    """Primitive shapes (kind, local pose, dimensions) and the half extents they span."""
    sx, sy, sz = obj.size_m
    shape = obj.shape
    if shape in ("box", "flat"):
        half = (sx / 2, sy / 2, sz / 2)
        return [("box", sapien.Pose(), half)], np.array(half)
    if shape in ("cylinder", "plate"):
        if max(sx, sy) <= 1.15 * min(sx, sy):
            r = (sx + sy) / 4
            return [("cylinder", _X_TO_Z, (r, sz / 2))], np.array([r, r, sz / 2])
        # An oval footprint (bleach, mustard bottles): a stadium, box between two half-cylinders.
        r, half_len = min(sx, sy) / 2, max(sx, sy) / 2 - min(sx, sy) / 2
        axis = np.array([1.0, 0.0, 0.0]) if sx >= sy else np.array([0.0, 1.0, 0.0])
        box_half = (half_len, r, sz / 2) if sx >= sy else (r, half_len, sz / 2)
        parts: list[tuple[str, sapien.Pose, tuple[float, ...]]] = [("box", sapien.Pose(), box_half)]
        for sign in (-1.0, 1.0):
            parts.append(("cylinder", sapien.Pose(p=(sign * half_len * axis).tolist(), q=_X_TO_Z.q), (r, sz / 2)))
        return parts, np.array([sx / 2, sy / 2, sz / 2])
    if shape == "sphere":
        r = (sx + sy + sz) / 6
        return [("sphere", sapien.Pose(), (r,))], np.array([r, r, r])
    if shape == "capsule":
        along_x = sx >= sy
        length, width = (sx, sy) if along_x else (sy, sx)
        r = min(width, sz) / 2
        half_len = max(length / 2 - r, 1e-3)
        pose = sapien.Pose() if along_x else _X_TO_Y
        half = (half_len + r, r, r) if along_x else (r, half_len + r, r)
        return [("capsule", pose, (r, half_len))], np.array(half)
    if shape == "container":
        wall = min(CONTAINER_WALL_M, sx / 6, sy / 6)
        floor = min(CONTAINER_WALL_M, sz / 4)
        hx, hy, hz = sx / 2, sy / 2, sz / 2
        wall_hz = (sz - floor) / 2
        wall_z = -hz + floor + wall_hz
        parts = [
            ("box", sapien.Pose([0, 0, -hz + floor / 2]), (hx, hy, floor / 2)),
            ("box", sapien.Pose([hx - wall / 2, 0, wall_z]), (wall / 2, hy, wall_hz)),
            ("box", sapien.Pose([-hx + wall / 2, 0, wall_z]), (wall / 2, hy, wall_hz)),
            ("box", sapien.Pose([0, hy - wall / 2, wall_z]), (hx - wall, wall / 2, wall_hz)),
            ("box", sapien.Pose([0, -hy + wall / 2, wall_z]), (hx - wall, wall / 2, wall_hz)),
        ]
        return parts, np.array([hx, hy, hz])
    raise ValueError(f"catalog object {obj.id!r}: no stand-in for shape {shape!r}")


def _volume(kind: str, dims: tuple[float, ...]) -> float:
    if kind == "box":
        return 8 * dims[0] * dims[1] * dims[2]
    if kind == "cylinder":
        return math.pi * dims[0] ** 2 * 2 * dims[1]
    if kind == "sphere":
        return 4 / 3 * math.pi * dims[0] ** 3
    if kind == "capsule":
        r, half_len = dims
        return math.pi * r * r * 2 * half_len + 4 / 3 * math.pi * r**3
    raise ValueError(kind)


def add_standin_shapes(builder: sapien.ActorBuilder, obj: CatalogObject) -> Array:
    """Add the stand-in's collision and visual shapes; returns its half extents."""
    parts, half = _standin_shapes(obj)
    density = obj.mass_kg / sum(_volume(kind, dims) for kind, _, dims in parts)
    mat, phys = _material(obj), _physx_material()
    for kind, pose, dims in parts:
        if kind == "box":
            builder.add_box_collision(pose, half_size=dims, material=phys, density=density)
            builder.add_box_visual(pose, half_size=dims, material=mat)
        elif kind == "cylinder":
            builder.add_cylinder_collision(pose, radius=dims[0], half_length=dims[1], material=phys, density=density)
            builder.add_cylinder_visual(pose, radius=dims[0], half_length=dims[1], material=mat)
        elif kind == "sphere":
            builder.add_sphere_collision(pose, radius=dims[0], material=phys, density=density)
            builder.add_sphere_visual(pose, radius=dims[0], material=mat)
        elif kind == "capsule":
            builder.add_capsule_collision(pose, radius=dims[0], half_length=dims[1], material=phys, density=density)
            builder.add_capsule_visual(pose, radius=dims[0], half_length=dims[1], material=mat)
    return half


# --- meshes -----------------------------------------------------------------------
def _first_existing(directory: Path, names: tuple[str, ...]) -> Path | None:
    for n in names:
        if (directory / n).exists():
            return directory / n
    return None


@functools.lru_cache(maxsize=256)
def cooked_hull_volume(collision_file: str) -> float:
    """Volume in m^3 of the convex hulls PhysX cooks from ``collision_file``.

    Measured as the mass of the hulls at density 1, on a scratch scene, so that it is
    exactly what the simulator will integrate (one hull per connected component).
    """
    material = sapien.physx.PhysxMaterial(0.5, 0.5, 0.0)
    shapes = sapien.physx.PhysxCollisionShapeConvexMesh.load_multiple(
        filename=collision_file, scale=[1.0, 1.0, 1.0], material=material
    )
    body = sapien.physx.PhysxRigidDynamicComponent()
    for shape in shapes:
        shape.set_density(1.0)
        body.attach(shape)
    entity = sapien.Entity()
    entity.add_component(body)
    sapien.Scene().add_entity(entity)
    volume = float(body.get_mass())
    if volume <= 0.0:
        raise ValueError(f"{collision_file}: PhysX cooked no volume from its hulls")
    return volume


def _mesh_box(collision_file: str, upright: tuple[float, float, float]) -> tuple[Array, Array]:
    """(centre, half extents) of the collision mesh after the upright rotation."""
    mesh = trimesh.load(collision_file, force="mesh")
    if not isinstance(mesh, trimesh.Trimesh):
        raise ValueError(f"{collision_file}: not a single mesh ({type(mesh).__name__})")
    q = euler2quat(*np.radians(upright))
    rot = sapien.Pose(q=q).to_transformation_matrix()[:3, :3]
    v = np.asarray(mesh.vertices) @ rot.T
    lo, hi = v.min(axis=0), v.max(axis=0)
    return (lo + hi) / 2, (hi - lo) / 2


def mesh_files(obj: CatalogObject, asset_dir: Path | None) -> tuple[Path, Path] | None:
    """(collision file, visual file) when ``asset_dir`` holds this object's mesh."""
    directory = obj.mesh_dir(asset_dir)
    if directory is None:
        return None
    collision = _first_existing(directory, _COLLISION_FILES)
    visual = _first_existing(directory, _VISUAL_FILES)
    if collision is None or visual is None:
        return None
    return collision, visual


def add_mesh_shapes(
    builder: sapien.ActorBuilder, obj: CatalogObject, files: tuple[Path, Path]
) -> tuple[Array, Array]:
    """Add the real mesh's hulls and visual; returns (box centre, half extents)."""
    assert obj.mesh is not None
    collision, visual = files
    ux, uy, uz = (float(a) for a in obj.mesh.upright_euler_deg)
    upright = (ux, uy, uz)
    pose = sapien.Pose(q=euler2quat(*np.radians(upright)))
    # The catalog is the one source of masses, for meshes as for stand-ins: the density
    # that gives the catalog mass on the hulls PhysX actually cooks from this file.
    density = obj.mass_kg / cooked_hull_volume(str(collision))
    builder.add_multiple_convex_collisions_from_file(
        filename=str(collision), pose=pose, material=_physx_material(), density=density
    )
    builder.add_visual_from_file(filename=str(visual), pose=pose)
    return _mesh_box(str(collision), upright)


def build_object(
    scene: object,
    obj: CatalogObject,
    name: str,
    asset_dir: Path | None,
    initial_pose: sapien.Pose,
    prefer_mesh: bool = True,
) -> tuple[object, BuiltObject]:
    """Build ``obj`` as a dynamic actor named ``name``; mesh when available, else stand-in."""
    # ManiSkill's scene class is not typed for mypy here (mani_skill is an untyped import), so the
    # parameter is `object`; create_actor_builder is its public API.
    builder = scene.create_actor_builder()  # type: ignore[attr-defined]
    files = mesh_files(obj, asset_dir) if prefer_mesh else None
    if files is not None:
        center, half = add_mesh_shapes(builder, obj, files)
        source: ObjectSource = "mesh"
    else:
        half = add_standin_shapes(builder, obj)
        center, source = np.zeros(3), "standin"
    builder.initial_pose = initial_pose
    actor = builder.build(name=name)
    actor.set_linear_damping(DAMPING)
    actor.set_angular_damping(DAMPING)
    return actor, BuiltObject(name, obj.id, source, np.asarray(center, float), np.asarray(half, float))
