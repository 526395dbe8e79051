"""How far the study's numbers can be trusted: success definitions, trials, controls, power.

    episodes = with_success_definition(episodes, "any")   # status/success from success_any
    real, controls = split_controls(episodes)
    m = measure(episodes, cfg)                             # frames for the measurement tables

- **Success definitions.** Each episode records success at its final step
  (``success_end``) and at any step (``success_any``); ``report.success``
  picks the one every table uses, and :func:`success_definitions` shows both.
- **Trials.** A scene's episodes (its trials, its paired instructions) are
  not independent. Rates get a cluster-bootstrap interval that resamples
  scenes whole; :func:`trial_agreement` counts the (scene, instruction)
  groups whose trials disagree ("flip").
- **Controls.** Control instructions (empty, unrelated, other object) run on
  the same scenes and trials as the basic instruction; :func:`control_comparison`
  pairs them (same policy, scene, trial) and gives control − real with its
  interval: a policy that follows language succeeds less under the control.
- **Power.** Every comparison carries the minimum detectable difference at
  its n (``report.mdd_power``, ``report.mdd_alpha``), so "no difference" can
  be told from "too few scenes".
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

import polars as pl

from ladev_lib.report.cells import JUDGED
from ladev_lib.report.stats import (
    cluster_bootstrap_mean,
    cluster_bootstrap_rate,
    mcnemar_exact,
    mdd_paired,
    newcombe_paired,
    wilson_interval,
)

SuccessDefinition = Literal["end", "any"]
DEFINITION_TEXT: dict[str, str] = {
    "end": "success at the final step",
    "any": "success at any step",
}
ALL_TASKS = "*"


def success_caption(definition: str) -> str:
    """The words every table caption carries about the success definition."""
    return f"Success = {DEFINITION_TEXT[definition]} (report.success={definition})."


def with_success_definition(episodes: pl.DataFrame, definition: str) -> pl.DataFrame:
    """Episodes whose ``status``/``success`` follow ``definition`` for judged episodes.

    ``end`` keeps them as recorded; ``any`` takes ``success_any``. Errors and
    invalid scenes stay as they are. Rows without the column's value (an older
    table) fall back to the recorded ``success``.
    """
    if definition not in DEFINITION_TEXT:
        raise ValueError(f"report.success: {definition!r}; known: {', '.join(DEFINITION_TEXT)}")
    column = "success_end" if definition == "end" else "success_any"
    judged = pl.col("status").is_in(list(JUDGED))
    ok = pl.coalesce(pl.col(column), pl.col("success"))
    return episodes.with_columns(
        status=pl.when(judged)
        .then(pl.when(ok).then(pl.lit("success")).otherwise(pl.lit("failure")))
        .otherwise(pl.col("status")),
        success=pl.when(judged).then(ok).otherwise(pl.lit(None, dtype=pl.Boolean)),
    )


def split_controls(episodes: pl.DataFrame) -> tuple[pl.DataFrame, pl.DataFrame]:
    """(episodes with real instructions, control episodes)."""
    is_control = pl.col("instruction_kind") == "control"
    return episodes.filter(~is_control), episodes.filter(is_control)


def _judged(episodes: pl.DataFrame) -> pl.DataFrame:
    return episodes.filter(pl.col("status").is_in(list(JUDGED)))


def _per_task(frame: pl.DataFrame) -> list[tuple[str, pl.DataFrame]]:
    """("*", all rows) then one entry per task present."""
    out = [(ALL_TASKS, frame)]
    for task in sorted(frame.get_column("task").unique().to_list()):
        out.append((task, frame.filter(pl.col("task") == task)))
    return out


@dataclass(frozen=True)
class BootstrapOptions:
    confidence: float = 0.95
    samples: int = 2000
    seed: int = 0


def rate_interval(
    judged: pl.DataFrame, ok_column: str, opts: BootstrapOptions
) -> tuple[float | None, float | None, str]:
    """Interval of the success rate of judged episodes: Wilson when every scene has one
    episode, else a cluster bootstrap over scenes."""
    if judged.is_empty():
        return None, None, "-"
    per_scene = judged.group_by("scene_id").agg(
        k=pl.col(ok_column).cast(pl.Int64).sum(), n=pl.len()
    ).sort("scene_id")
    if per_scene.get_column("n").max() == 1:
        w = wilson_interval(int(per_scene["k"].sum()), per_scene.height, opts.confidence)
        assert w is not None
        return w[0], w[1], "Wilson"
    ci = cluster_bootstrap_rate(
        per_scene["k"].to_list(), per_scene["n"].to_list(), opts.confidence, opts.samples, opts.seed
    )
    assert ci is not None
    return ci[0], ci[1], "cluster bootstrap (scenes)"


def success_definitions(
    episodes: pl.DataFrame, definition: str, opts: BootstrapOptions
) -> pl.DataFrame:
    """Per policy and task (and all tasks): the rate at the end and at any step, and the
    interval of the one ``definition`` picks. Real instructions only."""
    real, _ = split_controls(episodes)
    judged = _judged(real).with_columns(
        end=pl.coalesce(pl.col("success_end"), pl.col("success")),
        any=pl.coalesce(pl.col("success_any"), pl.col("success")),
    )
    rows: list[dict[str, Any]] = []
    for policy in sorted(judged.get_column("policy").unique().to_list()):
        for task, sub in _per_task(judged.filter(pl.col("policy") == policy)):
            n = sub.height
            low, high, method = rate_interval(sub, definition, opts)
            rows.append(
                dict(
                    policy=policy, task=task, n_scenes=sub["scene_id"].n_unique(), n_episodes=n,
                    trials=sub["trial"].n_unique() if n else 0,
                    end_pct=100.0 * int(sub["end"].sum()) / n if n else None,
                    any_pct=100.0 * int(sub["any"].sum()) / n if n else None,
                    definition=definition,
                    ci_low_pct=None if low is None else 100.0 * low,
                    ci_high_pct=None if high is None else 100.0 * high,
                    interval=method,
                    end_only_any=int((sub["any"] & ~sub["end"]).sum()),
                )
            )
    return pl.DataFrame(rows, schema=SUCCESS_SCHEMA)


SUCCESS_SCHEMA: dict[str, Any] = {
    "policy": pl.String, "task": pl.String, "n_scenes": pl.Int64, "n_episodes": pl.Int64,
    "trials": pl.Int64, "end_pct": pl.Float64, "any_pct": pl.Float64, "definition": pl.String,
    "ci_low_pct": pl.Float64, "ci_high_pct": pl.Float64, "interval": pl.String,
    "end_only_any": pl.Int64,
}
"""``end_only_any``: episodes that succeeded at some step but not at the end."""


def trial_agreement(episodes: pl.DataFrame) -> pl.DataFrame:
    """Per policy and task: (scene, instruction) groups run more than once, and how many of
    them flip (some trials succeed, others fail). ``status`` must already follow the report's
    success definition. Real and control instructions both count."""
    judged = _judged(episodes).with_columns(ok=pl.col("status") == "success")
    groups = (
        judged.group_by(["policy", "task", "scene_id", "instruction_id"])
        .agg(trials=pl.len(), successes=pl.col("ok").sum())
        .filter(pl.col("trials") > 1)
        .with_columns(flip=(pl.col("successes") > 0) & (pl.col("successes") < pl.col("trials")))
    )
    rows: list[dict[str, Any]] = []
    for policy in sorted(groups.get_column("policy").unique().to_list()):
        for task, sub in _per_task(groups.filter(pl.col("policy") == policy)):
            scene_flips = sub.group_by("scene_id").agg(pl.col("flip").any())
            rows.append(
                dict(
                    policy=policy, task=task, groups=sub.height,
                    flipping_groups=int(sub["flip"].sum()),
                    scenes=scene_flips.height, flipping_scenes=int(scene_flips["flip"].sum()),
                    agreement_pct=100.0 * (1 - int(sub["flip"].sum()) / sub.height) if sub.height else None,
                )
            )
    return pl.DataFrame(rows, schema=AGREEMENT_SCHEMA)


AGREEMENT_SCHEMA: dict[str, Any] = {
    "policy": pl.String, "task": pl.String, "groups": pl.Int64, "flipping_groups": pl.Int64,
    "scenes": pl.Int64, "flipping_scenes": pl.Int64, "agreement_pct": pl.Float64,
}


def control_pairs(episodes: pl.DataFrame) -> pl.DataFrame:
    """Judged (basic instruction, control) pairs of the same policy, scene and trial.

    Columns: policy, task, scene_id, trial, control, real_ok, control_ok.
    ``status`` must already follow the report's success definition.
    """
    judged = _judged(episodes).with_columns(ok=pl.col("status") == "success")
    keys = ["policy", "task", "scene_id", "trial"]
    real = judged.filter(pl.col("instruction_kind") == "basic").select([*keys, pl.col("ok").alias("real_ok")])
    ctrl = judged.filter(pl.col("instruction_kind") == "control").select(
        [*keys, "control", pl.col("ok").alias("control_ok")]
    )
    return real.join(ctrl, on=keys, how="inner").sort([*keys, "control"])


def control_comparison(
    episodes: pl.DataFrame, opts: BootstrapOptions, alpha: float = 0.05, power: float = 0.8
) -> pl.DataFrame:
    """Per policy and control (and every control pooled, ``control`` "all"): success under the
    real (basic) instruction and under the control on the same scenes and trials, the paired
    difference control − real with its interval (Newcombe's paired interval with one pair per
    scene; a cluster bootstrap over scenes with more), McNemar's exact p (one pair per scene
    only) and the minimum detectable difference."""
    pairs = control_pairs(episodes)
    rows: list[dict[str, Any]] = []
    for policy in sorted(pairs.get_column("policy").unique().to_list()):
        mine = pairs.filter(pl.col("policy") == policy)
        kinds = sorted(mine.get_column("control").unique().to_list())
        for kind in [*kinds, "all"]:
            sub = mine if kind == "all" else mine.filter(pl.col("control") == kind)
            rows.append(_control_row(policy, kind, sub, opts, alpha, power))
    return pl.DataFrame(rows, schema=CONTROL_SCHEMA)


def _control_row(
    policy: str, kind: str, sub: pl.DataFrame, opts: BootstrapOptions, alpha: float, power: float
) -> dict[str, Any]:
    a = int((sub["real_ok"] & sub["control_ok"]).sum())
    real_only = int((sub["real_ok"] & ~sub["control_ok"]).sum())
    control_only = int((~sub["real_ok"] & sub["control_ok"]).sum())
    d = sub.height - a - real_only - control_only
    n = sub.height
    scenes = sub["scene_id"].n_unique()
    per_scene = (
        sub.with_columns(diff=pl.col("control_ok").cast(pl.Int64) - pl.col("real_ok").cast(pl.Int64))
        .group_by("scene_id").agg(diff=pl.col("diff").sum(), n=pl.len()).sort("scene_id")
    )
    p_value: float | None = None
    if per_scene.get_column("n").max() == 1:
        diff = newcombe_paired(a, control_only, real_only, d, opts.confidence)  # control - real
        assert diff is not None
        low, high, method = diff.low, diff.high, "Newcombe paired"
        p_value = mcnemar_exact(real_only, control_only)
    else:
        # McNemar's test would take a scene's trials and controls for independent pairs: no p.
        ci = cluster_bootstrap_mean(
            per_scene["diff"].to_list(), per_scene["n"].to_list(), opts.confidence, opts.samples, opts.seed
        )
        assert ci is not None
        low, high, method = ci[0], ci[1], "cluster bootstrap (scenes)"
    # Pairs of one scene are not independent: power from the scenes, conservatively.
    mdd = mdd_paired(scenes, (real_only + control_only) / n, alpha, power)
    return dict(
        policy=policy, control=kind, n_pairs=n, n_scenes=scenes,
        real_pct=100.0 * (a + real_only) / n, control_pct=100.0 * (a + control_only) / n,
        diff_pct=100.0 * (control_only - real_only) / n, diff_low_pct=100.0 * low,
        diff_high_pct=100.0 * high, interval=method, p_value=p_value,
        real_only=real_only, control_only=control_only,
        mdd_pct=None if mdd is None else 100.0 * mdd,
    )


CONTROL_SCHEMA: dict[str, Any] = {
    "policy": pl.String, "control": pl.String, "n_pairs": pl.Int64, "n_scenes": pl.Int64,
    "real_pct": pl.Float64, "control_pct": pl.Float64, "diff_pct": pl.Float64,
    "diff_low_pct": pl.Float64, "diff_high_pct": pl.Float64, "interval": pl.String,
    "p_value": pl.Float64, "real_only": pl.Int64, "control_only": pl.Int64, "mdd_pct": pl.Float64,
}


@dataclass(frozen=True)
class Measurement:
    definition: str
    success: pl.DataFrame
    agreement: pl.DataFrame
    controls: pl.DataFrame


def measure(
    episodes: pl.DataFrame,
    definition: str,
    opts: BootstrapOptions,
    alpha: float = 0.05,
    power: float = 0.8,
) -> Measurement:
    """Every measurement table from the study's episodes (all kinds, as recorded)."""
    judged_as = with_success_definition(episodes, definition)
    return Measurement(
        definition=definition,
        success=success_definitions(episodes, definition, opts),
        agreement=trial_agreement(judged_as),
        controls=control_comparison(judged_as, opts, alpha, power),
    )


