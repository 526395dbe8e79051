"""``ladev scene "DESCRIPTION"``: the paper's single-scene flow, from words to a spec (and a picture).

    ladev scene "three objects, one of them a plastic bottle on the left; lighting a bit darker" \\
        --task pick_up --render scene.png
    ladev scene "ADD coke can to (0.1, 0.05)" -i "pick up the coke can" llm=openai

Prints how the offline reader read the text (the span tagger's marks, with the
default ``compile.reader: tagged``), the operations, the base instruction, the
objects and the spec; exits 1 with the reason when the scene is rejected.
"""

from __future__ import annotations

import importlib
import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import click

from ladev_lib.scenes.spec import SceneSpec
from ladev_lib.scenes.text_to_scene import CompiledScene, SceneText
from ladev_lib.vocabulary import OBJECT_SETS, TASKS

Renderer = Callable[[SceneSpec, Path, dict[str, Any]], list[Path]]


def find_renderer() -> Renderer | None:
    """Render with ``ladev_lib.sim.render`` (policy | overview PNG), when this install has it."""
    try:
        render = importlib.import_module("ladev_lib.sim.render")
    except ModuleNotFoundError as exc:
        if exc.name in ("ladev_lib.sim.render", "ladev_lib.sim"):
            return None
        raise
    render_spec, save_shots = getattr(render, "render_spec", None), getattr(render, "save_shots", None)
    if render_spec is None or save_shots is None:
        return None

    def renderer(spec: SceneSpec, path: Path, cfg: dict[str, Any]) -> list[Path]:
        from ladev_lib.config import section
        from ladev_lib.sim.config import SimConfig

        shots = render_spec(spec, section(cfg, "sim", SimConfig))
        saved: list[Path] = save_shots(shots, path)
        return saved

    return renderer


def _reading(description: str) -> str:
    """The description with the span tagger's marks: what the offline tagged reader took each phrase to say."""
    from ladev_lib.language.scene.tagged import plain_code
    from ladev_lib.language.tagging.markup import to_markup
    from ladev_lib.language.tagging.model import load_tagger

    text = plain_code(description)
    return to_markup(text, load_tagger().tag(text))


def _print_text(result: CompiledScene, description: str, backend: str, reading: str | None = None) -> None:
    click.echo(f"Description: {description}")
    if reading is not None:
        click.echo(f"Read as:     {reading}")
    if result.operations is not None:
        click.echo(f"\nOperations ({backend}, {'cached' if result.cached and not result.calls else 'new call'}):")
        click.echo(json.dumps(json.loads(result.operations.to_json()), indent=2))
    if result.status != "ok" or result.spec is None:
        click.echo(click.style(f"\nRejected: {result.reason}", fg="red"))
        for note in result.notes:
            click.echo(f"  note: {note}")
        return
    spec: SceneSpec = result.spec
    click.echo(f"\nInstruction: {result.instruction}")
    click.echo(f"Task: {spec.task.type} source={spec.task.source} target={spec.task.target}")
    click.echo("Objects (workspace frame, metres):")
    for o in spec.objects:
        click.echo(f"  {o.name:<28} {o.role:<10} x={o.x:+.3f} y={o.y:+.3f} yaw={o.yaw_deg:+7.1f}")
    cam = spec.camera
    click.echo(
        f"Lighting: {spec.lighting.intensity_delta:+.2f}   Camera: move {list(cam.translation_m)} m, "
        f"rotate {list(cam.rotation_deg)} deg"
    )
    for note in result.notes:
        click.echo(f"  note: {note}")
    click.echo("\nSpec:")
    click.echo(json.dumps(json.loads(spec.to_json()), indent=2))


@click.command(context_settings={"ignore_unknown_options": False})
@click.argument("description")
@click.argument("overrides", nargs=-1)
@click.option("-i", "--instruction", default=None, help="Basic instruction, e.g. 'pick up the coke can'.")
@click.option("-t", "--task", type=click.Choice(TASKS), default=None,
              help="Task type when there is no instruction (default pick_up).")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed for random objects and positions.")
@click.option("--object-set", type=click.Choice(OBJECT_SETS), default=None,
              help="Set random objects come from (default: compile.default_object_set).")
@click.option("--render", "render_path", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Render the scene to this PNG (needs ladev_lib.sim).")
@click.option("--save-spec", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Write the spec JSON here.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of text.")
@click.option("--no-cache", is_flag=True, help="Do not read or write the LLM cache.")
@click.option("--config-dir", default=None, help="Hydra config directory (default: ./conf).")
def command(
    description: str,
    overrides: tuple[str, ...],
    instruction: str | None,
    task: str | None,
    seed: int,
    object_set: str | None,
    render_path: Path | None,
    save_spec: Path | None,
    as_json: bool,
    no_cache: bool,
    config_dir: str | None,
) -> None:
    """Turn DESCRIPTION into operations and a scene spec; OVERRIDES are Hydra overrides (llm=openai)."""
    from ladev_lib.cli._scene_setup import scene_tools

    tools = scene_tools(list(overrides), config_dir, cache=not no_cache)
    item = SceneText(
        scene_id="cli",
        description=description,
        instruction=instruction,
        task=task,
        seed=seed,
        object_set=object_set,
        robot=tools.robot,
    )
    result = tools.compiler.compile(item)
    backend = f"{tools.llm.backend}:{tools.compiler.client.backend.model}"
    if as_json:
        click.echo(json.dumps(result.as_dict(), indent=2))
    else:
        tagged = tools.llm.backend == "offline" and tools.compiler.config.reader == "tagged"
        _print_text(result, description, backend, _reading(description) if tagged else None)
    if result.spec is None:
        raise SystemExit(1)
    if save_spec is not None:
        save_spec.parent.mkdir(parents=True, exist_ok=True)
        save_spec.write_text(result.spec.to_json() + "\n", encoding="utf-8")
        click.echo(f"spec written to {save_spec}", err=as_json)
    if render_path is not None:
        renderer = find_renderer()
        if renderer is None:
            fallback = render_path.with_suffix(".json")
            fallback.parent.mkdir(parents=True, exist_ok=True)
            fallback.write_text(result.spec.to_json() + "\n", encoding="utf-8")
            click.echo(
                f"cannot render: this install has no ladev_lib.sim.render; spec saved to {fallback} "
                f"(render it with `ladev render {fallback}` where the simulator is installed)",
                err=True,
            )
            raise SystemExit(2)
        for written in renderer(result.spec, render_path, tools.config):
            click.echo(f"rendered to {written} (policy camera | overview)", err=as_json)
