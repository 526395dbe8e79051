"""Stage ``compile``: scene descriptions -> validated scene specs (or rejections with reasons).

Reads ``study.bounds``, ``llm``, ``compile``, ``prompts.compile_scene``, ``catalog``
and ``paths``; writes ``paths.compiled``. LLM calls are cached in
``paths.llm_cache_dir/compile``. A bad description is a ``rejected`` row, never a
crash. The physical-validity check runs at rollout, at the start of each episode: its
verdict is the episode's ``invalid_scene`` status.

``ladev compile`` (a user's own JSONL of descriptions) and ``ladev scene`` use the
same set-up (:func:`scene_compiler`) and the same thread pool (:func:`compile_all`).
"""

from __future__ import annotations

import json
import sys
from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from pydantic import BaseModel, ConfigDict, ValidationError
from tqdm import tqdm

from ladev_lib.catalog import load_catalog
from ladev_lib.config import section
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig, make_client
from ladev_lib.llm.prompts import load_prompts
from ladev_lib.pipeline import StageMessages
from ladev_lib.scenes.compiler import CompileConfig
from ladev_lib.scenes.spec import SceneBounds
from ladev_lib.scenes.text_to_scene import (
    CompiledScene,
    SceneCompiler,
    SceneText,
    scene_text_of_row,
)
from ladev_lib.seeding import derive_seed
from ladev_lib.tables import CompiledSceneRow, SceneDesignRow, read_table, rows_of, write_table
from ladev_lib.vocabulary import Robot, TaskType, as_robot

T = TypeVar("T")


@dataclass(frozen=True)
class SceneCompilerSetup:
    """The configured compiler and what its callers report about it."""

    compiler: SceneCompiler
    llm: LLMConfig
    client: LLMClient
    robot: Robot


def scene_compiler(cfg: dict[str, Any], cache_dir: Path | None) -> SceneCompilerSetup:
    """The scene compiler the configuration describes; LLM calls cached under ``cache_dir`` (None: no cache)."""
    llm = section(cfg, "llm", LLMConfig)
    compile_cfg = section(cfg, "compile", CompileConfig)
    bounds = SceneBounds.model_validate((cfg.get("study") or {}).get("bounds") or {})
    prompt = load_prompts(cfg, ["compile_scene"])["compile_scene"]
    catalog = load_catalog(cfg.get("catalog"))
    client = make_client(llm, cache_dir)
    compiler = SceneCompiler(client, prompt, llm, catalog, bounds, compile_cfg)
    robot = as_robot(str((cfg.get("robot") or {}).get("name") or "panda"))
    return SceneCompilerSetup(compiler, llm, client, robot)


def compile_all(items: Sequence[T], one: Callable[[T], CompiledScene], concurrency: int) -> list[CompiledScene]:
    """``one`` over ``items`` on ``concurrency`` threads, in input order, with a progress bar."""
    results: list[CompiledScene] = []
    with tqdm(total=len(items), desc="compile", unit="scene", file=sys.stderr) as bar, ThreadPoolExecutor(
        max_workers=concurrency
    ) as pool:
        for result in pool.map(one, items):
            results.append(result)
            bar.update(1)
    return results


def rejection_lines(reasons: Iterable[str]) -> tuple[str, ...]:
    """The five most common rejection reasons (the part before the first colon), with counts."""
    counts = Counter(reason.split(":")[0] for reason in reasons)
    return tuple(f"  rejected x{n}: {reason}" for reason, n in counts.most_common(5))


# The stage: the generated designs -> compiled.parquet.


def compile_design(compiler: SceneCompiler, design: SceneDesignRow) -> CompiledScene:
    """One generated scene compiled; a failed generation is a rejection saying so."""
    if design.status != "ok" or not design.description:
        return CompiledScene(design.scene_id, "rejected", f"generation failed: {design.reason}")
    return compiler.compile(scene_text_of_row(design))


@dataclass(frozen=True)
class CompileSummary:
    scenes: int
    ok: int
    calls: int
    cached: int
    backend: str
    model: str
    rejections: tuple[str, ...]


@dataclass(frozen=True)
class CompileResult:
    table: Path
    results: list[CompiledScene]
    summary: CompileSummary

    def messages(self) -> StageMessages:
        s = self.summary
        head = (
            f"compile: {s.scenes} scenes ({s.ok} ok, {s.scenes - s.ok} rejected); LLM calls: {s.calls} made, "
            f"{s.cached} cached ({s.backend}:{s.model}) -> {self.table}"
        )
        return StageMessages((head, *s.rejections))


