"""Episode identity: a content hash of everything that decides an episode's outcome.

    episode_id = hash(scene spec, instruction text, policy name + config, seed,
                      sim config, robot config, which meshes are installed,
                      code fingerprint, options: trial and stop_on_success)

The code fingerprint hashes the source of the modules an outcome depends on
(the simulator package, the episode loop, the policy's module and every
``ladev_lib`` module they import, found by reading their imports, not by
importing them) plus the data files beside them (the object catalog) and the
versions of the simulator stack. A code change therefore never serves a stale
cached episode, and a change to an unrelated policy adapter leaves the cache
of the others intact.
"""

from __future__ import annotations

import ast
import functools
import hashlib
import importlib.metadata
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ladev_lib.assets import asset_dir
from ladev_lib.catalog import load_catalog
from ladev_lib.scenes import SceneSpec
from ladev_lib.store import content_key

PACKAGE = "ladev_lib"
PACKAGE_ROOT = Path(__file__).resolve().parents[1]

# What every episode's outcome depends on, whatever the policy.
ENGINE_MODULES: tuple[str, ...] = (
    "ladev_lib.rollout.episode",
    "ladev_lib.rollout.simulator",
    "ladev_lib.policies.base",
)
# Every module of these packages counts (the env registers tasks, robots, objects).
ENGINE_PACKAGES: tuple[str, ...] = ("ladev_lib.sim",)
EXTERNAL_DISTRIBUTIONS: tuple[str, ...] = ("mani-skill", "sapien", "mplib", "numpy", "torch")
DATA_SUFFIXES: frozenset[str] = frozenset({".yaml", ".yml", ".json", ".csv"})


def _module_file(module: str) -> Path | None:
    if module != PACKAGE and not module.startswith(PACKAGE + "."):
        return None
    parts = module.split(".")[1:]
    if not parts:
        return PACKAGE_ROOT / "__init__.py"
    rel = Path(*parts)
    for candidate in (PACKAGE_ROOT / rel.with_suffix(".py"), PACKAGE_ROOT / rel / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def _is_package(path: Path) -> bool:
    return path.name == "__init__.py"


def _imported_modules(module: str, path: Path) -> set[str]:
    """``ladev_lib`` modules imported anywhere in ``path`` (type-only imports included)."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    package = module if _is_package(path) else module.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base_parts = package.split(".")
                base_parts = base_parts[: len(base_parts) - (node.level - 1)]
                base = ".".join(base_parts + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            found.add(base)
            # "from pkg import name" may import a submodule.
            found.update(f"{base}.{alias.name}" for alias in node.names)
    return {m for m in found if _module_file(m) is not None}


def _with_parents(module: str) -> list[str]:
    parts = module.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts) + 1)]


def module_closure(roots: Iterable[str]) -> list[Path]:
    """Source files of ``roots`` and of every ``ladev_lib`` module they import, transitively."""
    seen: dict[str, Path] = {}
    stack = [m for r in roots for m in _with_parents(r)]
    while stack:
        name = stack.pop()
        if name in seen:
            continue
        path = _module_file(name)
        if path is None:
            continue
        seen[name] = path
        for imported in _imported_modules(name, path):
            stack.extend(_with_parents(imported))
    return sorted(set(seen.values()))


def package_modules(package: str) -> list[str]:
    """Every module of a ``ladev_lib`` package, recursively."""
    root = _module_file(package)
    if root is None or not _is_package(root):
        return []
    out = []
    for path in sorted(root.parent.rglob("*.py")):
        rel = path.relative_to(PACKAGE_ROOT).with_suffix("")
        parts = [PACKAGE, *rel.parts]
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out.append(".".join(parts))
    return out


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
    files = module_closure(roots)
    data_files = sorted({p for f in files for p in f.parent.iterdir() if p.suffix in DATA_SUFFIXES})
    h = hashlib.sha256()
    for path in [*files, *data_files]:
        h.update(str(path.relative_to(PACKAGE_ROOT)).encode())
        h.update(b"\0")
        h.update(path.read_bytes())
        h.update(b"\0")
    h.update(content_key(_distribution_versions()).encode())
    return h.hexdigest()[:16]


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
