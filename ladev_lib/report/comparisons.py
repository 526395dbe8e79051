"""Comparisons between levels of a factor, per policy and task.

- ``instruction``: the design pairs them (each scene is run with its basic and
  its paraphrased instruction), so McNemar's exact test on the discordant
  pairs, and the paired difference with Newcombe's interval.
- ``object_set`` and ``environment``: independent scene sets, so Fisher's
  exact test and Newcombe's interval for each level against the first
  (``ycb`` vs ``simpler``; ``lighting``, ``camera`` vs ``default``), plus a
  chi-squared test of homogeneity where there are more than two levels.
- ``num_objects``: ordered levels, so the Cochran–Armitage trend test.

Differences are ``level - baseline`` in percentage points: negative means the
level is harder. p-values are per comparison, not adjusted for multiplicity.
Every comparison states its minimum detectable difference (``mdd_pct``: the
smallest difference it would detect with 80 % power at the 5 % level, paired
for the instruction factor, two independent proportions otherwise, first vs
last level for the trend), so "no difference" can be told from "too few scenes".
With several trials, pairs are formed per (scene, trial).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import polars as pl

from ladev_lib.report.cells import AVERAGE_LEVEL, JUDGED
from ladev_lib.report.stats import (
    chi2_homogeneity,
    cochran_armitage,
    fisher_exact,
    mcnemar_exact,
    mdd_paired,
    mdd_two_proportions,
    newcombe_paired,
    newcombe_unpaired,
)

# factor -> (baseline level, compared levels), for level-vs-baseline comparisons.
UNPAIRED = {"object_set": ("simpler", ("ycb",)), "environment": ("default", ("lighting", "camera"))}
PAIRED = {"instruction": ("basic", "paraphrase")}
TREND = ("num_objects",)
HOMOGENEITY = ("environment",)

COMPARISON_SCHEMA: dict[str, Any] = {
    "policy": pl.String,
    "task": pl.String,
    "factor": pl.String,
    "comparison": pl.String,
    "test": pl.String,
    "baseline": pl.String,
    "level": pl.String,
    "n_baseline": pl.Int64,
    "n_level": pl.Int64,
    "baseline_pct": pl.Float64,
    "level_pct": pl.Float64,
    "diff_pct": pl.Float64,
    "diff_low_pct": pl.Float64,
    "diff_high_pct": pl.Float64,
    "statistic": pl.Float64,
    "p_value": pl.Float64,
    "baseline_only": pl.Int64,
    "level_only": pl.Int64,
    "note": pl.String,
    "mdd_pct": pl.Float64,
}


@dataclass(frozen=True)
class Power:
    """The minimum detectable difference's settings."""

    alpha: float = 0.05
    power: float = 0.8


def _pct(x: float | None) -> float | None:
    return None if x is None else 100.0 * x


def paired_counts(episodes: pl.DataFrame, factor: str, baseline: str, level: str) -> pl.DataFrame:
    """Per policy and task: pairs (same scene) by outcome under ``baseline`` and ``level``.

    Only scenes judged under both levels pair up, trial by trial; ``unpaired`` counts the
    judged episodes left without a partner (the other one errored or is missing).
    If a scene has several episodes at one level and trial, the first by instruction id is used.
    """
    judged = episodes.filter(
        (pl.col("factor") == factor) & pl.col("status").is_in(list(JUDGED))
    ).with_columns(ok=pl.col("status") == "success")
    keys = ["policy", "task", "scene_id", "trial"]

    def side(lv: str, name: str) -> pl.DataFrame:
        return (
            judged.filter(pl.col("level") == lv)
            .sort("instruction_id")
            .unique(subset=keys, keep="first", maintain_order=True)
            .select([*keys, pl.col("ok").alias(name)])
        )

    base, other = side(baseline, "base_ok"), side(level, "level_ok")
    pairs = base.join(other, on=keys, how="inner")
    counts = pairs.group_by(["policy", "task"]).agg(
        both=(pl.col("base_ok") & pl.col("level_ok")).sum().cast(pl.Int64),
        baseline_only=(pl.col("base_ok") & ~pl.col("level_ok")).sum().cast(pl.Int64),
        level_only=(~pl.col("base_ok") & pl.col("level_ok")).sum().cast(pl.Int64),
        neither=(~pl.col("base_ok") & ~pl.col("level_ok")).sum().cast(pl.Int64),
    )
    judged_per_cell = (
        judged.filter(pl.col("level").is_in([baseline, level])).group_by(["policy", "task"]).len("judged")
    )
    return (
        counts.join(judged_per_cell, on=["policy", "task"], how="full", coalesce=True)
        .with_columns(pl.col(c).fill_null(0) for c in ("both", "baseline_only", "level_only", "neither"))
        .with_columns(
            unpaired=pl.col("judged").cast(pl.Int64)
            - 2 * (pl.col("both") + pl.col("baseline_only") + pl.col("level_only") + pl.col("neither"))
        )
        .sort(["policy", "task"])
    )


