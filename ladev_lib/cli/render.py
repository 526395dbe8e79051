"""``ladev render SPEC.json -o scene.png``: the policy camera and an overview, side by side."""

from __future__ import annotations

from pathlib import Path

import click

from ladev_lib.cli._spec_file import read_spec_file
from ladev_lib.vocabulary import ROBOTS


def _parse_size(text: str | None) -> tuple[int, int] | None:
    if text is None:
        return None
    parts = text.lower().replace("x", " ").split()
    try:
        w, h = (int(parts[0]), int(parts[-1]))
    except (ValueError, IndexError):
        raise click.BadParameter(f"expected WIDTH or WIDTHxHEIGHT, got {text!r}") from None
    return (w, h)


@click.command()
@click.argument("spec_path", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=Path("scene.png"),
              show_default=True, help="PNG to write (policy | overview).")
@click.option("--robot", type=click.Choice(ROBOTS), default=None,
              help="Render with this robot instead of the spec's.")
@click.option("--size", default=None, help="Policy image size, WIDTH or WIDTHxHEIGHT (default: sim config).")
@click.option("--separate", is_flag=True, help="Write NAME_policy.png and NAME_overview.png instead.")
@click.option("--no-overlay", is_flag=True, help="Render the simulated background, not the real one.")
@click.option("--check", is_flag=True, help="Also run the physical-validity check and print it.")
@click.option("--config-dir", default=None, help="Hydra config directory (default: ./conf).")
def command(
    spec_path: Path,
    output: Path,
    robot: str | None,
    size: str | None,
    separate: bool,
    no_overlay: bool,
    check: bool,
    config_dir: str | None,
) -> None:
    """Render a scene spec (JSON) with its policy camera and an overview camera."""
    from ladev_lib.config import compose_config, section
    from ladev_lib.errors import ConfigError
    from ladev_lib.sim.config import SimConfig
    from ladev_lib.sim.render import render_spec, save_shots

    spec = read_spec_file(spec_path)
    try:
        cfg = section(compose_config([], config_dir), "sim", SimConfig)
    except ConfigError as exc:
        raise click.ClickException(str(exc)) from exc
    if no_overlay:
        cfg = cfg.model_copy(update={"overlay": False})
    try:
        shots = render_spec(spec, cfg, robot=robot, image_size=_parse_size(size), check=check)
    except ConfigError as exc:
        raise click.ClickException(str(exc)) from exc
    for path in save_shots(shots, output, separate=separate):
        click.echo(f"wrote {path}")
    built = ", ".join(f"{n} ({s})" for n, s in shots.object_sources.items())
    click.echo(f"robot {shots.robot}; background {'real overlay' if shots.overlay else 'simulated'}; objects: {built}")
    if shots.validity is not None:
        v = shots.validity
        click.echo("valid scene" if v.valid else "INVALID scene: " + v.reason)
        for name, ok in v.checks.items():
            click.echo(f"  {'ok ' if ok else 'BAD'} {name}")
