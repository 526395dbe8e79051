"""``ladev compile DESCRIPTIONS.jsonl -o SPECS.jsonl``: compile a user's own scene descriptions.

Each input line is a JSON object with at least ``id`` and ``description``;
optional ``instruction``, ``task``, ``seed`` (default: derived from the id),
``object_set``, ``robot``. Each input line gives one output line with
``id``, ``status`` (ok | rejected), ``reason``, ``instruction``,
``operations``, ``spec``, ``notes`` and ``llm_call_ids``; a bad line is a
rejected line with its reason, never a crash.
"""

from __future__ import annotations

import json
import sys
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import click
from pydantic import BaseModel, ConfigDict, ValidationError
from tqdm import tqdm

from ladev_lib.scenes.spec import Robot, TaskType
from ladev_lib.scenes.text_to_scene import CompiledScene, SceneText
from ladev_lib.seeding import derive_seed


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


@click.command()
@click.argument("descriptions", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.argument("overrides", nargs=-1)
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), required=True,
              help="Output JSONL, one line per input line.")
@click.option("--no-cache", is_flag=True, help="Do not read or write the LLM cache.")
@click.option("--config-dir", default=None, help="Hydra config directory (default: ./conf).")
def command(
    descriptions: Path, overrides: tuple[str, ...], output: Path, no_cache: bool, config_dir: str | None
) -> None:
    """Compile DESCRIPTIONS (JSONL) into scene specs; OVERRIDES are Hydra overrides (llm=openai)."""
    from ladev_lib.cli._scene_setup import scene_tools

    tools = scene_tools(list(overrides), config_dir, cache=not no_cache)
    lines = [
        (n, text) for n, text in enumerate(descriptions.read_text(encoding="utf-8").splitlines(), 1)
        if text.strip()
    ]

    def one(entry: tuple[int, str]) -> dict[str, Any]:
        number, text = entry
        parsed = parse_line(number, text)
        if isinstance(parsed, str):
            return CompiledScene(_line_id(number, text), "rejected", parsed).as_dict()
        item = SceneText(
            scene_id=parsed.id,
            description=parsed.description,
            instruction=parsed.instruction,
            task=parsed.task,
            seed=parsed.seed if parsed.seed is not None else derive_seed(0, parsed.id),
            object_set=parsed.object_set,
            robot=parsed.robot or tools.robot,  # type: ignore[arg-type]
        )
        return tools.compiler.compile(item).as_dict()

    results: list[dict[str, Any]] = []
    with ThreadPoolExecutor(max_workers=tools.llm.concurrency) as pool, tqdm(
        total=len(lines), desc="compile", unit="scene", file=sys.stderr
    ) as bar:
        for result in pool.map(one, lines):
            results.append(result)
            bar.update(1)
    output.parent.mkdir(parents=True, exist_ok=True)
    with open(output, "w", encoding="utf-8") as f:
        for result in results:
            f.write(json.dumps(result, ensure_ascii=False) + "\n")

    ok = sum(r["status"] == "ok" for r in results)
    click.echo(f"compiled {len(results)} descriptions: {ok} ok, {len(results) - ok} rejected -> {output}", err=True)
    for reason, n in Counter(str(r["reason"]).split(":")[0] for r in results if r["status"] != "ok").most_common(5):
        click.echo(f"  rejected x{n}: {reason}", err=True)