def _mdd_pct(value: float | None) -> float | None:
    return None if value is None else 100.0 * value


def _paired_rows(episodes: pl.DataFrame, confidence: float, power: Power) -> list[dict[str, Any]]:
    rows = []
    for factor, (baseline, level) in PAIRED.items():
        for r in paired_counts(episodes, factor, baseline, level).iter_rows(named=True):
            a, b, c, d = r["both"], r["baseline_only"], r["level_only"], r["neither"]
            n_pairs = a + b + c + d
            if n_pairs == 0:
                continue
            diff = newcombe_paired(a, c, b, d, confidence)  # level - baseline
            assert diff is not None
            note = (
                f"{r['unpaired']} judged episode(s) without a judged partner left out" if r["unpaired"] else None
            )
            rows.append(
                dict(
                    policy=r["policy"], task=r["task"], factor=factor,
                    comparison=f"{level} - {baseline} (paired by scene)", test="McNemar exact",
                    baseline=baseline, level=level, n_baseline=n_pairs, n_level=n_pairs,
                    baseline_pct=100.0 * (a + b) / n_pairs, level_pct=100.0 * (a + c) / n_pairs,
                    diff_pct=_pct(diff.estimate), diff_low_pct=_pct(diff.low), diff_high_pct=_pct(diff.high),
                    p_value=mcnemar_exact(b, c),
                    baseline_only=b, level_only=c, note=note,
                    mdd_pct=_mdd_pct(mdd_paired(n_pairs, (b + c) / n_pairs, power.alpha, power.power)),
                )
            )
    return rows


def _level_counts(cells: pl.DataFrame, factor: str) -> dict[tuple[str, str], dict[str, tuple[int, int]]]:
    """(policy, task) -> level -> (successes, judged n), for levels with judged episodes."""
    out: dict[tuple[str, str], dict[str, tuple[int, int]]] = {}
    sub = cells.filter((pl.col("factor") == factor) & (pl.col("level") != AVERAGE_LEVEL) & (pl.col("n") > 0))
    for r in sub.select("policy", "task", "level", "successes", "n").iter_rows(named=True):
        out.setdefault((r["policy"], r["task"]), {})[r["level"]] = (r["successes"], r["n"])
    return out


def _unpaired_rows(cells: pl.DataFrame, confidence: float, power: Power) -> list[dict[str, Any]]:
    rows = []
    for factor, (baseline, levels) in UNPAIRED.items():
        for (policy, task), by_level in sorted(_level_counts(cells, factor).items()):
            if baseline not in by_level:
                continue
            k0, n0 = by_level[baseline]
            for level in levels:
                if level not in by_level:
                    continue
                k1, n1 = by_level[level]
                diff = newcombe_unpaired(k1, n1, k0, n0, confidence)
                assert diff is not None
                rows.append(
                    dict(
                        policy=policy, task=task, factor=factor,
                        comparison=f"{level} - {baseline}", test="Fisher exact",
                        baseline=baseline, level=level, n_baseline=n0, n_level=n1,
                        baseline_pct=100.0 * k0 / n0, level_pct=100.0 * k1 / n1,
                        diff_pct=_pct(diff.estimate), diff_low_pct=_pct(diff.low),
                        diff_high_pct=_pct(diff.high), p_value=fisher_exact(k1, n1, k0, n0),
                        mdd_pct=_mdd_pct(mdd_two_proportions(k0 / n0, n0, n1, power.alpha, power.power)),
                    )
                )
    return rows


