"""``ladev paraphrase "put the carrot on the plate" -k 10``: write and check paraphrases."""

from __future__ import annotations

import json

import click

from ladev_lib.cli._language import language_setup, reading, scene_objects
from ladev_lib.language.llm_jobs import ParaphraseAnswer, paraphrase_request


@click.command()
@click.argument("instruction")
@click.argument("overrides", nargs=-1)
@click.option("-k", "k", type=click.IntRange(1, 100), default=10, show_default=True, help="Paraphrases to ask for.")
@click.option("--seed", type=int, default=None, help="Sampling seed (default: llm.seed).")
@click.option("--objects", default=None, help="Catalog ids of the scene's objects, e.g. 'carrot,plate,sponge': names resolve against them first.")
@click.option("--threshold", type=float, default=None, help="Similarity threshold (default: paraphrase.similarity_threshold).")
@click.option("--cache-dir", default=None, help="Cache LLM calls here (default: no cache).")
@click.option("--config-dir", default=None, help="Hydra config directory (default: ./conf).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object per candidate instead of a table.")
def command(
    instruction: str,
    overrides: tuple[str, ...],
    k: int,
    seed: int | None,
    objects: str | None,
    threshold: float | None,
    cache_dir: str | None,
    config_dir: str | None,
    as_json: bool,
) -> None:
    """Ask the configured LLM for K paraphrases of INSTRUCTION and validate each.

    Every candidate is printed with its similarity to the instruction (as
    written; and, when that is below the threshold, with object names
    canonicalised), how it reads back as (task, source, target), and the
    verdict with its reason.
    OVERRIDES are Hydra overrides, e.g. llm=openai paraphrase.similarity_threshold=0.6.
    """
    setup = language_setup(overrides, config_dir, cache_dir, threshold)
    scene = scene_objects(objects, setup.catalog)
    request = paraphrase_request(setup.prompts["paraphrase"], setup.llm, instruction, k, seed)
    result = setup.client.complete_json(request, ParaphraseAnswer)
    if result.value is None:
        raise click.ClickException(f"the LLM gave no usable answer: {result.reason}")
    candidates = result.value.paraphrases
    verdicts = setup.validator.validate(instruction, candidates, scene)
    original = setup.validator.reader.read([instruction], [scene])[0]

    if as_json:
        for v in verdicts:
            click.echo(json.dumps({
                "candidate": v.candidate, "similarity": round(v.similarity, 4),
                "canonical_similarity": v.canonical_similarity, "parse": v.parse.as_dict(),
                "valid": v.valid, "reason": v.reason,
            }))
        return
    backend = f"{setup.client.backend.name} ({setup.client.backend.model})"
    click.echo(f"original: {instruction!r} -> {reading(*original.roles)}"
               + (f"  [not understood: {original.reason}]" if original.reason else ""))
    click.echo(f"{len(candidates)} candidates from {backend}; similarity threshold "
               f"{setup.validator.threshold:.2f}; reader: {setup.validator.reader.name}")
    if result.value.problem:
        click.echo(f"note from the paraphraser: {result.value.problem}")
    click.echo(f"{'#':>3}  {'verdict':7}  {'sim':>5}  {'canon':>5}  {'reads as':38}  candidate")
    for i, v in enumerate(verdicts, start=1):
        verdict = click.style("valid", fg="green") if v.valid else click.style("REJECT", fg="red")
        pad = " " * (7 - len("valid" if v.valid else "REJECT"))
        canon = "" if v.canonical_similarity is None else f"{v.canonical_similarity:.2f}"
        click.echo(f"{i:>3}  {verdict}{pad}  {v.similarity:5.2f}  {canon:>5}  "
                   f"{reading(*v.parse.roles):38}  {v.candidate}")
        if v.reason:
            click.echo(f"{'':>3}  {'':7}  {'':5}  {'':5}  -> {v.reason}")
    n_valid = sum(v.valid for v in verdicts)
    click.echo(f"{n_valid}/{len(verdicts)} valid")
