"""``ladev validate-paraphrases PAIRS.csv -o VERDICTS.csv``: check a user's own paraphrase pairs."""

from __future__ import annotations

import csv
from pathlib import Path

import click

from ladev_lib.cli._language import language_setup, scene_objects
from ladev_lib.language.evaluation import score

CHUNK = 256
"""Pairs validated per batch (one progress step)."""

ADDED_COLUMNS = (
    "similarity", "canonical_similarity",
    "original_task", "original_source", "original_target",
    "parsed_task", "parsed_source", "parsed_target",
    "similar", "same_structure", "valid", "reason",
)


@click.command()
@click.argument("pairs", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.argument("overrides", nargs=-1)
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), required=True, help="Verdicts CSV to write.")
@click.option("--threshold", type=float, default=None, help="Similarity threshold (default: paraphrase.similarity_threshold).")
@click.option("--reader", type=click.Choice(["auto", "offline", "llm"]), default=None, help="Who reads the sentences back (default: paraphrase.reader).")
@click.option("--cache-dir", default=None, help="Cache LLM calls here (only used by the llm reader).")
@click.option("--config-dir", default=None, help="Hydra config directory (default: ./conf).")
def command(
    pairs: Path,
    overrides: tuple[str, ...],
    output: Path,
    threshold: float | None,
    reader: str | None,
    cache_dir: str | None,
    config_dir: str | None,
) -> None:
    """Validate (original, candidate) pairs from PAIRS, e.g. a published paraphrase set.

    \b
    Input columns (header row required):
      original       the instruction as given (required)
      candidate      its paraphrase (required)
      scene_objects  catalog ids of the scene's objects, separated by ';' or
                     spaces (optional: names then resolve against the scene)
      label          same | different (optional: precision and recall are printed)
      any other      copied to the output unchanged
    \b
    Output: every input column, then
      similarity            cosine similarity of the sentences as written
      canonical_similarity  the same with object names replaced by display names, when
                            similarity is below the threshold (empty otherwise)
      original_task / original_source / original_target   how the original reads
      parsed_task / parsed_source / parsed_target          how the candidate reads
      similar               max(similarity, canonical_similarity) >= threshold
      same_structure        the candidate reads as the original's (task, source, target)
      valid                 similar and same_structure
      reason                why it is not valid (empty when valid)

    OVERRIDES are Hydra overrides, e.g. llm=openai to read with an LLM.
    """
    with open(pairs, newline="", encoding="utf-8-sig") as f:
        reader_ = csv.DictReader(f)
        columns = list(reader_.fieldnames or [])
        rows = list(reader_)
    missing = [c for c in ("original", "candidate") if c not in columns]
    if missing:
        raise click.UsageError(f"{pairs}: missing column(s) {', '.join(missing)}; found {', '.join(columns) or 'none'}")
    setup = language_setup(overrides, config_dir, cache_dir, threshold, reader)
    scenes = [scene_objects(r.get("scene_objects"), setup.catalog) for r in rows]
    verdicts = []
    with click.progressbar(length=len(rows), label=f"validating {len(rows)} pairs") as bar:
        for start in range(0, len(rows), CHUNK):
            chunk = rows[start : start + CHUNK]
            verdicts += setup.validator.validate_pairs(
                [(r["original"], r["candidate"]) for r in chunk], scenes[start : start + CHUNK]
            )
            bar.update(len(chunk))

    out_columns = columns + [c for c in ADDED_COLUMNS if c not in columns]
    output.parent.mkdir(parents=True, exist_ok=True)
    with open(output, "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=out_columns)
        writer.writeheader()
        for row, v in zip(rows, verdicts, strict=True):
            writer.writerow({
                **row,
                "similarity": f"{v.similarity:.4f}",
                "canonical_similarity": "" if v.canonical_similarity is None else f"{v.canonical_similarity:.4f}",
                "original_task": v.expected.task or "", "original_source": v.expected.source or "",
                "original_target": v.expected.target or "",
                "parsed_task": v.parse.task or "", "parsed_source": v.parse.source or "",
                "parsed_target": v.parse.target or "",
                "similar": v.similar, "same_structure": v.same_structure, "valid": v.valid,
                "reason": v.reason or "",
            })
    n_valid = sum(v.valid for v in verdicts)
    click.echo(f"{n_valid}/{len(verdicts)} valid -> {output}")
    labels = [(r.get("label") or "").strip().lower() for r in rows]
    if labels and all(lab in ("same", "different") for lab in labels):
        s = score([v.valid for v in verdicts], [lab == "same" for lab in labels])
        click.echo(f"against the labels: precision {s.precision:.3f}, recall {s.recall:.3f} "
                   f"({s.fp} false valid, {s.fn} false invalid)")
