"""Episode identity: a content hash of everything that decides an episode's outcome.

    episode_id = hash(scene spec, instruction text, policy name + config, seed,
                      sim config, robot config, which meshes are installed,
                      code fingerprint, options: trial and stop_on_success)

The code fingerprint (``ladev_lib.fingerprint``, the one mechanism the LLM
cache and the DVC dependency check use too) hashes the source of the modules an outcome depends on
(the simulator package, the episode loop, the policy's module and every
``ladev_lib`` module they import, found by reading their imports, not by
importing them) plus the data files beside them (the object catalog) and the
versions of the simulator stack. A code change therefore never serves a stale
cached episode, and a change to an unrelated policy adapter leaves the cache
of the others intact.
"""

from __future__ import annotations

import functools
import importlib.metadata
from typing import Any

from ladev_lib.assets import asset_dir
from ladev_lib.catalog import load_catalog
from ladev_lib.fingerprint import closure_files, hash_files, module_closure, package_modules
from ladev_lib.scenes import SceneSpec
from ladev_lib.store import content_key

__all__ = ["code_fingerprint", "episode_id", "module_closure", "package_modules"]

# What every episode's outcome depends on, whatever the policy.
ENGINE_MODULES: tuple[str, ...] = (
    "ladev_lib.rollout.episode",
    "ladev_lib.rollout.simulator",
    "ladev_lib.policies.base",
)
# Every module of these packages counts (the env registers tasks, robots, objects).
ENGINE_PACKAGES: tuple[str, ...] = ("ladev_lib.sim",)
EXTERNAL_DISTRIBUTIONS: tuple[str, ...] = ("mani-skill", "sapien", "mplib", "numpy", "torch")


def _distribution_versions() -> dict[str, str]:
    versions = {}
    for dist in EXTERNAL_DISTRIBUTIONS:
        try:
            versions[dist] = importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
            versions[dist] = "absent"
    return versions


@functools.lru_cache(maxsize=32)
def code_fingerprint(policy_module: str | None) -> str:
    """Hash of the code and data an episode of a policy from ``policy_module`` depends on."""
    roots = list(ENGINE_MODULES)
    for pkg in ENGINE_PACKAGES:
        roots += package_modules(pkg)
    if policy_module:
        roots.append(policy_module)
    return hash_files(closure_files(roots), _distribution_versions())


def asset_signature(spec: SceneSpec) -> list[str]:
    """Per object, whether it will be built from a real mesh or a stand-in here."""
    catalog = load_catalog()
    directory = asset_dir()
    out = []
    for obj in spec.objects:
        has_mesh = obj.id in catalog and catalog.get(obj.id).mesh_dir(directory) is not None
        out.append(f"{obj.id}:{'mesh' if has_mesh else 'standin'}")
    return out


def episode_id(
    *,
    spec: SceneSpec,
    instruction: str,
    policy_name: str,
    policy_config: dict[str, Any],
    seed: int,
    sim_config: dict[str, Any],
    robot_config: dict[str, Any],
    code: str,
    options: dict[str, Any] | None = None,
) -> str:
    """The content hash that names an episode in the store and in the table.

    ``options``: what else decides the outcome (the trial, ``stop_on_success``).
    """
    return content_key(
        "episode/v2",
        spec.model_dump(mode="json"),
        instruction,
        {"name": policy_name, "config": policy_config},
        seed,
        sim_config,
        robot_config,
        asset_signature(spec),
        code,
        options or {},
    )
