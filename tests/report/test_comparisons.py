"""Comparisons between levels: paired McNemar, unpaired Fisher, trend, homogeneity."""

from __future__ import annotations

import polars as pl
import pytest

from ladev_lib.report.cells import success_cells
from ladev_lib.report.comparisons import compare_levels, paired_counts
from ladev_lib.report.stats import fisher_exact, mcnemar_exact, newcombe_paired
from ladev_lib.report.synthetic import CellCounts, PairedCounts, episodes_from_counts


def only(frame: pl.DataFrame, **eq: str) -> dict:
    for k, v in eq.items():
        frame = frame.filter(pl.col(k) == v)
    assert frame.height == 1, frame
    return frame.to_dicts()[0]


def test_paired_counts_recover_the_design(known_episodes):
    counts = only(paired_counts(known_episodes, "instruction", "basic", "paraphrase"), policy="oracle")
    assert (counts["both"], counts["baseline_only"], counts["level_only"], counts["neither"]) == (3, 8, 2, 7)
    assert counts["unpaired"] == 0


def test_mcnemar_row_for_the_paired_instruction_factor(known_episodes):
    comps = compare_levels(known_episodes, success_cells(known_episodes))
    row = only(comps, factor="instruction")
    assert row["test"] == "McNemar exact"
    assert (row["baseline_only"], row["level_only"], row["n_baseline"]) == (8, 2, 20)
    assert row["p_value"] == pytest.approx(112 / 1024)  # hand-worked: b=8, c=2
    assert row["baseline_pct"] == pytest.approx(55.0) and row["level_pct"] == pytest.approx(25.0)
    expected = newcombe_paired(3, 2, 8, 7)  # paraphrase - basic
    assert row["diff_pct"] == pytest.approx(-30.0)
    assert row["diff_low_pct"] == pytest.approx(100 * expected.low)
    assert row["diff_high_pct"] == pytest.approx(100 * expected.high)


def test_an_errored_partner_removes_the_pair_and_says_so():
    eps = episodes_from_counts(paired=[PairedCounts("p", "pick_up", both=2, basic_only=3, neither=1)])
    # the first paraphrase episode crashes: its scene no longer pairs
    first_para = eps.filter(pl.col("level") == "paraphrase").get_column("episode_id")[0]
    eps = eps.with_columns(
        status=pl.when(pl.col("episode_id") == first_para).then(pl.lit("error")).otherwise("status")
    )
    row = only(compare_levels(eps, success_cells(eps)), factor="instruction")
    assert row["n_baseline"] == 5
    assert "1 judged episode(s) without a judged partner" in row["note"]


def test_unpaired_object_set_comparison(known_episodes):
    row = only(compare_levels(known_episodes, success_cells(known_episodes)), factor="object_set")
    assert row["comparison"].startswith("ycb - simpler")
    assert row["diff_pct"] == pytest.approx(-60.0)
    assert row["p_value"] == pytest.approx(fisher_exact(1, 10, 7, 10))
    assert row["diff_low_pct"] < -60.0 < row["diff_high_pct"] < 0


def test_trend_and_homogeneity_rows():
    cells = [
        CellCounts("p", "pick_up", "num_objects", lv, successes=s, failures=10 - s)
        for lv, s in [("1", 9), ("2", 7), ("3", 5), ("4", 3), ("5", 1)]
    ] + [
        CellCounts("p", "pick_up", "environment", lv, successes=s, failures=20 - s)
        for lv, s in [("default", 15), ("lighting", 5), ("camera", 14)]
    ]
    eps = episodes_from_counts(cells)
    comps = compare_levels(eps, success_cells(eps))
    trend = only(comps, factor="num_objects")
    assert trend["statistic"] < 0 and trend["p_value"] < 0.001
    assert trend["diff_pct"] == pytest.approx(-20.0)  # 20 points fewer per extra object, exactly linear
    env = comps.filter(pl.col("factor") == "environment")
    assert set(env.get_column("test")) == {"Fisher exact", "chi-squared homogeneity (df=2)"}
    assert only(env, test="chi-squared homogeneity (df=2)")["comparison"] == "any difference among default, lighting, camera"
    lighting = only(env, level="lighting")
    assert lighting["diff_pct"] == pytest.approx(-50.0)


def test_no_comparison_without_data_on_both_sides():
    eps = episodes_from_counts([CellCounts("p", "pick_up", "object_set", "simpler", successes=3, failures=1)])
    assert compare_levels(eps, success_cells(eps)).is_empty()


def test_mcnemar_function_agrees_with_the_row(known_episodes):
    row = only(compare_levels(known_episodes, success_cells(known_episodes)), factor="instruction")
    assert row["p_value"] == mcnemar_exact(8, 2)
