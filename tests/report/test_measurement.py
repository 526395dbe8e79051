"""Measurement tables on small episode tables whose answers are known by construction:
success at the end vs at any step, cluster-bootstrap intervals against a plain
reference computation, flips across trials, the control arm's paired difference,
and the minimum detectable difference against hand-worked sample-size formulas."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import polars as pl
import pytest

from ladev_lib.report import ReportConfig, StudyInputs, aggregate
from ladev_lib.report.measurement import (
    BootstrapOptions,
    control_comparison,
    measure,
    measurement_markdown,
    success_definitions,
    trial_agreement,
    with_success_definition,
)
from ladev_lib.report.stats import (
    cluster_bootstrap_rate,
    mdd_paired,
    mdd_two_proportions,
    newcombe_paired,
    wilson_interval,
)
from ladev_lib.tables import EpisodeRow, polars_schema

Z_975, Z_80 = 1.959963984540054, 0.8416212335729143


def episode(scene: str, *, end: bool | None, any_: bool | None = None, status: str | None = None,
            kind: str = "basic", control: str | None = None, trial: int = 0, policy: str = "p",
            task: str = "pick_up", factor: str = "num_objects", level: str = "1") -> dict[str, Any]:
    any_ = end if any_ is None else any_
    status = status or ("success" if end else "failure")
    judged = status in ("success", "failure")
    suffix = f"control-{control}" if control else kind
    return dict(
        episode_id=f"{policy}:{scene}:{suffix}:{trial}", study="s", scene_id=scene,
        instruction_id=f"{scene}/{suffix}", policy=policy, task=task, factor=factor, level=level,
        num_objects=1, object_set="simpler", environment="default", instruction_kind=kind,
        instruction="pick up the apple", robot="panda", seed=trial, status=status,
        success=end if judged else None, predicates_json="{}", steps=10, error=None,
        video_path=None, first_frame_path=None, last_frame_path=None, trial=trial, control=control,
        success_end=end if judged else None, success_any=any_ if judged else None,
        first_success_step=(3 if any_ else None) if judged else None,
    )


def frame(rows: list[dict[str, Any]]) -> pl.DataFrame:
    return pl.DataFrame(rows, schema=polars_schema(EpisodeRow))


OPTS = BootstrapOptions(confidence=0.95, samples=4000, seed=7)


# -- success at the end vs at any step ------------------------------------------------

def test_end_and_any_rates_and_the_definition_switch():
    # 10 judged episodes: 4 succeed at the end, 3 more only on the way (7 at any step),
    # plus an error that neither definition counts.
    rows = [episode(f"s{i}", end=True) for i in range(4)]
    rows += [episode(f"s{i}", end=False, any_=True) for i in range(4, 7)]
    rows += [episode(f"s{i}", end=False) for i in range(7, 10)]
    rows.append(episode("s10", end=None, status="error"))
    eps = frame(rows)
    table = success_definitions(eps, "end", OPTS).filter(pl.col("task") == "*").row(0, named=True)
    assert (table["end_pct"], table["any_pct"], table["n_episodes"]) == (40.0, 70.0, 10)
    assert table["end_only_any"] == 3
    # one episode per scene: Wilson interval on the chosen rate
    assert (table["ci_low_pct"], table["ci_high_pct"]) == pytest.approx(
        [100 * x for x in wilson_interval(4, 10)]  # type: ignore[union-attr]
    )
    as_any = with_success_definition(eps, "any")
    assert as_any.filter(pl.col("status") == "success").height == 7
    assert as_any.filter(pl.col("status") == "error").height == 1  # errors stay errors
    assert with_success_definition(eps, "end")["status"].to_list() == eps["status"].to_list()
    with pytest.raises(ValueError, match="report.success"):
        with_success_definition(eps, "sometimes")


def test_report_uses_the_chosen_definition_and_keeps_controls_out_of_the_paper_tables():
    rows = [episode(f"s{i}", end=i < 2, any_=i < 3) for i in range(4)]
    rows += [episode(f"s{i}", end=True, kind="control", control="empty") for i in range(4)]
    inputs = StudyInputs(frame(rows))
    end = aggregate(inputs, ReportConfig(success="end", figures=False, html=False))
    anyd = aggregate(inputs, ReportConfig(success="any", figures=False, html=False))
    # controls (all successes) do not enter the headline: 2/4 at the end, 3/4 at any step
    assert end.metrics["success_rate/p"] == 0.5 and anyd.metrics["success_rate/p"] == 0.75
    assert end.metrics["success_rate_any/p"] == 0.75 and anyd.metrics["success_rate_end/p"] == 0.5
    cell = end.cells.filter((pl.col("factor") == "num_objects") & (pl.col("level") == "1")).row(0, named=True)
    assert (cell["successes"], cell["n"]) == (2, 4)
    text = measurement_markdown(end.measurement, {}, 0.95)
    assert text.count("report.success=end") == 3  # every measurement caption names it


# -- clustered intervals ---------------------------------------------------------------

def reference_cluster_bootstrap(k: list[int], n: list[int], samples: int, seed: int) -> tuple[float, float]:
    """Resample scenes with replacement, one bootstrap sample at a time, as a textbook would."""
    rng = np.random.default_rng(seed)
    draws = rng.integers(0, len(k), size=(samples, len(k)))
    rates = []
    for row in draws:
        num = sum(k[i] for i in row)
        den = sum(n[i] for i in row)
        rates.append(num / den)
    return float(np.quantile(rates, 0.025)), float(np.quantile(rates, 0.975))


def test_cluster_bootstrap_matches_a_reference_and_is_wider_than_wilson_when_trials_agree():
    # 8 scenes x 3 trials; trials agree within a scene (5 scenes always succeed, 3 never)
    rows = [episode(f"s{i}", end=i < 5, trial=t) for i in range(8) for t in range(3)]
    eps = frame(rows)
    row = success_definitions(eps, "end", OPTS).filter(pl.col("task") == "*").row(0, named=True)
    assert row["interval"].startswith("cluster bootstrap") and row["trials"] == 3
    k = [3 if i < 5 else 0 for i in range(8)]
    low, high = reference_cluster_bootstrap(k, [3] * 8, OPTS.samples, OPTS.seed)
    assert (row["ci_low_pct"], row["ci_high_pct"]) == pytest.approx((100 * low, 100 * high))
    # Treating the 24 episodes as independent understates the uncertainty of 8 scenes.
    w = wilson_interval(15, 24)
    assert w is not None and (high - low) > (w[1] - w[0])
    # ... while one trial per scene with the same rate gives nearly the same width as 8 scenes' Wilson
    assert cluster_bootstrap_rate(k, [3] * 8, samples=10, seed=1) == cluster_bootstrap_rate(
        k, [3] * 8, samples=10, seed=1
    )


# -- flips across trials -------------------------------------------------------------

def test_flip_counts_per_instruction_and_per_scene():
    rows = []
    for t in range(3):
        rows.append(episode("a", end=True, trial=t))                        # agrees
        rows.append(episode("b", end=t != 1, trial=t))                      # flips
        rows.append(episode("c", end=False, trial=t))                       # agrees
        rows.append(episode("c", end=t == 0, trial=t, kind="paraphrase"))   # flips: scene c flips
    rows.append(episode("d", end=True))                                     # one trial: not counted
    rows.append(episode("e", end=None, status="error", trial=0))
    rows.append(episode("e", end=True, trial=1))                            # one judged trial
    table = trial_agreement(frame(rows)).filter(pl.col("task") == "*").row(0, named=True)
    assert (table["groups"], table["flipping_groups"]) == (4, 2)
    assert (table["scenes"], table["flipping_scenes"]) == (3, 2)
    assert table["agreement_pct"] == 50.0


# -- controls -----------------------------------------------------------------------------

def control_study(trials: int = 1) -> pl.DataFrame:
    """Scene i: the real instruction succeeds for i < 8 of 10; the 'empty' control succeeds on
    scenes 0 and 9 only; 'unrelated' exactly as real (a policy that ignores it)."""
    rows = []
    for t in range(trials):
        for i in range(10):
            rows.append(episode(f"s{i}", end=i < 8, trial=t))
            rows.append(episode(f"s{i}", end=i in (0, 9), trial=t, kind="control", control="empty"))
            rows.append(episode(f"s{i}", end=i < 8, trial=t, kind="control", control="unrelated"))
    return frame(rows)


def test_control_difference_with_one_pair_per_scene():
    table = control_comparison(control_study(), OPTS)
    empty = table.filter(pl.col("control") == "empty").row(0, named=True)
    # pairs: both 1 (scene 0), real only 7 (1..7), control only 1 (9), neither 1 (8)
    assert (empty["real_pct"], empty["control_pct"], empty["diff_pct"]) == (80.0, 20.0, -60.0)
    assert (empty["real_only"], empty["control_only"], empty["n_pairs"]) == (7, 1, 10)
    ref = newcombe_paired(1, 1, 7, 1)  # control - real
    assert ref is not None
    assert (empty["diff_low_pct"], empty["diff_high_pct"]) == pytest.approx((100 * ref.low, 100 * ref.high))
    assert empty["p_value"] == pytest.approx(2 * (1 + 8) / 2**8)  # exact McNemar, 1 vs 7
    unrelated = table.filter(pl.col("control") == "unrelated").row(0, named=True)
    assert unrelated["diff_pct"] == 0.0 and unrelated["p_value"] == 1.0
    pooled = table.filter(pl.col("control") == "all").row(0, named=True)
    assert pooled["n_pairs"] == 20 and pooled["diff_pct"] == -30.0


def test_control_difference_with_trials_uses_scenes_as_clusters():
    table = control_comparison(control_study(trials=2), OPTS)
    empty = table.filter(pl.col("control") == "empty").row(0, named=True)
    assert empty["interval"].startswith("cluster bootstrap") and empty["n_scenes"] == 10
    assert empty["n_pairs"] == 20 and empty["diff_pct"] == -60.0
    assert empty["diff_low_pct"] < -60.0 < empty["diff_high_pct"] <= 0.0
    assert empty["p_value"] is None  # 20 pairs from 10 scenes are not 20 independent pairs
    # power from 10 scenes, not 20 pairs
    assert empty["mdd_pct"] == pytest.approx(100 * mdd_paired(10, 0.8))  # type: ignore[operator]


# -- power ----------------------------------------------------------------------------------

def test_unpaired_mdd_reproduces_a_textbook_sample_size():
    # Fleiss (no continuity correction): 50% vs 30% needs
    # n = (1.96 sqrt(2 * .4 * .6) + 0.8416 sqrt(.25 + .21))^2 / .2^2 = 93.0 per group.
    n = (Z_975 * math.sqrt(2 * 0.4 * 0.6) + Z_80 * math.sqrt(0.5 * 0.5 + 0.3 * 0.7)) ** 2 / 0.2**2
    assert round(n) == 93
    assert mdd_two_proportions(0.5, 93, 93) == pytest.approx(0.2, abs=0.002)
    # a perfect baseline can only drop; 4 episodes per arm cannot show less than ~84 pp
    assert mdd_two_proportions(1.0, 4, 4) == pytest.approx(0.8387, abs=0.001)
    assert mdd_two_proportions(0.5, 1, 1) is None  # nothing is detectable with one episode each


def test_paired_mdd_solves_connors_sample_size_formula():
    for n_pairs, psi in ((100, 0.2), (40, 0.5), (12, 0.0)):
        d = mdd_paired(n_pairs, psi)
        assert d is not None
        psi_used = max(psi, d)  # discordance cannot be below the difference itself
        n_needed = (Z_975 * math.sqrt(psi_used) + Z_80 * math.sqrt(psi_used - d * d)) ** 2 / d**2
        assert n_needed == pytest.approx(n_pairs, rel=1e-4)
    assert mdd_paired(100, 0.2) < mdd_paired(25, 0.2)  # type: ignore[operator]
    assert mdd_paired(3, 0.0) is None


def test_every_comparison_states_its_mdd():
    rows = [episode(f"o{i}-{lv}", end=(i + int(lv)) % 3 != 0, factor="num_objects", level=lv)
            for i in range(6) for lv in ("1", "3")]
    rows += [episode(f"i{i}", end=i < 5, factor="instruction", level="basic") for i in range(8)]
    rows += [episode(f"i{i}", end=i < 3, factor="instruction", level="paraphrase", kind="paraphrase")
             for i in range(8)]
    agg = aggregate(StudyInputs(frame(rows)), ReportConfig(figures=False, html=False))
    paired = agg.comparisons.filter(pl.col("factor") == "instruction").row(0, named=True)
    assert paired["mdd_pct"] == pytest.approx(100 * mdd_paired(8, 2 / 8))  # type: ignore[operator]
    trend = agg.comparisons.filter(pl.col("factor") == "num_objects").row(0, named=True)
    assert trend["mdd_pct"] is not None or mdd_two_proportions(
        trend["baseline_pct"] / 100, trend["n_baseline"], trend["n_level"]
    ) is None


def test_measure_is_deterministic():
    eps = control_study(trials=2)
    a, b = measure(eps, "end", OPTS), measure(eps, "end", OPTS)
    assert a.controls.equals(b.controls) and a.success.equals(b.success)


def test_paper_cells_with_trials_count_each_scene_once_in_their_interval():
    from ladev_lib.report.cells import success_cells

    # level 1: 3 scenes x 4 trials (clustered); level 3: 12 scenes once each; same 9/12 rate
    rows = [episode(f"a{i}", end=i < 2 or t < 1, trial=t) for i in range(3) for t in range(4)]
    rows += [episode(f"b{i}", end=i < 9, level="3") for i in range(12)]
    cells = success_cells(frame(rows)).filter(pl.col("factor") == "num_objects")
    clustered = cells.filter(pl.col("level") == "1").row(0, named=True)
    single = cells.filter(pl.col("level") == "3").row(0, named=True)
    assert clustered["success_rate"] == single["success_rate"] == 0.75 and clustered["n"] == 12
    assert clustered["interval"] == "Wilson over scenes" and single["interval"] == "Wilson"
    # scene means 1, 1, 1/4: Wilson of 2.25 successes in 3 scenes, wider than 9 of 12 episodes
    w3 = wilson_interval(2.25, 3)
    assert (clustered["ci_low"], clustered["ci_high"]) == pytest.approx(w3)
    assert (single["ci_low"], single["ci_high"]) == pytest.approx(wilson_interval(9, 12))
    avg = cells.filter(pl.col("level") == "avg").row(0, named=True)
    assert avg["interval"] == "Wilson over scenes" and avg["n"] == 24
