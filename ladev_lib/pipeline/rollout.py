"""Stage ``rollout``: every planned episode of one policy -> ``paths.episodes_dir/<policy>.parquet``.

Reads ``policy.<label>``, ``sim``, ``robot``, ``executor``, ``rollout``,
``study.name``, ``study.trials_per_scene``, ``study.trial_factors`` and ``paths``. The work (plan, run what the episode store
lacks, write the table) is :func:`ladev_lib.rollout.stage.rollout_stage`; this
module is the stage's entry point and says what to print.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ladev_lib.pipeline import StageMessages
from ladev_lib.policies.base import Policy
from ladev_lib.rollout.engine import RolloutSummary
from ladev_lib.rollout.simulator import EpisodeSim, SimSetup
from ladev_lib.rollout.stage import rollout_stage


@dataclass(frozen=True)
class RolloutResult:
    table: Path
    timings: Path | None
    """Where the episodes' timings went (outside the DVC-cached outcomes), if written."""
    summary: RolloutSummary
    max_error_rate: float
    exit_code: int
    """Non-zero only when more episodes ended in error than ``rollout.max_error_rate`` allows."""

    def messages(self) -> StageMessages:
        err: tuple[str, ...] = ()
        if self.exit_code:
            err = (
                f"rollout: error rate {100 * self.summary.error_rate:.1f}% is above the configured "
                f"{100 * self.max_error_rate:.1f}% (rollout.max_error_rate)",
            )
        wrote = f"rollout: wrote {self.table}" + (f" and {self.timings}" if self.timings else "")
        return StageMessages((self.summary.format(), wrote), err, self.exit_code)


def run_rollout(
    params: dict[str, Any],
    label: str,
    *,
    root: Path | None = None,
    progress: bool = True,
    sim_factory: Callable[[SimSetup], EpisodeSim] | None = None,
    policy_factory: Callable[..., Policy] | None = None,
) -> RolloutResult:
    """Run (what the store lacks) and write the episodes of policy ``label``; paths relative to ``root`` (cwd)."""
    done = rollout_stage(
        params, label, root=root if root is not None else Path.cwd(), progress=progress,
        sim_factory=sim_factory, policy_factory=policy_factory,
    )
    return RolloutResult(done.table, done.timings, done.summary, done.max_error_rate, done.exit_code)
