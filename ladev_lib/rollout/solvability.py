"""Is a scene solvable? Run the privileged oracle on it, through the one episode loop.

    result = check_solvable(spec)                      # builds a state-only simulator
    result.solved, result.reason, result.predicates

    for result in check_scenes(specs):                 # one simulator reused for all
        ...

LADEV proves generated scenes solvable this way: a scene the oracle solves is
known to be physically possible for the Panda; one it fails is reported with
the reason (no grasp fits, nothing reachable, the object slipped, the final
predicates that are false), never dropped silently. The check is an episode
like any other (:func:`ladev_lib.rollout.episode.run_episode`, the oracle as
the policy), so it judges success exactly as a study does.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from ladev_lib.policies.oracle import OraclePolicy
from ladev_lib.rollout.episode import run_episode
from ladev_lib.rollout.jobs import EpisodeJob
from ladev_lib.rollout.simulator import ManiSkillSim, SimSetup
from ladev_lib.scenes.spec import SceneSpec
from ladev_lib.sim.config import SimConfig

SOLVABILITY_VERSION: Literal[1] = 1


class SolvabilityResult(BaseModel):
    """The oracle's verdict on one scene."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    schema_version: Literal[1] = SOLVABILITY_VERSION
    scene_id: str | None = None
    task: str
    status: Literal["solved", "failed", "error"]
    """solved: the task's success predicate holds at the end; failed: it does not (or
    the scene is physically invalid); error: the check itself crashed (``reason`` has
    the exception)."""
    reason: str = Field(default="", description="Why it failed; empty when solved.")
    predicates: dict[str, bool] = Field(default_factory=dict, description="Final task predicates.")
    steps: int = 0
    seconds: float = 0.0
    attempts: int = Field(default=0, description="Grasp attempts the oracle made.")
    object_sources: dict[str, str] = Field(
        default_factory=dict, description="Object name -> 'mesh' or 'standin', as built."
    )

    @property
    def solved(self) -> bool:
        return self.status == "solved"


def solvability_sim(sim_config: SimConfig | None = None, *, prefer_meshes: bool = True) -> ManiSkillSim:
    """A state-only Panda simulator for the oracle (no camera: nothing is rendered).

    ``prefer_meshes=False`` builds stand-ins even where ``MS_ASSET_DIR`` has meshes.
    """
    cfg = sim_config or SimConfig()
    return ManiSkillSim(
        SimSetup(
            sim_config=cfg.model_dump(mode="json"),
            robot_config={},
            robot="panda",
            control_mode=OraclePolicy.info.control_mode,
            image_size=None,
            prefer_meshes=prefer_meshes,
        )
    )


def check_solvable(
    spec: SceneSpec,
    sim_config: SimConfig | None = None,
    *,
    sim: ManiSkillSim | None = None,
    policy: OraclePolicy | None = None,
) -> SolvabilityResult:
    """Run the oracle on ``spec`` and judge the final state with the task's predicates.

    ``sim`` (from :func:`solvability_sim`) is reused when given; otherwise one is made
    and closed here.
    """
    own = sim is None
    sim = sim or solvability_sim(sim_config)
    oracle = policy or OraclePolicy()
    try:
        job = EpisodeJob(
            episode_id=f"solvability-{spec.scene_id or 'scene'}",
            spec=spec,
            instruction="",
            seed=spec.seed,
        )
        outcome = run_episode(sim, oracle, job)
        predicates = dict(outcome.predicates)
        success = predicates.pop("success", False)
        skill = oracle.outcome
        if outcome.status == "error":
            status: Literal["solved", "failed", "error"] = "error"
            reason = outcome.error or "error"
        elif success:
            status, reason = "solved", ""
        else:
            status = "failed"
            why = f"invalid scene: {outcome.error}" if outcome.status == "invalid_scene" else ""
            why = why or (skill.reason if skill is not None and skill.reason else "")
            limit = oracle.info.episode_steps_for(spec.task.type)
            if not why and limit is not None and outcome.steps >= limit:
                why = f"ran out of steps ({limit})"
            false = [k for k, v in predicates.items() if not v]
            reason = "; ".join(p for p in (why or "", f"false: {', '.join(false)}" if false else "") if p)
        sources = getattr(sim.env.unwrapped, "object_sources", {}) if sim._env is not None else {}
        return SolvabilityResult(
            scene_id=spec.scene_id,
            task=spec.task.type,
            status=status,
            reason=reason,
            predicates=predicates,
            steps=outcome.steps,
            seconds=outcome.total_seconds,
            attempts=skill.attempts if skill is not None else 0,
            object_sources={n: str(s) for n, s in sources.items()},
        )
    finally:
        if own:
            sim.close()


def check_scenes(
    specs: Iterable[SceneSpec],
    sim_config: SimConfig | None = None,
    *,
    prefer_meshes: bool = True,
) -> Iterator[SolvabilityResult]:
    """Check many scenes with one simulator; a scene whose check crashes becomes an ``error`` row."""
    sim = solvability_sim(sim_config, prefer_meshes=prefer_meshes)
    try:
        for spec in specs:
            try:
                yield check_solvable(spec, sim_config, sim=sim)
            except Exception as exc:  # a crash is data here: report it, keep checking the rest
                yield SolvabilityResult(
                    scene_id=spec.scene_id,
                    task=spec.task.type,
                    status="error",
                    reason=f"{type(exc).__name__}: {exc}",
                )
    finally:
        sim.close()
