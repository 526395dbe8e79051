"""Reading a scene spec file for a command, with errors a user can act on."""

from __future__ import annotations

from pathlib import Path

import click

from ladev_lib.scenes.spec import SceneSpec


def read_spec_file(spec_path: Path) -> SceneSpec:
    """The validated spec in ``spec_path`` (JSON); a ClickException lists each problem."""
    from pydantic import ValidationError

    from ladev_lib.catalog import load_catalog
    from ladev_lib.scenes.spec import parse_scene_spec

    try:
        return parse_scene_spec(spec_path.read_text(encoding="utf-8"), catalog=load_catalog())
    except ValidationError as exc:
        lines = "\n".join(f"  {e['msg']}" for e in exc.errors())
        raise click.ClickException(f"{spec_path} is not a valid scene spec:\n{lines}") from exc
