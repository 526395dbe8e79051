"""Precision and recall of "valid" on labelled (original, candidate) pairs.

Compares the paper's check (a similarity threshold alone, at its best
threshold for the data, which flatters it) with LADEV's validator
(similarity AND structural round-trip, at its configured threshold).

    pairs = load_labelled_pairs("tests/data/paraphrase_pairs.csv")
    ev = evaluate_validator(pairs, validator)
    print(render_markdown({"labelled set": ev}, validator))
"""

from __future__ import annotations

import csv
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ladev_lib.language.validator import ParaphraseValidator, Verdict


@dataclass(frozen=True)
class LabelledPair:
    original: str
    candidate: str
    same: bool
    category: str
    scene_objects: frozenset[str] | None = None
    """The scene's objects (catalog ids or plain names) when the set gives them."""
    suite: str = ""


def load_labelled_pairs(path: str | Path) -> list[LabelledPair]:
    """Rows of a CSV with columns original, candidate, label (same | different), category."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    pairs = []
    for n, row in enumerate(rows, start=2):
        label = (row.get("label") or "").strip().lower()
        if label not in ("same", "different"):
            raise ValueError(f"{path}:{n}: label must be 'same' or 'different', got {label!r}")
        cell = (row.get("scene_objects") or "").strip()
        scene = frozenset(p.strip() for p in cell.replace(",", ";").split(";") if p.strip()) or None
        pairs.append(
            LabelledPair(
                row["original"], row["candidate"], label == "same", row.get("category") or "",
                scene, row.get("suite") or "",
            )
        )
    return pairs


@dataclass(frozen=True)
class Scores:
    """Precision and recall of the positive class "valid" (= same meaning)."""

    tp: int
    fp: int
    fn: int
    tn: int
    threshold: float | None = None

    @property
    def precision(self) -> float:
        return self.tp / (self.tp + self.fp) if self.tp + self.fp else 1.0

    @property
    def recall(self) -> float:
        return self.tp / (self.tp + self.fn) if self.tp + self.fn else 1.0

    @property
    def f1(self) -> float:
        p, r = self.precision, self.recall
        return 2 * p * r / (p + r) if p + r else 0.0


def score(predicted: Sequence[bool], actual: Sequence[bool], threshold: float | None = None) -> Scores:
    tp = sum(p and a for p, a in zip(predicted, actual, strict=True))
    fp = sum(p and not a for p, a in zip(predicted, actual, strict=True))
    fn = sum(a and not p for p, a in zip(predicted, actual, strict=True))
    tn = sum(not p and not a for p, a in zip(predicted, actual, strict=True))
    return Scores(tp, fp, fn, tn, threshold)


def threshold_sweep(similarities: Sequence[float], actual: Sequence[bool]) -> list[Scores]:
    """Scores of "valid iff similarity >= t" for every distinct t in the data."""
    sims = np.asarray(similarities, dtype=float)
    return [score(list(sims >= t), actual, float(t)) for t in np.unique(sims)]


def best_f1(sweep: Sequence[Scores]) -> Scores:
    return max(sweep, key=lambda s: (round(s.f1, 12), s.precision))


def best_precision_at_recall(sweep: Sequence[Scores], min_recall: float) -> Scores:
    eligible = [s for s in sweep if s.recall >= min_recall]
    return max(eligible, key=lambda s: (s.precision, s.recall))


@dataclass
class ValidatorEvaluation:
    pairs: list[LabelledPair]
    verdicts: list[Verdict]
    similarity_best_f1: Scores
    similarity_at_recall: Scores
    canonical_best_f1: Scores
    ladev: Scores
    min_recall: float
    by_category: dict[str, tuple[int, int, int]] = field(default_factory=dict)
    """category -> (pairs, LADEV correct, best-F1 similarity threshold correct)."""

    def errors(self) -> list[tuple[LabelledPair, Verdict]]:
        return [(p, v) for p, v in zip(self.pairs, self.verdicts, strict=True) if v.valid != p.same]


def evaluate_validator(
    pairs: Sequence[LabelledPair], validator: ParaphraseValidator, min_recall: float = 0.90
) -> ValidatorEvaluation:
    verdicts = validator.validate_pairs(
        [(p.original, p.candidate) for p in pairs], [p.scene_objects for p in pairs]
    )
    actual = [p.same for p in pairs]
    raw = [v.similarity for v in verdicts]
    sweep = threshold_sweep(raw, actual)
    sim_f1 = best_f1(sweep)
    sim_at_recall = best_precision_at_recall(sweep, min_recall)
    canonical = validator.canonical_similarities([(p.original, p.candidate) for p in pairs])
    canonical_f1 = best_f1(threshold_sweep(canonical.tolist(), actual))
    ladev = score([v.valid for v in verdicts], actual, validator.threshold)
    by_category: dict[str, tuple[int, int, int]] = {}
    assert sim_f1.threshold is not None
    for p, v in zip(pairs, verdicts, strict=True):
        n, ok_ladev, ok_sim = by_category.get(p.category, (0, 0, 0))
        by_category[p.category] = (
            n + 1,
            ok_ladev + (v.valid == p.same),
            ok_sim + ((v.similarity >= sim_f1.threshold) == p.same),
        )
    return ValidatorEvaluation(
        list(pairs), verdicts, sim_f1, sim_at_recall, canonical_f1, ladev, min_recall, by_category
    )


def render_markdown(
    evaluations: dict[str, ValidatorEvaluation],
    validator: ParaphraseValidator,
    model: str,
    notes: Sequence[str] = (),
) -> str:
    lines = [
        "# Paraphrase validator: precision and recall of \"valid\"",
        "",
        f"Embedding model: `{model}`; LADEV threshold {validator.threshold:.2f} on the better of the "
        f"similarity as written and with canonical object names; structure reader: {validator.reader.name}.",
        "Positive class: *valid* (the candidate keeps the original's meaning). Similarity-only rows "
        "use the threshold that is best **for that very set** (an optimistic baseline); "
        "the similarity is cosine similarity of the sentences as written, as in the paper.",
        "",
        *(f"- {note}" for note in notes),
        *([""] if notes else []),
    ]
    for name, ev in evaluations.items():
        n_same = sum(p.same for p in ev.pairs)
        lines += [
            f"## {name} ({len(ev.pairs)} pairs: {n_same} same, {len(ev.pairs) - n_same} different)",
            "",
            "| check | threshold | precision | recall | F1 | false valid | false invalid |",
            "|---|---|---|---|---|---|---|",
            _row("(a) similarity alone, best F1", ev.similarity_best_f1),
            _row(f"(a) similarity alone, best precision at recall >= {ev.min_recall:.2f}", ev.similarity_at_recall),
            _row("similarity with canonical names alone, best F1", ev.canonical_best_f1),
            _row("(b) LADEV: similarity AND structural round-trip", ev.ladev),
            "",
            "| category | pairs | LADEV correct | similarity (best-F1 threshold) correct |",
            "|---|---|---|---|",
        ]
        for cat, (n, ok_ladev, ok_sim) in sorted(ev.by_category.items()):
            lines.append(f"| {cat} | {n} | {ok_ladev} | {ok_sim} |")
        errors = ev.errors()
        lines += ["", f"LADEV errors ({len(errors)}):", ""]
        for p, v in errors[:40]:
            verdict = "valid" if v.valid else f"invalid ({v.reason})"
            lines.append(f"- [{p.category}] \"{p.original}\" -> \"{p.candidate}\": {verdict}")
        if not errors:
            lines.append("- none")
        lines.append("")
    return "\n".join(lines)


def _row(label: str, s: Scores) -> str:
    thr = f"{s.threshold:.3f}" if s.threshold is not None else "-"
    return f"| {label} | {thr} | {s.precision:.3f} | {s.recall:.3f} | {s.f1:.3f} | {s.fp} | {s.fn} |"