# -- text --------------------------------------------------------------------------

@dataclass(frozen=True)
class TextTable:
    """A measurement table as text: caption, header, rows (for Markdown and HTML)."""

    title: str
    caption: str
    header: tuple[str, ...]
    rows: list[tuple[str, ...]]
    right: int
    """Columns from this index on are numbers (right-aligned)."""


def _f(x: float | None, decimals: int = 1) -> str:
    return "–" if x is None else f"{x:.{decimals}f}"


def measurement_tables(m: Measurement, labels: dict[str, str], confidence: float) -> list[TextTable]:
    """The three measurement tables, each caption naming the success definition."""
    conf = round(100 * confidence)
    cap = success_caption(m.definition)

    def label(policy: str) -> str:
        return labels.get(policy, policy)

    success = TextTable(
        "Success at the final step and at any step",
        f"{cap} Interval ({conf}%) of the rate the report uses: Wilson when each scene has one "
        "episode, else a cluster bootstrap over scenes. Real instructions only (controls below); "
        "'any, not end': episodes that succeeded at some step but not at the last.",
        ("Model", "Task", "Method", "Scenes", "Episodes", "Trials", "End", "Any", "Interval", "Any, not end"),
        [
            (label(r["policy"]), r["task"], r["interval"], str(r["n_scenes"]), str(r["n_episodes"]),
             str(r["trials"]), f"{_f(r['end_pct'])}%", f"{_f(r['any_pct'])}%",
             f"{_f(r['ci_low_pct'])}–{_f(r['ci_high_pct'])}%", str(r["end_only_any"]))
            for r in m.success.iter_rows(named=True)
        ],
        3,
    )
    agreement = TextTable(
        "Agreement across trials",
        f"{cap} A (scene, instruction) run more than once flips when some of its trials succeed "
        "and others fail; a scene flips when any of its instructions does.",
        ("Model", "Task", "Groups", "Flipping groups", "Scenes", "Flipping scenes", "Agreement"),
        [
            (label(r["policy"]), r["task"], str(r["groups"]), str(r["flipping_groups"]), str(r["scenes"]),
             str(r["flipping_scenes"]), f"{_f(r['agreement_pct'])}%")
            for r in m.agreement.iter_rows(named=True)
        ],
        2,
    )
    controls = TextTable(
        "Control instructions",
        f"{cap} The same scenes and trials under the basic instruction (real) and under a control; "
        f"difference control − real in percentage points with its {conf}% interval, McNemar's exact "
        "p (one pair per scene only; with more, the pairs are not independent and the cluster "
        "interval stands alone), and the minimum detectable difference (MDD: 80% power, 5% level, "
        "from the number of scenes). A policy that follows language drops under the controls.",
        ("Model", "Control", "Method", "Pairs", "Scenes", "Real", "Control", "Diff (pp)", "Interval",
         "p", "MDD (pp)"),
        [
            (label(r["policy"]), r["control"], r["interval"], str(r["n_pairs"]), str(r["n_scenes"]),
             f"{_f(r['real_pct'])}%", f"{_f(r['control_pct'])}%", _f(r["diff_pct"]),
             f"{_f(r['diff_low_pct'])} to {_f(r['diff_high_pct'])}", _f(r["p_value"], 3),
             _f(r["mdd_pct"]) if r["mdd_pct"] is not None else "> 100")
            for r in m.controls.iter_rows(named=True)
        ],
        3,
    )
    return [success, agreement, controls]


def measurement_markdown(m: Measurement, labels: dict[str, str], confidence: float) -> str:
    """The measurement tables as Markdown."""
    lines: list[str] = []
    for t in measurement_tables(m, labels, confidence):
        lines += [f"**{t.title}.** {t.caption}", ""]
        lines.append("| " + " | ".join(t.header) + " |")
        lines.append("|" + "---|" * t.right + "---:|" * (len(t.header) - t.right))
        for row in t.rows or [("–",) * len(t.header)]:
            lines.append("| " + " | ".join(c.replace("|", r"\|") for c in row) + " |")
        lines.append("")
    return "\n".join(lines)
