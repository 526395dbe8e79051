"""The rollout stage as a function: configuration in, ``episodes/<policy>.parquet`` out.

    result = rollout_stage(cfg, "oracle", root=Path("."))
    print(result.summary.format()); sys.exit(result.exit_code)

``cfg`` is the composed configuration (``params.yaml``); every path in it is
relative to ``root``. The per-policy outputs are the table
``paths.episodes_dir/<label>.parquet``, its timings
``paths.timings_dir/<label>.parquet`` (kept apart: they differ on every run),
media under ``paths.media_dir/<label>/`` and the persistent store
``paths.episode_store_dir/<label>/``. ``study.trials_per_scene`` and
``study.trial_factors`` say how many times each scene runs.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ladev_lib.config import section
from ladev_lib.errors import ConfigError
from ladev_lib.policies import POLICIES
from ladev_lib.policies.base import Policy
from ladev_lib.policies.config import PolicyConfig
from ladev_lib.rollout.config import RolloutConfig, executor_config
from ladev_lib.rollout.engine import RolloutSummary, run_rollout
from ladev_lib.rollout.executors import make_executor
from ladev_lib.rollout.identity import code_fingerprint
from ladev_lib.rollout.jobs import MediaOptions, WorkerSpec
from ladev_lib.rollout.plan import PolicyIdentity, TrialPlan, plan_episodes
from ladev_lib.rollout.simulator import EpisodeSim, SimSetup
from ladev_lib.sim.config import RobotConfig, SimConfig
from ladev_lib.store import ContentStore
from ladev_lib.tables import (
    CompiledSceneRow,
    EpisodeRow,
    EpisodeTimingRow,
    InstructionRow,
    SceneDesignRow,
    read_table,
    write_table,
)


@dataclass(frozen=True)
class RolloutStageResult:
    summary: RolloutSummary
    table: Path
    max_error_rate: float
    timings: Path | None = None

    @property
    def exit_code(self) -> int:
        """Non-zero only when more episodes ended in error than the configuration tolerates."""
        return 1 if self.summary.error_rate > self.max_error_rate else 0


def keep_only_this_studys_media(media_dir: Path, archive: Path, rows: Sequence[EpisodeRow]) -> None:
    """Make the stage's media folder hold exactly the files its episode rows name.

    Media of stored episodes outlive the study that made them (a study that shrinks and
    grows back reuses its episodes, pictures included), but the DVC output must not carry
    files of episodes no longer planned: they would make the output's hash depend on the
    history of runs. Files no row names move to ``archive`` (beside the episode store);
    files a row names that lie in the archive move back.
    """
    named = {
        Path(p).name for r in rows for p in (r.first_frame_path, r.last_frame_path, r.video_path) if p
    }
    for name in named:
        kept = archive / name
        if not (media_dir / name).exists() and kept.exists():
            kept.replace(media_dir / name)
    for f in media_dir.iterdir():
        if f.is_file() and not f.name.startswith(".") and f.name not in named:
            archive.mkdir(parents=True, exist_ok=True)
            f.replace(archive / f.name)


def policy_config(cfg: dict[str, Any], label: str) -> PolicyConfig:
    """``cfg["policy"][label]``, validated; an unknown label lists the configured ones."""
    policies = cfg.get("policy") or {}
    if label not in policies:
        known = ", ".join(sorted(policies)) or "(none)"
        raise ConfigError(
            f"policy {label!r} is not configured (policy section has: {known}); "
            f"add conf/policy/{label}.yaml or pass policy=[...,{label}]"
        )
    return section(policies, label, PolicyConfig)


def _path(cfg: dict[str, Any], key: str, root: Path) -> Path:
    paths = cfg.get("paths") or {}
    if key not in paths:
        raise ConfigError(f"paths.{key} is not set in the configuration")
    return root / str(paths[key])


def trial_plan(cfg: dict[str, Any], rollout: RolloutConfig) -> TrialPlan:
    """Trials from the ``study`` section (1 per scene when it says nothing)."""
    study = cfg.get("study") or {}
    trials = study.get("trials_per_scene", 1)
    factors = study.get("trial_factors")
    if not isinstance(trials, int) or isinstance(trials, bool) or trials < 1:
        raise ConfigError(f"study.trials_per_scene: a whole number >= 1, got {trials!r}")
    if factors is not None and not isinstance(factors, list):
        raise ConfigError(f"study.trial_factors: a list of factors or null, got {factors!r}")
    return TrialPlan(
        trials_per_scene=trials,
        trial_factors=tuple(str(f) for f in factors) if factors is not None else None,
        stop_on_success=rollout.stop_on_success,
    )


def rollout_stage(
    cfg: dict[str, Any],
    label: str,
    *,
    root: Path,
    progress: bool = True,
    sim_factory: Callable[[SimSetup], EpisodeSim] | None = None,
    policy_factory: Callable[..., Policy] | None = None,
) -> RolloutStageResult:
    """Plan, run (what the store lacks) and write the episodes of policy ``label``."""
    pc = policy_config(cfg, label)
    if policy_factory is None:
        POLICIES.get(pc.name)  # fail fast: unknown name, or the extra to install
    rollout = section(cfg, "rollout", RolloutConfig)
    executor_cfg = executor_config(cfg)
    sim_config = section(cfg, "sim", SimConfig).model_dump(mode="json")
    robot_config = section(cfg, "robot", RobotConfig).model_dump(mode="json")
    study = str((cfg.get("study") or {}).get("name") or "study")

    compiled = read_table(_path(cfg, "compiled", root), CompiledSceneRow)
    instructions_path = _path(cfg, "instructions", root)
    instructions = read_table(instructions_path, InstructionRow) if instructions_path.exists() else None
    scenes_path = _path(cfg, "scenes", root)
    scenes = read_table(scenes_path, SceneDesignRow) if scenes_path.exists() else None

    module = policy_factory.__module__ if policy_factory is not None else POLICIES.module_of(pc.name)
    code = code_fingerprint(module)
    identity = PolicyIdentity(label=label, name=pc.name, config=pc.identity, code=code)
    plans = plan_episodes(
        compiled,
        instructions,
        scenes,
        study=study,
        policy=identity,
        sim_config=sim_config,
        robot_config=robot_config,
        trials=trial_plan(cfg, rollout),
    )

    media_rel = Path(str((cfg.get("paths") or {}).get("media_dir", "data/media"))) / label
    media = MediaOptions(
        root=str((root / media_rel).resolve()),
        prefix=media_rel.as_posix(),
        video=rollout.video,
        frames=rollout.frames,
        fps=rollout.video_fps,
    )
    # The stage's media output exists even when every episode comes from the store.
    Path(media.root).mkdir(parents=True, exist_ok=True)
    worker_spec = WorkerSpec(
        policy_name=pc.name,
        policy_config=pc.kwargs,
        sim_config=sim_config,
        robot_config=robot_config,
        media=media,
        step_timeout_s=rollout.step_timeout_s,
        setup_timeout_s=rollout.setup_timeout_s,
        sim_factory=sim_factory,
        policy_factory=policy_factory,
        robot_by_task={str(task): str(robot) for task, robot in pc.robot_by_task.items()},
    )
    store = ContentStore(_path(cfg, "episode_store_dir", root) / label)
    executor = make_executor(executor_cfg, rollout, policy_module=module, code_fingerprint=code)
    try:
        rows, summary = run_rollout(
            plans, store, executor, worker_spec, label=label, progress=progress, media_base=root
        )
    finally:
        store.close()
    table = write_table(rows, _path(cfg, "episodes_dir", root) / f"{label}.parquet", EpisodeRow)
    keep_only_this_studys_media(
        Path(media.root), _path(cfg, "episode_store_dir", root) / label / "media", rows
    )
    timings = None
    if "timings_dir" in (cfg.get("paths") or {}):
        timings = write_table(
            summary.timings, _path(cfg, "timings_dir", root) / f"{label}.parquet", EpisodeTimingRow
        )
    return RolloutStageResult(summary, table, rollout.max_error_rate, timings)
