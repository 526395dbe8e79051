"""``ladev validate-paraphrases PAIRS.csv -o VERDICTS.csv``: check a user's own paraphrase pairs."""

from __future__ import annotations

import csv
import json
import re
from pathlib import Path

import click

from ladev_lib.cli._language import language_setup
from ladev_lib.language.evaluation import score
from ladev_lib.language.validator import Verdict

CHUNK = 256
"""Pairs validated per batch (one progress step)."""

ADDED_COLUMNS = (
    "similarity", "canonical_similarity",
    "original_task", "original_source", "original_target",
    "parsed_task", "parsed_source", "parsed_target",
    "similar", "same_structure", "valid", "reason",
    "original_frame", "candidate_frame", "groundings",
)


def scene_entries(text: str | None) -> tuple[frozenset[str] | None, str | None]:
    """Scene objects from a cell: catalog ids or plain names, separated by ';' or ',' (or spaces
    between ids: "coke_can apple"). Returns (entries or None when empty, a problem or None)."""
    if text is None or not text.strip():
        return None, None
    parts = [p.strip() for p in re.split(r"[;,|]", text) if p.strip()]
    if len(parts) == 1 and " " in parts[0] and all("_" in w for w in parts[0].split()):
        parts = parts[0].split()  # ids separated by spaces
    bad = [p for p in parts if not re.search(r"[a-zA-Z]", p)]
    if bad:
        return None, f"unreadable scene_objects entries: {', '.join(repr(b) for b in bad)}"
    return frozenset(parts), None


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
      scene_objects  the scene's objects as catalog ids or plain names
                     ("black bowl; plate"), separated by ';' or ',' (optional:
                     phrases then ground against the scene)
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
      reason                why it is not valid (empty when valid); a row that cannot be
                            read (bad scene cell, empty text) gets a reason, never an abort
      original_frame / candidate_frame   both frames as JSON (task, object, destination, ...)
      groundings            how each phrase was grounded ("'dinner plate' -> plate (head)")

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
    cells = [scene_entries(r.get("scene_objects")) for r in rows]
    scenes = [entries for entries, _ in cells]
    verdicts: list[Verdict | None] = []
    errors: list[str | None] = []
    with click.progressbar(length=len(rows), label=f"validating {len(rows)} pairs") as bar:
        for start in range(0, len(rows), CHUNK):
            chunk = rows[start : start + CHUNK]
            batch = [((r.get("original") or ""), (r.get("candidate") or "")) for r in chunk]
            try:
                verdicts += setup.validator.validate_pairs(batch, scenes[start : start + CHUNK])
                errors += [None] * len(chunk)
            except Exception:  # one bad row must not sink the others: retry one by one
                for k, pair in enumerate(batch):
                    try:
                        verdicts += setup.validator.validate_pairs([pair], [scenes[start + k]])
                        errors.append(None)
                    except Exception as exc:  # the row gets a reason instead of a verdict
                        verdicts.append(None)
                        errors.append(f"error: {type(exc).__name__}: {exc}")
            bar.update(len(chunk))

    out_columns = columns + [c for c in ADDED_COLUMNS if c not in columns]
    output.parent.mkdir(parents=True, exist_ok=True)
    with open(output, "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=out_columns, extrasaction="ignore")
        writer.writeheader()
        for row, v, err, (_, cell_problem) in zip(rows, verdicts, errors, cells, strict=True):
            writer.writerow({**row, **_verdict_columns(v, err, cell_problem)})
    valid = [v is not None and v.valid and not p for v, (_, p) in zip(verdicts, cells, strict=True)]
    n_valid = sum(valid)
    click.echo(f"{n_valid}/{len(verdicts)} valid -> {output}")
    labels = [(r.get("label") or "").strip().lower() for r in rows]
    if labels and all(lab in ("same", "different") for lab in labels):
        s = score(valid, [lab == "same" for lab in labels])
        click.echo(f"against the labels: precision {s.precision:.3f}, recall {s.recall:.3f} "
                   f"({s.fp} false valid, {s.fn} false invalid)")


def _verdict_columns(v: Verdict | None, error: str | None, cell_problem: str | None) -> dict[str, object]:
    if v is None:
        return {"similar": False, "same_structure": False, "valid": False, "reason": error or "not validated"}
    reasons = [r for r in (cell_problem, v.reason) if r]
    return {
        "similarity": f"{v.similarity:.4f}",
        "canonical_similarity": "" if v.canonical_similarity is None else f"{v.canonical_similarity:.4f}",
        "original_task": v.expected.task or "", "original_source": v.expected.source or "",
        "original_target": v.expected.target or "",
        "parsed_task": v.parse.task or "", "parsed_source": v.parse.source or "",
        "parsed_target": v.parse.target or "",
        "similar": v.similar, "same_structure": v.same_structure,
        "valid": v.valid and cell_problem is None,
        "reason": "; ".join(reasons),
        "original_frame": json.dumps(v.expected_frame.as_dict()) if v.expected_frame else "",
        "candidate_frame": json.dumps(v.frame.as_dict()) if v.frame else "",
        "groundings": " | ".join(v.groundings),
    }
