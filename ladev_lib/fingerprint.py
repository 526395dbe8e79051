"""One fingerprint mechanism for code and the data beside it.

Everything that caches work by content — episode ids (``rollout.identity``),
the offline LLM backend's cache keys (``llm.offline``) — and the check that
``dvc.yaml`` names every dependency of a stage (``tests/pipeline``) asks the
same question: *which files decide this result?* The answer here is the
import closure of some root modules, found by reading their imports (not by
importing them), plus the data files that sit in the directories of those
modules (catalogs, lexicons, templates, prompt files).

    files = closure_files(["ladev_lib.policies.grounded"])
    key = fingerprint(["ladev_lib.policies.grounded"], extra={"torch": "2.13"})

This module is the base layer: it imports nothing of ``ladev_lib``.
"""

from __future__ import annotations

import ast
import functools
import hashlib
import json
from collections.abc import Iterable, Mapping
from pathlib import Path

PACKAGE = "ladev_lib"
PACKAGE_ROOT = Path(__file__).resolve().parent
REPO_ROOT = PACKAGE_ROOT.parent
FINGERPRINT_VERSION = "fingerprint/v1"
"""Bumped when the way files are found or hashed changes."""

DATA_SUFFIXES: frozenset[str] = frozenset(
    {".yaml", ".yml", ".json", ".csv", ".txt", ".jinja", ".md", ".safetensors"}
)
"""Files beside a module that count as its data."""


def module_file(module: str) -> Path | None:
    """Source file of a ``ladev_lib`` module or package, or None (outside, or absent)."""
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


def imported_modules(module: str, path: Path) -> set[str]:
    """``ladev_lib`` modules imported anywhere in ``path`` (type-only and lazy imports included)."""
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
    return {m for m in found if module_file(m) is not None}


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
        path = module_file(name)
        if path is None:
            continue
        seen[name] = path
        for imported in imported_modules(name, path):
            stack.extend(_with_parents(imported))
    return sorted(set(seen.values()))


def script_closure(script: Path) -> list[Path]:
    """Library files a script outside the package (a stage, a benchmark) depends on."""
    tree = ast.parse(script.read_text(encoding="utf-8"), filename=str(script))
    roots: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            roots.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            roots.add(node.module)
            roots.update(f"{node.module}.{alias.name}" for alias in node.names)
    return module_closure(r for r in roots if module_file(r) is not None)


def package_modules(package: str) -> list[str]:
    """Every module of a ``ladev_lib`` package, recursively."""
    root = module_file(package)
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


def data_files(sources: Iterable[Path]) -> list[Path]:
    """Data files in the directories of ``sources`` (and in their non-package subdirectories)."""
    out: set[Path] = set()
    for directory in {p.parent for p in sources}:
        for path in directory.rglob("*"):
            if not path.is_file() or path.suffix not in DATA_SUFFIXES:
                continue
            # A subpackage's data belongs to that subpackage, counted when it is imported.
            between = path.relative_to(directory).parents
            if any((directory / d / "__init__.py").is_file() for d in between if str(d) != "."):
                continue
            out.add(path)
    return sorted(out)


def closure_files(roots: Iterable[str]) -> list[Path]:
    """Every file (source and data) that the modules ``roots`` depend on."""
    sources = module_closure(roots)
    return sorted({*sources, *data_files(sources)})


def hash_files(files: Iterable[Path], extra: Mapping[str, str] | None = None) -> str:
    """A short hash of the files' repository paths and bytes, plus ``extra`` facts."""
    digest = hashlib.sha256(FINGERPRINT_VERSION.encode())
    for path in sorted(set(files)):
        try:
            name = str(path.relative_to(REPO_ROOT))
        except ValueError:
            name = str(path)
        digest.update(name.encode())
        digest.update(b"\0")
        digest.update(path.read_bytes())
        digest.update(b"\0")
    digest.update(json.dumps(dict(extra or {}), sort_keys=True).encode())
    return digest.hexdigest()[:16]


@functools.lru_cache(maxsize=64)
def _cached(roots: tuple[str, ...], extra: tuple[tuple[str, str], ...]) -> str:
    return hash_files(closure_files(roots), dict(extra))


def fingerprint(roots: Iterable[str], extra: Mapping[str, str] | None = None) -> str:
    """Fingerprint of the code and data the modules ``roots`` depend on (cached per process)."""
    return _cached(tuple(sorted(set(roots))), tuple(sorted((extra or {}).items())))


def clear_cache() -> None:
    """Forget cached fingerprints (after editing files in a running process, e.g. in tests)."""
    _cached.cache_clear()


def dvc_missing_deps(dvc_yaml: Path | None = None) -> dict[str, list[str]]:
    """Per ``dvc.yaml`` stage, the files its script's closure holds that its ``deps`` do not cover.

    A stage ``name`` runs ``stages/<name>.py``; a dep covers a file when it is that
    file or a directory above it. ``scripts/dvc_deps.py --fix`` adds what is missing.
    """
    import yaml  # a dependency of the pipeline, not of the fingerprint itself

    path = dvc_yaml or REPO_ROOT / "dvc.yaml"
    stages = yaml.safe_load(path.read_text(encoding="utf-8"))["stages"]
    out: dict[str, list[str]] = {}
    for name, body in stages.items():
        body = body["do"] if "foreach" in body else body
        deps = [Path(d) for d in body.get("deps", []) if "${" not in d]
        sources = script_closure(path.parent / "stages" / f"{name}.py")
        files = sorted({*sources, *data_files(sources)})
        rels = [f.relative_to(REPO_ROOT) for f in files]
        out[name] = [str(r) for r in rels if not any(r == d or d in r.parents for d in deps)]
    return out
