"""Aggregation into cells on synthetic episodes with known answers."""

from __future__ import annotations

import polars as pl
import pytest

from ladev_lib.report.cells import count_outcomes, filter_study, success_cells
from ladev_lib.report.stats import wilson_interval
from ladev_lib.report.synthetic import CellCounts, episodes_from_counts, random_episodes


def cell(cells: pl.DataFrame, policy: str, task: str, factor: str, level: str) -> dict:
    rows = cells.filter(
        (pl.col("policy") == policy) & (pl.col("task") == task) & (pl.col("factor") == factor) & (pl.col("level") == level)
    ).to_dicts()
    assert len(rows) == 1, rows
    return rows[0]


def test_counts_rates_and_wilson_bounds(known_episodes):
    cells = success_cells(known_episodes)
    c = cell(cells, "oracle", "pick_up", "num_objects", "1")
    assert (c["n_episodes"], c["successes"], c["failures"], c["n_error"], c["n_invalid_scene"]) == (10, 6, 2, 1, 1)
    # errors and invalid scenes are not failures: 6 of 8 judged, not 6 of 10
    assert c["n"] == 8
    assert c["success_rate"] == pytest.approx(0.75)
    low, high = wilson_interval(6, 8)
    assert (c["ci_low"], c["ci_high"]) == (pytest.approx(low), pytest.approx(high))
    assert (round(c["ci_low"], 4), round(c["ci_high"], 4)) == (0.4093, 0.9285)


def test_error_only_rows_count_apart_and_never_as_zero_percent():
    eps = episodes_from_counts([CellCounts("p", "put_in", "environment", "camera", errors=3, invalid=2)])
    c = cell(success_cells(eps), "p", "put_in", "environment", "camera")
    assert (c["n"], c["n_error"], c["n_invalid_scene"]) == (0, 3, 2)
    assert c["success_rate"] is None and c["ci_low"] is None and c["ci_high"] is None


def test_average_pools_the_levels_of_table_one(known_episodes):
    cells = success_cells(known_episodes)
    avg = cell(cells, "oracle", "pick_up", "num_objects", "avg")
    assert (avg["successes"], avg["n"], avg["n_error"], avg["n_invalid_scene"]) == (8, 16, 1, 1)
    assert avg["success_rate"] == pytest.approx(0.5)
    # the average exists only for the factor whose paper table has one
    assert cells.filter((pl.col("level") == "avg") & (pl.col("factor") != "num_objects")).is_empty()


def test_paired_instruction_cells(known_episodes):
    cells = success_cells(known_episodes)
    basic = cell(cells, "oracle", "pick_up", "instruction", "basic")
    para = cell(cells, "oracle", "pick_up", "instruction", "paraphrase")
    assert (basic["successes"], basic["n"]) == (11, 20)  # both + basic only
    assert (para["successes"], para["n"]) == (5, 20)  # both + paraphrase only


def test_status_not_the_success_column_decides(known_episodes):
    # a row whose success flag disagrees with its status: status wins (success is null for errors)
    broken = known_episodes.with_columns(success=pl.lit(None, dtype=pl.Boolean))
    assert success_cells(broken).equals(success_cells(known_episodes))


def test_filter_study_drops_other_studies(known_episodes):
    other = known_episodes.head(5).with_columns(study=pl.lit("old"))
    kept, dropped = filter_study(pl.concat([known_episodes, other]), "known")
    assert (kept.height, dropped) == (known_episodes.height, 5)


def test_count_outcomes_on_a_random_study_adds_up():
    eps = random_episodes(5000, policies=["a", "b", "c"], seed=7)
    per_policy = count_outcomes(eps, ["policy"])
    assert per_policy.get_column("n_episodes").sum() == eps.height
    totals = per_policy.select(pl.sum_horizontal("successes", "failures", "n_error", "n_invalid_scene"))
    assert totals.to_series().to_list() == per_policy.get_column("n_episodes").to_list()
    judged = eps.filter(pl.col("status").is_in(["success", "failure"]))
    assert per_policy.get_column("n").sum() == judged.height
