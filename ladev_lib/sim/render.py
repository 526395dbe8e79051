"""Render a scene spec to images: the policy camera and an overview camera.

    shots = render_spec(spec, SimConfig())
    save_side_by_side(shots, "scene.png")

For many specs, pass the same ``env`` (made with :func:`ladev_lib.sim.make_env`):
each spec is then built with ``reset(options={"spec": ...})`` instead of a new env.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.scenes.spec import SceneSpec
from ladev_lib.sim.config import SimConfig


@dataclass(frozen=True)
class SceneShots:
    """Images of one built scene and what was built."""

    policy: Array
    """(H, W, 3) uint8: what the policy sees (with the real background when active)."""
    overview: Array
    """(H, W, 3) uint8: a wider view from the front-right of the workspace."""
    object_sources: dict[str, str]
    robot: str
    overlay: bool
    validity: Any = None
    """A ``ValidityVerdict`` when asked for (``check=True``)."""


def render_spec(
    spec: SceneSpec,
    sim_config: SimConfig | None = None,
    *,
    robot: str | None = None,
    image_size: tuple[int, int] | None = None,
    env: Any = None,
    check: bool = False,
) -> SceneShots:
    """Build ``spec`` (in ``env`` when given, else a new env) and take both pictures."""
    from ladev_lib.sim import make_env
    from ladev_lib.sim.validity import check_scene

    cfg = sim_config or SimConfig()
    if image_size is not None:
        cfg = cfg.model_copy(update={"image_size": image_size})
    if env is None:
        env = make_env(spec, cfg, control_mode=None, robot=robot)
        env.reset(seed=spec.seed)
    else:
        env.reset(seed=spec.seed, options={"spec": spec.model_dump(mode="json")})
    u = env.unwrapped
    return SceneShots(
        policy=u.policy_image(),
        overview=u.overview_image(),
        object_sources=dict(u.object_sources),
        robot=u.profile.name,
        overlay=u.overlay_active,
        validity=check_scene(u) if check else None,
    )


def side_by_side(left: Array, right: Array, gap: int = 4) -> Array:
    """Both images at the taller one's height, left to right, on a white background."""
    from PIL import Image

    h = max(left.shape[0], right.shape[0])

    def fit(img: Array) -> Array:
        if img.shape[0] == h:
            return img
        w = round(img.shape[1] * h / img.shape[0])
        return np.asarray(Image.fromarray(img).resize((w, h), Image.Resampling.NEAREST))

    a, b = fit(left), fit(right)
    canvas = np.full((h, a.shape[1] + gap + b.shape[1], 3), 255, dtype=np.uint8)
    canvas[:, : a.shape[1]] = a
    canvas[:, a.shape[1] + gap :] = b
    return canvas


def save_shots(shots: SceneShots, path: str | Path, separate: bool = False) -> list[Path]:
    """Write ``path`` (policy | overview side by side), or two files with ``separate``."""
    from PIL import Image

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if not separate:
        Image.fromarray(side_by_side(shots.policy, shots.overview)).save(path)
        return [path]
    out = [path.with_name(f"{path.stem}_policy{path.suffix}"), path.with_name(f"{path.stem}_overview{path.suffix}")]
    Image.fromarray(shots.policy).save(out[0])
    Image.fromarray(shots.overview).save(out[1])
    return out
