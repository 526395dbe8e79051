"""The tagged reader's two parts scored apart: the assembly on hand-written tags, and the tagger.

    PYTHONPATH=$PWD .venv/bin/python benchmarks/eval_reader_parts.py [--rows 'training/scene_tagger/rows_*.jsonl']
        [--tagger] [--errors N] [--json out.json]

Rows are annotated training rows (``annotated`` markup plus the ``expected``
scene). For each row the description (the markup removed) is compiled with
the configured compiler, the tagger replaced by the row's own markup: what
the value rules and the assembly make of correct tags. Where that is not the
expected scene, the assembly (or the row's markup) is at fault, never the
tagger. With ``--tagger``, the rows of the tagger's validation share (held
out of its training by a hash of their ids) are also compiled with the real
tagger, so the two columns side by side tell the tagger's share of the errors.
"""

from __future__ import annotations

import argparse
import glob
import json
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ladev_lib.language.tagging import model as tagging_model  # noqa: E402
from ladev_lib.language.tagging.markup import Span, parse_markup  # noqa: E402
from ladev_lib.language.tagging.training import is_validation  # noqa: E402
from ladev_lib.scenes.description_eval import (  # noqa: E402
    FIELDS,
    evaluate_descriptions,
    offline_compile_fn,
)


class _GoldTagger:
    """Answers with a row's own markup for the rows' texts, and with the real tagger for any other text."""

    def __init__(self, gold: dict[str, list[Span]]) -> None:
        self.gold = gold

    def tag(self, text: str) -> list[Span]:
        if text in self.gold:
            return list(self.gold[text])
        return _REAL(None).tag(text)


_REAL = tagging_model.load_tagger


def _rows(pattern: str) -> list[dict[str, Any]]:
    out = []
    for path in sorted(glob.glob(pattern)):
        for line in Path(path).read_text(encoding="utf-8").splitlines():
            if not line.strip():
                continue
            row = json.loads(line)
            if not isinstance(row.get("expected"), dict) or "annotated" not in row:
                continue
            text, spans = parse_markup(row["annotated"])
            out.append({"id": row["id"], "style": Path(path).stem, "description": text, "annotated": row["annotated"],
                        "expected": row["expected"], "_spans": spans})
    return out


def _score(rows: list[dict[str, Any]], root: Path, gold: bool) -> Any:
    from ladev_lib.language.scene import tagged

    plain = tagged.plain_code
    # the rows' tags are on their own words: the text is not rewritten before it is read with them
    tagged.plain_code = (lambda text: text) if gold else plain  # type: ignore[assignment]
    try:
        return _score_with(rows, root, gold)
    finally:
        tagged.plain_code = plain  # type: ignore[assignment]


def _score_with(rows: list[dict[str, Any]], root: Path, gold: bool) -> Any:
    if gold:
        table = {r["description"]: r["_spans"] for r in rows}
        tagging_model.load_tagger = lambda weights=None: _GoldTagger(table)  # type: ignore[assignment]
    else:
        tagging_model.load_tagger = _REAL  # type: ignore[assignment]
    try:
        compile_fn, catalog, resolver = offline_compile_fn(root / "conf", ["compile.reader=tagged"])
        return evaluate_descriptions(rows, compile_fn, catalog, resolver)
    finally:
        tagging_model.load_tagger = _REAL  # type: ignore[assignment]


def main() -> int:
    root = Path(__file__).resolve().parents[1]
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", default=str(root / "training" / "scene_tagger" / "rows_*.jsonl"))
    parser.add_argument("--tagger", action="store_true", help="also the real tagger on the validation share")
    parser.add_argument("--validation", type=float, default=0.08,
                        help="the validation share the weights were trained with (ladev train-reader's default)")
    parser.add_argument("--errors", type=int, default=0, help="print this many rows the assembly gets wrong")
    parser.add_argument("--field", action="append", default=[],
                        help="with --errors: only rows wrong in this field (repeatable)")
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()
    rows = _rows(args.rows)
    if not rows:
        print(f"no annotated rows with an expected scene at {args.rows}", file=sys.stderr)
        return 2
    start = time.perf_counter()
    on_gold = _score(rows, root, gold=True)
    print(f"eval_reader_parts: {len(rows)} annotated rows ({args.rows}), {time.perf_counter() - start:.0f} s")
    print(f"assembly on the rows' own tags: scene-exact {on_gold.scene_exact:.3f}")
    print("  " + ", ".join(f"{f} {on_gold.per_field[f]:.3f}" for f in FIELDS))
    wrong = Counter(f for r in on_gold.rows if not r.exact for f in r.errors)
    print("  rows wrong per field: " + ", ".join(f"{f} {n}" for f, n in wrong.most_common()))
    summary: dict[str, Any] = {"rows": len(rows), "gold": on_gold.summary()}
    if args.tagger:
        val = [r for r in rows if is_validation(r["id"], args.validation)]
        by_id = {r.id: r for r in on_gold.rows}
        tagged = _score(val, root, gold=False)
        gold_exact = sum(by_id[r["id"]].exact for r in val) / len(val)
        print(f"validation share ({len(val)} rows): assembly on own tags {gold_exact:.3f}, "
              f"on the tagger's tags {tagged.scene_exact:.3f}")
        summary["validation"] = {"rows": len(val), "gold_exact": gold_exact, "tagged": tagged.summary()}
    if args.errors:
        by_id = {r["id"]: r for r in rows}
        shown = [r for r in on_gold.rows if not r.exact and (not args.field or set(args.field) & set(r.errors))]
        for r in shown[: args.errors]:
            print(f"\n{r.id} {by_id[r.id]['annotated']}")
            print(f"   expected: {json.dumps(by_id[r.id]['expected'])}")
            for f, why in r.errors.items():
                print(f"   {f}: {why}")
    if args.json is not None:
        summary["errors"] = {r.id: r.errors for r in on_gold.rows if not r.exact}
        args.json.write_text(json.dumps(summary, indent=1), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
