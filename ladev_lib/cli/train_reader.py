"""``ladev train-reader``: train the reader's span tagger on annotated scene descriptions.

    ladev train-reader                                   # the project's rows -> the packaged weights
    ladev train-reader my_rows/*.jsonl -o reader.safetensors --epochs 12

Rows are JSON lines with an ``annotated`` description or instruction in the
tagger's markup (``[[words|TAG]]``, see ``training/*/README.md``). Training
runs on the CPU (about two minutes an epoch for 9,000 rows on two cores) and
prints the span scores on the held-out share. Point the compiler at other weights with
``LADEV_READER_WEIGHTS=path``.
"""

from __future__ import annotations

import json
from pathlib import Path

import click

from ladev_lib.fingerprint import REPO_ROOT

DEFAULT_ROWS = (REPO_ROOT / "training" / "scene_tagger", REPO_ROOT / "training" / "instruction_tagger")
DEFAULT_REPEATS = {REPO_ROOT / "training" / "instruction_tagger": 2}
"""The instruction rows count twice by default: there are 1,905 of them beside 5,100 scene rows, and the
paraphrase validator's second reading needs the instruction tags (a negation, an extra step) as much as the
scene reader needs its own."""


@click.command()
@click.argument("rows", nargs=-1, type=click.Path(exists=True, path_type=Path))
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Weights file to write (default: the packaged weights).")
@click.option("--epochs", type=click.IntRange(1, 100), default=12, show_default=True)
@click.option("--batch-size", type=click.IntRange(1, 256), default=16, show_default=True)
@click.option("--lr", type=float, default=1e-3, show_default=True)
@click.option("--seed", type=int, default=0, show_default=True)
@click.option("--validation", type=click.FloatRange(0.0, 0.5), default=0.08, show_default=True,
              help="Share of rows (chosen by id) held out to score the spans.")
@click.option("--repeat", "repeats", multiple=True, metavar="PATH=N",
              help="Count the rows of PATH (a file or folder among ROWS) N times in training; default with no ROWS: "
                   "training/instruction_tagger=2.")
def command(
    rows: tuple[Path, ...], output: Path | None, epochs: int, batch_size: int, lr: float, seed: int, validation: float,
    repeats: tuple[str, ...],
) -> None:
    """Train the span tagger on ROWS (JSONL files or folders; default: training/scene_tagger and
    training/instruction_tagger)."""
    from ladev_lib.errors import ConfigError
    from ladev_lib.language.tagging.model import WEIGHTS
    from ladev_lib.language.tagging.training import load_examples, train

    times: dict[Path, int] = {} if rows else dict(DEFAULT_REPEATS)
    for item in repeats:
        where, _, n = item.rpartition("=")
        if not where or not n.isdigit() or int(n) < 1:
            raise ConfigError(f"--repeat takes PATH=N with N >= 1, got {item!r}")
        times[Path(where).resolve()] = int(n)
    paths: list[Path] = []
    for p in rows or DEFAULT_ROWS:
        found = sorted(p.glob("*.jsonl")) if p.is_dir() else [p]
        paths.extend(found * times.get(p.resolve(), 1))
    if not paths:
        raise ConfigError(f"no annotated rows found in {', '.join(str(p) for p in rows or DEFAULT_ROWS)}")
    examples, problems = load_examples(paths)
    for line in problems:
        click.echo(f"skipped {line}", err=True)
    if not examples:
        raise ConfigError("none of the rows could be read")
    report = train(
        examples, output or WEIGHTS, epochs=epochs, batch_size=batch_size, lr=lr, seed=seed,
        val_fraction=validation, log=lambda line: click.echo(line, err=True),
    )
    click.echo(json.dumps(report["validation"].get("all", {})))
