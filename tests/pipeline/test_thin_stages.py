"""Stage scripts and the compile command are thin: they call ``ladev_lib.pipeline``, nothing more.

Checked on the source (AST): under 45 code lines per stage script, no loops or
comprehensions, no table rows built, and only the pipeline (plus ``load_params``)
imported from the library. And the pipeline sits on top: nothing below imports it.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from ladev_lib.fingerprint import PACKAGE_ROOT, REPO_ROOT, imported_modules

STAGES = sorted((REPO_ROOT / "stages").glob("*.py"))
THIN_CLI = [PACKAGE_ROOT / "cli" / "compile.py", PACKAGE_ROOT / "cli" / "_scene_setup.py"]
MAX_CODE_LINES = 45
LOOPS = (ast.For, ast.AsyncFor, ast.While, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp)


def code_lines(source: str) -> int:
    """Non-blank lines that are not only a comment (docstrings count)."""
    return sum(1 for line in source.splitlines() if line.strip() and not line.strip().startswith("#"))


def problems(path: Path) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, LOOPS):
            found.append(f"line {node.lineno}: a {type(node).__name__}")
        elif isinstance(node, ast.Call):
            func = node.func
            name = func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""
            if name.endswith("Row") or name in {"row", "as_dict", "write_table", "CompiledScene", "SceneText"}:
                found.append(f"line {node.lineno}: builds a row ({name})")
        elif isinstance(node, ast.ImportFrom) and node.module == "ladev_lib.tables":
            found.append(f"line {node.lineno}: imports ladev_lib.tables")
    return found


def test_there_is_one_script_per_stage():
    assert [p.stem for p in STAGES] == sorted(["generate", "compile", "paraphrase", "rollout", "aggregate"])


@pytest.mark.parametrize("path", STAGES + THIN_CLI, ids=lambda p: p.name)
def test_no_loops_and_no_rows(path: Path):
    assert not problems(path), f"{path.relative_to(REPO_ROOT)}: move this into ladev_lib.pipeline: {problems(path)}"


@pytest.mark.parametrize("path", STAGES, ids=lambda p: p.name)
def test_stage_scripts_are_short_and_call_only_the_pipeline(path: Path):
    n = code_lines(path.read_text(encoding="utf-8"))
    assert n < MAX_CODE_LINES, f"{path.name}: {n} code lines"
    library = imported_modules(f"stages.{path.stem}", path)
    assert library and all(m.startswith("ladev_lib.pipeline") or m in {"ladev_lib.config", "ladev_lib"}
                           for m in library), sorted(library)
    assert f"ladev_lib.pipeline.{path.stem}" in library


def test_the_checks_see_a_fat_stage(tmp_path: Path):
    fat = tmp_path / "fat.py"
    fat.write_text(
        '"""A stage doing its own work."""\n# a comment\n\n'
        "from ladev_lib.tables import CompiledSceneRow, write_table\n"
        "rows = [CompiledSceneRow(scene_id=s) for s in 'ab']\n"
        "for r in rows:\n    print(r)\n"
        "write_table(rows, 'x.parquet', CompiledSceneRow)\n"
    )
    assert code_lines(fat.read_text()) == 6  # not the blank line, not the comment
    found = problems(fat)
    assert any("ListComp" in p for p in found) and any("For" in p for p in found)
    assert any("CompiledSceneRow" in p for p in found) and any("write_table" in p for p in found)
    assert any("imports ladev_lib.tables" in p for p in found)


def _module_name(path: Path) -> str:
    parts = path.relative_to(REPO_ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def test_nothing_below_the_pipeline_imports_it():
    climbs = []
    for path in sorted(PACKAGE_ROOT.rglob("*.py")):
        rel = path.relative_to(PACKAGE_ROOT).parts
        if rel[0] in {"pipeline", "cli"}:
            continue
        climbs += [f"{path.relative_to(REPO_ROOT)} imports {m}" for m in imported_modules(_module_name(path), path)
                   if m.startswith("ladev_lib.pipeline")]
    assert not climbs


def test_the_pipeline_does_not_import_the_cli():
    for path in sorted((PACKAGE_ROOT / "pipeline").glob("*.py")):
        assert not any(m.startswith("ladev_lib.cli") for m in imported_modules(_module_name(path), path)), path
