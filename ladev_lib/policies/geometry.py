"""Object geometry for privileged planners: surface points of an object's collision shapes.

The oracle reasons on point sets, not on boxes: a banana, a mug with its handle or
a bottle with a cap are poorly described by one oriented box, while a few
thousand surface points answer every question the skills ask (how wide is the
object between the fingers here, how high is its top under the palm, where is
the floor of this bowl) with the same few lines of numpy.

The points come from the scene's read-only view (:mod:`ladev_lib.sim.view`),
which samples the collision shapes PhysX simulates.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import trimesh

from ladev_lib.arrays import Array
from ladev_lib.sim.view import SURFACE_SAMPLES, transform_points
from ladev_lib.sim.view import sample_surface as surface_points

if TYPE_CHECKING:
    from ladev_lib.sim.view import SceneView

__all__ = ["SURFACE_SAMPLES", "ObjectGeometry", "footprint_rectangle", "surface_points", "transform_points"]


@dataclass(frozen=True)
class ObjectGeometry:
    """Surface points of one object, in the world frame at the time they were taken."""

    name: str
    points: Array
    """(N, 3) world-frame points on the collision surface."""

    @classmethod
    def of(cls, view: SceneView, name: str, count: int = SURFACE_SAMPLES) -> ObjectGeometry:
        """The object ``name`` of the scene ``view`` as it is now."""
        return cls(name, view.surface_points(name, count))

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
