"""Precision / recall of "valid" on the labelled paraphrase pairs: similarity alone vs LADEV.

    PYTHONPATH=. python benchmarks/eval_paraphrase_validator.py [--threshold 0.45] [-o reports/paraphrase_validator.md]

Prints the table and writes it as Markdown. The labelled sets are
tests/data/paraphrase_pairs.csv (written before the parser) and
tests/data/paraphrase_pairs_holdout.csv (written after its first version).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

os.environ.setdefault("HF_HUB_OFFLINE", "1")

from ladev_lib.language.embeddings import load_embedder  # noqa: E402
from ladev_lib.language.evaluation import (  # noqa: E402
    evaluate_validator,
    load_labelled_pairs,
    render_markdown,
)
from ladev_lib.language.validator import (  # noqa: E402
    DEFAULT_THRESHOLD,
    ParaphraseValidator,
    resolve_precision,
)

ROOT = Path(__file__).resolve().parents[1]
NOTES = (
    "`paraphrase_pairs.csv` was written by hand before the parser and the offline paraphraser "
    "existed (commit 0288cee). The parser's grammar was then developed with these sentences in "
    "view, so LADEV's score on it is a development score, not a held-out one.",
    "`paraphrase_pairs_holdout.csv` (134 pairs, other objects and phrasings) was written after the "
    "parser's first version, and scored once before any change: 0 false valid, 1 false invalid "
    "of 59 (\"please lift up the peach carefully so it doesn't fall\", a negation that negates no "
    "task). The one general fix that followed (a negated clause without a task verb is a manner "
    "constraint) is in the figures below.",
    "Both sets were written by the author of the parser; sentences from a real LLM or other "
    "people will be harder. `ladev validate-paraphrases` scores any labelled CSV.",
)

SETS = {
    "labelled set (tests/data/paraphrase_pairs.csv)": ROOT / "tests/data/paraphrase_pairs.csv",
    "held-out set (tests/data/paraphrase_pairs_holdout.csv)": ROOT / "tests/data/paraphrase_pairs_holdout.csv",
}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--threshold", type=float, default=DEFAULT_THRESHOLD)
    ap.add_argument("--model", default="all-MiniLM-L6-v2")
    ap.add_argument("--precision", choices=["auto", "fp32", "bf16"], default="auto")
    ap.add_argument("-o", "--output", default=str(ROOT / "reports/paraphrase_validator.md"))
    args = ap.parse_args()
    precision = resolve_precision(args.precision)
    validator = ParaphraseValidator(load_embedder(args.model), threshold=args.threshold, precision=precision)
    evaluations = {name: evaluate_validator(load_labelled_pairs(path), validator) for name, path in SETS.items()}
    text = render_markdown(evaluations, validator, f"{args.model} ({precision})", NOTES)
    print(text)
    out = Path(args.output)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text, encoding="utf-8")
    print(f"written: {out}")


if __name__ == "__main__":
    main()
