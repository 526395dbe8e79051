"""``ladev config``: print the configuration composed from ``conf/`` with overrides.

    ladev config                          # what params.yaml should hold
    ladev config study=paper policy=[oracle,grounded] > params.yaml
"""

from __future__ import annotations

import click
import yaml

from ladev_lib.config import compose_config

HEADER = "# Composed from conf/ by `ladev config`; `dvc exp run -S group=option` recomposes it.\n"


def render_params(overrides: list[str], config_dir: str | None = None) -> str:
    return HEADER + yaml.safe_dump(compose_config(overrides, config_dir), sort_keys=False)


@click.command()
@click.argument("overrides", nargs=-1)
@click.option("--config-dir", default=None, help="Hydra config directory (default: ./conf).")
@click.option("--check", "check_path", default=None, metavar="PARAMS",
              help="Exit 1 if this params file differs from the composition (drift check).")
def command(overrides: tuple[str, ...], config_dir: str | None, check_path: str | None) -> None:
    """Print the composed configuration (write it to params.yaml to run it with dvc repro)."""
    text = render_params(list(overrides), config_dir)
    if check_path is None:
        click.echo(text, nl=False)
        return
    with open(check_path, encoding="utf-8") as f:
        current = yaml.safe_load(f)
    if current != yaml.safe_load(text):
        raise click.ClickException(
            f"{check_path} differs from conf/ composed with {list(overrides) or 'no overrides'}; "
            f"regenerate it: ladev config {' '.join(overrides)} > {check_path}"
        )
    click.echo(f"{check_path} matches conf/")
