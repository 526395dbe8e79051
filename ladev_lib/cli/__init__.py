"""The ``ladev`` command line.

Subcommands are imported only when run, so ``ladev --help`` stays fast and a
command's heavy stack (SAPIEN, torch, an LLM client) loads only when needed.
Each subcommand lives in its own module here and exposes ``command``.
"""

from __future__ import annotations

import importlib
import os
import sys
from typing import Any

import click

# name -> (module, one-line help). Keep in the order users meet them.
COMMANDS: dict[str, tuple[str, str]] = {
    "doctor": ("ladev_lib.cli.doctor", "Check rendering, assets, extras and the LLM backend."),
    "render": ("ladev_lib.cli.render", "Render a scene spec to PNG (policy and overview cameras)."),
    "run": ("ladev_lib.cli.run", "Roll out one policy on one scene spec and print the predicates."),
    "scene": ("ladev_lib.cli.scene", "Turn a scene description into operations and a spec; render it."),
    "compile": ("ladev_lib.cli.compile", "Compile a JSONL file of scene descriptions into specs."),
    "paraphrase": ("ladev_lib.cli.paraphrase", "Paraphrase an instruction and validate each candidate."),
    "validate-paraphrases": ("ladev_lib.cli.validate_paraphrases", "Validate a CSV of (original, candidate) pairs."),
    "train-reader": ("ladev_lib.cli.train_reader", "Train the reader's span tagger on annotated descriptions."),
    "serve-policy": ("ladev_lib.cli.serve_policy", "Serve a policy over the openpi websocket protocol."),
    "study": ("ladev_lib.cli.study", "Run the whole pipeline for a configuration; sweep with -m (Hydra)."),
    "summary": ("ladev_lib.cli.summary", "Print a study's report location and headline numbers."),
    "config": ("ladev_lib.cli.config", "Print the configuration composed from conf/ (params.yaml)."),
}


class LazyGroup(click.Group):
    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in COMMANDS:
            return None
        module = importlib.import_module(COMMANDS[cmd_name][0])
        command: click.Command = module.command
        return command

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        rows = [(name, help_text) for name, (_, help_text) in COMMANDS.items()]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="ladev")
def cli() -> None:
    """LADEV: language-driven testing and evaluation of VLA robot policies."""


def main(argv: list[str] | None = None) -> Any:
    """The ``ladev`` entry point: a LADEV error (bad config, missing input) prints its message, not a traceback.

    ``LADEV_DEBUG=1`` shows the traceback as well.
    """
    from ladev_lib.errors import LadevError

    try:
        return cli.main(args=argv if argv is not None else sys.argv[1:], prog_name="ladev")
    except LadevError as exc:
        if os.environ.get("LADEV_DEBUG"):
            raise
        click.secho(f"error: {exc}", fg="red", err=True)
        sys.exit(2)
