"""The episode engine: planned episodes in, one table row per episode out.

    rows, summary = run_rollout(plans, store, executor, worker_spec)

Episodes already in the store (by content id) are not run again; the rest go
to the executor, and each outcome is put in the store the moment it arrives
(one committed transaction each), so a run killed at any point loses only the
episodes in flight, and the next run picks up the rest. The table is built
from the store, in plan order, so an interrupted-then-resumed run writes the
same table as an uninterrupted one.

The rows hold outcomes only; where each episode's time went (and on which
machine) goes to ``summary.timings``, which the stage writes to its own table:
the episode table is then the same on every machine and every run.
"""

from __future__ import annotations

import re
import time
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from pydantic import ValidationError

from ladev_lib.rollout.executors.base import Executor
from ladev_lib.rollout.jobs import EpisodeJob, EpisodeOutcome, WorkerSpec
from ladev_lib.rollout.plan import EpisodePlan
from ladev_lib.store import ContentStore
from ladev_lib.tables import EpisodeRow, EpisodeTimingRow


@dataclass
class RolloutSummary:
    """What a rollout did, for the end-of-run message and the exit status."""

    policy: str
    planned: int
    from_store: int
    ran: int
    statuses: Counter[str] = field(default_factory=Counter)
    errors: Counter[str] = field(default_factory=Counter)
    wall_seconds: float = 0.0
    timings: list[EpisodeTimingRow] = field(default_factory=list)
    """One per planned episode, in plan order (the timings table)."""

    @property
    def judged(self) -> int:
        return self.statuses["success"] + self.statuses["failure"]

    @property
    def success_rate(self) -> float | None:
        return self.statuses["success"] / self.judged if self.judged else None

    @property
    def error_rate(self) -> float:
        return self.statuses["error"] / self.planned if self.planned else 0.0

    def format(self) -> str:
        rate = f"{100 * self.success_rate:.1f}%" if self.success_rate is not None else "n/a"
        lines = [
            f"rollout {self.policy}: {self.planned} episodes ({self.ran} run now, "
            f"{self.from_store} from the store) in {self.wall_seconds:.1f} s",
            "  " + ", ".join(f"{k} {self.statuses[k]}" for k in ("success", "failure", "error", "invalid_scene")),
            f"  success rate {rate} of {self.judged} judged episodes; error rate {100 * self.error_rate:.1f}%",
        ]
        for reason, n in self.errors.most_common(5):
            lines.append(f"  error x{n}: {reason}")
        return "\n".join(lines)


def _error_kind(reason: str) -> str:
    """The reason without its episode-specific details (where, step numbers, values)."""
    head = re.sub(r" \(at [^)]*\)$", "", reason)
    head = re.sub(r"\bstep \d+", "step N", head)
    head = re.sub(r" \(\[.*\]\)$", "", head)
    return head if len(head) < 160 else head[:157] + "..."


class _Progress:
    """A tqdm bar with episodes done, success so far and ETA (silent when disabled)."""

    def __init__(self, total: int, initial: int, label: str, enabled: bool) -> None:
        self.counts: Counter[str] = Counter()
        self.bar = None
        if enabled:
            from tqdm import tqdm

            self.bar = tqdm(total=total, initial=initial, desc=f"rollout {label}", unit="ep", dynamic_ncols=True)

    def add(self, outcome: EpisodeOutcome, advance: bool) -> None:
        self.counts[outcome.status] += 1
        if self.bar is None:
            return
        judged = self.counts["success"] + self.counts["failure"]
        rate = f"{100 * self.counts['success'] / judged:.0f}%" if judged else "-"
        self.bar.set_postfix_str(
            f"success {self.counts['success']}/{judged} ({rate}), errors {self.counts['error']}", refresh=False
        )
        if advance:
            self.bar.update(1)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _load_outcome(value: object) -> EpisodeOutcome | None:
    try:
        return EpisodeOutcome.model_validate(value)
    except ValidationError:
        return None  # written by an older schema: run the episode again


def _existing(path: str | None, root: Path | None) -> str | None:
    """Media paths of stored episodes whose files were deleted since are left out."""
    if path is None or root is None:
        return path
    return path if (root / path).exists() else None


def run_rollout(
    plans: Sequence[EpisodePlan],
    store: ContentStore,
    executor: Executor,
    worker_spec: WorkerSpec,
    *,
    label: str,
    progress: bool = True,
    media_base: Path | None = None,
) -> tuple[list[EpisodeRow], RolloutSummary]:
    """Run what is not in the store, and return every planned episode's row, in plan order.

    ``media_base`` is the directory media paths in rows are relative to; when
    given, paths to files that no longer exist are dropped from the rows.
    """
    started = time.perf_counter()
    unique: dict[str, EpisodePlan] = {}
    for p in plans:
        unique.setdefault(p.job.episode_id, p)

    outcomes: dict[str, EpisodeOutcome] = {}
    for key, value in store.get_many(list(unique)).items():
        loaded = _load_outcome(value)
        if loaded is not None:
            outcomes[key] = loaded
    from_store = len(outcomes)
    stored = set(outcomes)
    todo: list[EpisodeJob] = [p.job for eid, p in unique.items() if eid not in outcomes]

    bar = _Progress(len(unique), len(unique) - len(todo), label, progress)
    for o in outcomes.values():
        bar.add(o, advance=False)

    def on_outcome(job: EpisodeJob, outcome: EpisodeOutcome) -> None:
        store.put(job.episode_id, outcome.model_dump(mode="json"))
        outcomes[job.episode_id] = outcome
        bar.add(outcome, advance=True)

    try:
        executor.run(todo, worker_spec, on_outcome)
    finally:
        bar.close()

    rows: list[EpisodeRow] = []
    summary = RolloutSummary(label, len(plans), from_store, len(todo))
    for p in plans:
        o = outcomes[p.job.episode_id]
        summary.statuses[o.status] += 1
        if o.status == "error" and o.error:
            summary.errors[_error_kind(o.error)] += 1
        rows.append(
            EpisodeRow(
                **p.meta,
                robot=o.robot,
                status=o.status,
                success=o.success,
                success_end=o.success,
                success_any=o.success_any,
                first_success_step=o.first_success_step,
                predicates_json=o.predicates_json(),
                steps=o.steps,
                error=o.error,
                video_path=_existing(o.video_path, media_base),
                first_frame_path=_existing(o.first_frame_path, media_base),
                last_frame_path=_existing(o.last_frame_path, media_base),
            )
        )
        summary.timings.append(
            EpisodeTimingRow(
                episode_id=p.job.episode_id,
                policy=label,
                steps=o.steps,
                from_store=p.job.episode_id in stored,
                sim_seconds=o.sim_seconds,
                policy_seconds=o.policy_seconds,
                total_seconds=o.total_seconds,
                host=o.host,
            )
        )
    summary.wall_seconds = time.perf_counter() - started
    return rows, summary
