"""``ladev_lib.llm`` is LLM plumbing (backends, client, cache, prompts): it imports no domain package.

The scene reader, the scene writer and the jobs the offline backend runs live
in ``language``, ``scenes`` and ``study``; they register with ``llm``, never
the other way round. Lazy imports inside functions and ``TYPE_CHECKING``
imports count too.
"""

from __future__ import annotations

import ast
from pathlib import Path

import ladev_lib.llm

DOMAIN = ("catalog", "language", "scenes", "study", "sim", "policies", "rollout", "report", "cli", "pipeline")


def _imports(path: Path) -> list[tuple[int, str]]:
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found: list[tuple[int, str]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.extend((node.lineno, alias.name) for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.append((node.lineno, node.module))
        elif isinstance(node, ast.ImportFrom) and node.level > 1:
            # a relative import that climbs out of llm
            found.append((node.lineno, "ladev_lib." + (node.module or "")))
    return found


def domain_imports(root: Path) -> list[str]:
    bad = []
    for path in sorted(root.rglob("*.py")):
        for line, module in _imports(path):
            parts = module.split(".")
            if parts[0] == "ladev_lib" and len(parts) > 1 and parts[1] in DOMAIN:
                bad.append(f"{path.relative_to(root.parent)}:{line} imports {module}")
    return bad


def test_llm_imports_no_domain_package() -> None:
    root = Path(ladev_lib.llm.__file__).parent
    assert domain_imports(root) == []


def test_the_walk_sees_lazy_and_type_checking_imports(tmp_path: Path) -> None:
    pkg = tmp_path / "llm"
    pkg.mkdir()
    (pkg / "a.py").write_text(
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n    from ladev_lib.scenes.spec import SceneSpec\n"
        "def f():\n    import ladev_lib.study.design\n"
        "from ladev_lib.llm.base import LLMRequest\n",
        encoding="utf-8",
    )
    bad = domain_imports(pkg)
    assert [b.split(" imports ")[1] for b in bad] == ["ladev_lib.scenes.spec", "ladev_lib.study.design"]