def run_compile(params: dict[str, Any]) -> CompileResult:
    """Compile every generated scene of ``paths.scenes`` and write ``paths.compiled``."""
    paths = params["paths"]
    setup = scene_compiler(params, Path(paths["llm_cache_dir"]) / "compile")
    designs = rows_of(read_table(paths["scenes"], SceneDesignRow), SceneDesignRow)
    results = compile_all(designs, lambda d: compile_design(setup.compiler, d), setup.llm.concurrency)
    write_table([r.row() for r in results], paths["compiled"], CompiledSceneRow)
    summary = CompileSummary(
        scenes=len(results),
        ok=sum(r.status == "ok" for r in results),
        calls=sum(r.calls for r in results),
        cached=sum(r.cached for r in results),
        backend=setup.llm.backend,
        model=setup.client.backend.model,
        rejections=rejection_lines((r.reason or "") for r in results if r.status == "rejected"),
    )
    return CompileResult(Path(paths["compiled"]), results, summary)


# ``ladev compile``: a user's JSONL of descriptions -> a JSONL of results.


class DescriptionLine(BaseModel):
    """One input line."""

    model_config = ConfigDict(extra="ignore")

    id: str
    description: str
    instruction: str | None = None
    task: TaskType | None = None
    seed: int | None = None
    object_set: str | None = None
    robot: Robot | None = None


def parse_line(number: int, text: str) -> DescriptionLine | str:
    """The line's fields, or why it cannot be read."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        return f"line {number}: not JSON ({exc.msg})"
    if not isinstance(data, dict):
        return f"line {number}: expected a JSON object"
    try:
        return DescriptionLine.model_validate(data)
    except ValidationError as exc:
        problems = "; ".join(f"{'.'.join(map(str, e['loc']))}: {e['msg']}" for e in exc.errors())
        return f"line {number}: {problems}"


def _line_id(number: int, text: str) -> str:
    try:
        data = json.loads(text)
        if isinstance(data, dict) and data.get("id") is not None:
            return str(data["id"])
    except json.JSONDecodeError:
        pass
    return f"line-{number}"


def compile_line(compiler: SceneCompiler, number: int, text: str, robot: Robot) -> CompiledScene:
    """One input line compiled; an unreadable line is a rejection with its reason."""
    parsed = parse_line(number, text)
    if isinstance(parsed, str):
        return CompiledScene(_line_id(number, text), "rejected", parsed)
    item = SceneText(
        scene_id=parsed.id,
        description=parsed.description,
        instruction=parsed.instruction,
        task=parsed.task,
        seed=parsed.seed if parsed.seed is not None else derive_seed(0, parsed.id),
        object_set=parsed.object_set,
        robot=parsed.robot or robot,
    )
    return compiler.compile(item)


@dataclass(frozen=True)
class CompileFileResult:
    output: Path
    results: list[dict[str, Any]]
    ok: int
    rejections: tuple[str, ...]

    def messages(self) -> StageMessages:
        n = len(self.results)
        head = f"compiled {n} descriptions: {self.ok} ok, {n - self.ok} rejected -> {self.output}"
        return StageMessages((), (head, *self.rejections))


def compile_file(setup: SceneCompilerSetup, descriptions: Path, output: Path) -> CompileFileResult:
    """Compile each non-blank line of ``descriptions`` (JSONL); write one JSON line per input to ``output``."""
    lines = [
        (n, text) for n, text in enumerate(descriptions.read_text(encoding="utf-8").splitlines(), 1)
        if text.strip()
    ]
    compiled = compile_all(
        lines, lambda entry: compile_line(setup.compiler, entry[0], entry[1], setup.robot), setup.llm.concurrency
    )
    results = [c.as_dict() for c in compiled]
    output.parent.mkdir(parents=True, exist_ok=True)
    with open(output, "w", encoding="utf-8") as f:
        for result in results:
            f.write(json.dumps(result, ensure_ascii=False) + "\n")
    ok = sum(r["status"] == "ok" for r in results)
    reasons = (str(r["reason"]) for r in results if r["status"] != "ok")
    return CompileFileResult(output, results, ok, rejection_lines(reasons))
