"""The optional asset pack: real meshes, robots and backgrounds under MS_ASSET_DIR.

LADEV works without it (procedural stand-ins, Panda) and uses it when present.
ManiSkill reads the same variable, so its own loaders find the files too.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from ladev_lib.catalog import Catalog, load_catalog

BRIDGE_DIR = "data/tasks/bridge_v2_real2sim_dataset"
OVERLAY_DIR = f"{BRIDGE_DIR}/real_inpainting"
ROBOT_URDFS = {
    "widowx": "data/robots/widowx/wx250s.urdf",
    "google_robot": "data/robots/googlerobot/google_robot_meta_sim_fix_wheel_fix_fingertip.urdf",
}


def asset_dir() -> Path | None:
    """MS_ASSET_DIR when it is set and exists, else None."""
    value = os.environ.get("MS_ASSET_DIR")
    if not value:
        return None
    p = Path(value).expanduser()
    return p if p.is_dir() else None


@dataclass(frozen=True)
class AssetSummary:
    """What an asset dir provides, for ``ladev doctor`` and the scene record."""

    directory: Path | None
    meshes_by_set: dict[str, tuple[int, int]]
    """set -> (objects with a mesh present, objects in the catalog)."""
    robots: dict[str, bool]
    overlays: int


def summarize_assets(directory: Path | None = None, catalog: Catalog | None = None) -> AssetSummary:
    directory = directory if directory is not None else asset_dir()
    catalog = catalog or load_catalog()
    counts: dict[str, tuple[int, int]] = {}
    for obj in catalog:
        have, total = counts.get(obj.set, (0, 0))
        counts[obj.set] = (have + (obj.mesh_dir(directory) is not None), total + 1)
    robots = {r: bool(directory and (directory / p).exists()) for r, p in ROBOT_URDFS.items()}
    overlays = len(list((directory / OVERLAY_DIR).glob("*.png"))) if directory else 0
    return AssetSummary(directory, counts, robots, overlays)
