"""``ladev compile DESCRIPTIONS.jsonl -o SPECS.jsonl``: compile a user's own scene descriptions.

Each input line is a JSON object with at least ``id`` and ``description``;
optional ``instruction``, ``task``, ``seed`` (default: derived from the id),
``object_set``, ``robot``. Each input line gives one output line with
``id``, ``status`` (ok | rejected), ``reason``, ``instruction``,
``operations``, ``spec``, ``notes`` and ``llm_call_ids``; a bad line is a
rejected line with its reason, never a crash.
"""

from __future__ import annotations

from pathlib import Path

import click


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
    from ladev_lib.pipeline.compile import compile_file

    tools = scene_tools(list(overrides), config_dir, cache=not no_cache)
    result = compile_file(tools.setup, descriptions, output)
    click.echo("\n".join(result.messages().err), err=True)
