"""Study summary (what each stage produced) and the headline metrics (``metrics.json``).

Metric names are flat and stable, for ``dvc metrics show`` / ``dvc exp show``:

    episodes, episodes_judged, errors, invalid_scenes, error_rate, invalid_scene_rate,
    scenes, scene_generation_ok_rate, compile_ok_rate, physical_validity_rate,
    paraphrase_candidates, paraphrase_valid_rate,
    success_rate/<policy>, success_rate/<policy>/<task>           (report.success's definition)
    success_rate_end/<policy>[/<task>], success_rate_any/<policy>[/<task>]
    success_definition (0: end, 1: any), trials_per_scene (the most any scene had),
    control/<policy>/real, control/<policy>/control, control/<policy>/diff (pooled controls),
    flipping_scenes/<policy>, repeated_scenes/<policy>

Rates are fractions in [0, 1] over judged episodes (errors and invalid scenes
excluded), ``null`` when there is nothing to divide by; success rates are of the
real instructions (controls apart). Nothing here measures time: the metrics are
the same on every machine.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import polars as pl

from ladev_lib.report.cells import count_outcomes
from ladev_lib.report.measurement import Measurement

REASON_CHARS = 200


def _rate(num: int, den: int) -> float | None:
    return None if den == 0 else num / den


@dataclass(frozen=True)
class ReasonCount:
    where: str
    reason: str
    count: int


@dataclass(frozen=True)
class StudySummary:
    scenes: int = 0
    scenes_ok: int = 0
    compiled: int = 0
    compiled_ok: int = 0
    validity_ok: int = 0
    validity_invalid: int = 0
    validity_source: str = "none"
    """Where the physical-validity verdicts come from: "rollout" (one verdict per
    scene and policy, since the robot and camera are the policy's), or "none"."""
    basic_instructions: int = 0
    paraphrase_candidates: int = 0
    paraphrases_valid: int = 0
    paraphrases_selected: int = 0
    episodes: int = 0
    by_status: dict[str, int] = field(default_factory=dict)
    reasons: list[ReasonCount] = field(default_factory=list)
    missing_inputs: list[str] = field(default_factory=list)

    @property
    def scene_generation_ok_rate(self) -> float | None:
        return _rate(self.scenes_ok, self.scenes)

    @property
    def compile_ok_rate(self) -> float | None:
        return _rate(self.compiled_ok, self.compiled)

    @property
    def physical_validity_rate(self) -> float | None:
        return _rate(self.validity_ok, self.validity_ok + self.validity_invalid)

    @property
    def paraphrase_valid_rate(self) -> float | None:
        return _rate(self.paraphrases_valid, self.paraphrase_candidates)

    @property
    def judged(self) -> int:
        return self.by_status.get("success", 0) + self.by_status.get("failure", 0)


def _top_reasons(frame: pl.DataFrame, column: str, where: str, limit: int) -> list[ReasonCount]:
    if frame.is_empty():
        return []
    counts = (
        frame.filter(pl.col(column).is_not_null())
        .with_columns(pl.col(column).str.slice(0, REASON_CHARS))
        .group_by(column).len("count").sort(["count", column], descending=[True, False]).head(limit)
    )
    return [ReasonCount(where, r[column], r["count"]) for r in counts.iter_rows(named=True)]


def summarize_study(
    episodes: pl.DataFrame,
    scenes: pl.DataFrame | None,
    compiled: pl.DataFrame | None,
    instructions: pl.DataFrame | None,
    reasons_per_stage: int = 5,
) -> StudySummary:
    """Counts and validity rates of every stage, and the most frequent reasons things failed."""
    values: dict[str, Any] = {"missing_inputs": []}
    reasons: list[ReasonCount] = []
    if scenes is None:
        values["missing_inputs"].append("scenes")
    else:
        values["scenes"] = scenes.height
        values["scenes_ok"] = scenes.filter(pl.col("status") == "ok").height
        reasons += _top_reasons(scenes, "reason", "generate", reasons_per_stage)
    if compiled is None:
        values["missing_inputs"].append("compiled scenes")
    else:
        values["compiled"] = compiled.height
        values["compiled_ok"] = compiled.filter(pl.col("status") == "ok").height
        reasons += _top_reasons(compiled, "reason", "compile", reasons_per_stage)
    if instructions is None:
        values["missing_inputs"].append("instructions")
    else:
        para = instructions.filter(pl.col("kind") == "paraphrase")
        values["basic_instructions"] = instructions.filter(pl.col("kind") == "basic").height
        values["paraphrase_candidates"] = para.height
        values["paraphrases_valid"] = para.filter(pl.col("valid")).height
        values["paraphrases_selected"] = para.filter(pl.col("selected")).height
        reasons += _top_reasons(para, "reason", "paraphrase", reasons_per_stage)
    values["episodes"] = episodes.height
    values["by_status"] = dict(episodes.group_by("status").len("count").iter_rows())
    if not episodes.is_empty():
        # The check ran at the start of each episode, with the policy's robot and camera.
        per_scene = episodes.group_by(["policy", "scene_id"]).agg(
            (pl.col("status") == "invalid_scene").any().alias("invalid")
        )
        values["validity_invalid"] = per_scene.filter(pl.col("invalid")).height
        values["validity_ok"] = per_scene.height - values["validity_invalid"]
        values["validity_source"] = "rollout"
    excluded = episodes.filter(pl.col("status").is_in(["error", "invalid_scene"]))
    reasons += _top_reasons(excluded.with_columns(pl.col("error").fill_null("(no reason given)")),
                            "error", "rollout", 2 * reasons_per_stage)
    return StudySummary(reasons=reasons, **values)


def headline_metrics(
    summary: StudySummary, episodes: pl.DataFrame, measurement: Measurement | None = None
) -> dict[str, float | int | None]:
    """The flat metrics written to ``metrics.json`` (see the module docstring)."""

    def r4(x: float | None) -> float | None:
        return None if x is None else round(x, 4)

    errors = summary.by_status.get("error", 0)
    invalid = summary.by_status.get("invalid_scene", 0)
    metrics: dict[str, float | int | None] = {
        "episodes": summary.episodes,
        "episodes_judged": summary.judged,
        "errors": errors,
        "invalid_scenes": invalid,
        "error_rate": r4(_rate(errors, summary.episodes)),
        "invalid_scene_rate": r4(_rate(invalid, summary.episodes)),
        "scenes": summary.scenes,
        "scene_generation_ok_rate": r4(summary.scene_generation_ok_rate),
        "compile_ok_rate": r4(summary.compile_ok_rate),
        "physical_validity_rate": r4(summary.physical_validity_rate),
        "paraphrase_candidates": summary.paraphrase_candidates,
        "paraphrase_valid_rate": r4(summary.paraphrase_valid_rate),
    }
    for r in count_outcomes(episodes, ["policy"]).iter_rows(named=True):
        metrics[f"success_rate/{r['policy']}"] = r4(r["success_rate"])
    for r in count_outcomes(episodes, ["policy", "task"]).iter_rows(named=True):
        metrics[f"success_rate/{r['policy']}/{r['task']}"] = r4(r["success_rate"])
    if measurement is None:
        return metrics
    metrics["success_definition"] = 0 if measurement.definition == "end" else 1
    trials = [int(t) for t in measurement.success["trials"].to_list()]
    metrics["trials_per_scene"] = max(trials, default=1)
    for r in measurement.success.iter_rows(named=True):
        suffix = r["policy"] if r["task"] == "*" else f"{r['policy']}/{r['task']}"
        for d in ("end", "any"):
            value = r[f"{d}_pct"]
            metrics[f"success_rate_{d}/{suffix}"] = None if value is None else round(value / 100.0, 4)
    for r in measurement.controls.filter(pl.col("control") == "all").iter_rows(named=True):
        for key in ("real", "control", "diff"):
            metrics[f"control/{r['policy']}/{key}"] = round(r[f"{key}_pct"] / 100.0, 4)
    for r in measurement.agreement.filter(pl.col("task") == "*").iter_rows(named=True):
        metrics[f"flipping_scenes/{r['policy']}"] = r["flipping_scenes"]
        metrics[f"repeated_scenes/{r['policy']}"] = r["scenes"]
    return metrics