def _trend_rows(cells: pl.DataFrame, power: Power) -> list[dict[str, Any]]:
    rows = []
    for factor in TREND:
        for (policy, task), by_level in sorted(_level_counts(cells, factor).items()):
            levels = sorted(by_level, key=float)
            if len(levels) < 2:
                continue
            ks = [by_level[lv][0] for lv in levels]
            ns = [by_level[lv][1] for lv in levels]
            test = cochran_armitage(ks, ns, [float(lv) for lv in levels])
            first, last = levels[0], levels[-1]
            rows.append(
                dict(
                    policy=policy, task=task, factor=factor,
                    comparison=f"linear trend over levels {first}..{last} (diff: pp per level)",
                    test="Cochran-Armitage trend", baseline=first, level=last,
                    n_baseline=by_level[first][1], n_level=by_level[last][1],
                    baseline_pct=100.0 * by_level[first][0] / by_level[first][1],
                    level_pct=100.0 * by_level[last][0] / by_level[last][1],
                    diff_pct=None if test is None else 100.0 * test.slope,
                    statistic=None if test is None else test.z,
                    p_value=None if test is None else test.p_value,
                    note="undefined: every judged episode had the same outcome" if test is None else None,
                    mdd_pct=_mdd_pct(mdd_two_proportions(
                        by_level[first][0] / by_level[first][1], by_level[first][1], by_level[last][1],
                        power.alpha, power.power,
                    )),
                )
            )
    return rows


def _homogeneity_rows(cells: pl.DataFrame) -> list[dict[str, Any]]:
    rows = []
    for factor in HOMOGENEITY:
        for (policy, task), by_level in sorted(_level_counts(cells, factor).items()):
            if len(by_level) < 3:
                continue  # two levels: the pairwise comparison says it all
            baseline, others = UNPAIRED.get(factor, ("", ()))
            canonical = [baseline, *others]
            levels = sorted(by_level, key=lambda lv: (canonical.index(lv) if lv in canonical else len(canonical), lv))
            test = chi2_homogeneity([by_level[lv][0] for lv in levels], [by_level[lv][1] for lv in levels])
            note = None
            if test is None:
                note = "undefined: every judged episode had the same outcome"
            elif test.min_expected < 5:
                note = f"approximate: smallest expected count {test.min_expected:.1f} < 5"
            rows.append(
                dict(
                    policy=policy, task=task, factor=factor,
                    comparison=f"any difference among {', '.join(levels)}",
                    test=f"chi-squared homogeneity (df={len(levels) - 1})",
                    statistic=None if test is None else test.chi2,
                    p_value=None if test is None else test.p_value, note=note,
                )
            )
    return rows


def compare_levels(
    episodes: pl.DataFrame,
    cells: pl.DataFrame,
    confidence: float = 0.95,
    policies: Sequence[str] = (),
    tasks: Sequence[str] = (),
    power: Power | None = None,
) -> pl.DataFrame:
    """Every comparison the design supports, one row each (see the module docstring).

    Rows are ordered by factor, then by ``policies`` and ``tasks`` (others after, by name).
    """
    power = power or Power()
    rows = (
        _paired_rows(episodes, confidence, power)
        + _unpaired_rows(cells, confidence, power)
        + _trend_rows(cells, power)
        + _homogeneity_rows(cells)
    )
    columns = {k: [r.get(k) for r in rows] for k in COMPARISON_SCHEMA}
    frame = pl.DataFrame(columns, schema=COMPARISON_SCHEMA)
    factor_order = {f: i for i, f in enumerate(["num_objects", "instruction", "object_set", "environment"])}

    def rank(column: str, order: dict[str, int]) -> pl.Expr:
        return pl.col(column).replace_strict(order, default=len(order), return_dtype=pl.Int64)

    return frame.sort(
        [
            rank("factor", factor_order),
            rank("policy", {p: i for i, p in enumerate(policies)}),
            "policy",
            rank("task", {t: i for i, t in enumerate(tasks)}),
            "task",
        ],
        maintain_order=True,
    )
